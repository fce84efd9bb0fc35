#pragma once
// MUMPS (Debian's MPI build, called through its C interface) as the direct solver on 1 and N
// ranks: the matrix goes in distributed (each rank its own rows, ICNTL(18) = 3), the right-hand
// side and the solution are gathered on rank 0 (ICNTL(20) = ICNTL(21) = 0). The analysis
// (ordering, symbolic factorisation) is kept while the matrix structure stays the same; the
// numeric factorisation is redone on request only, and the factors of an earlier matrix
// can serve as a preconditioner (as_operator).
#include <memory>

#include "emcontact/linalg/direct_solver.hpp"

namespace emc::linalg {

class DirectMumps : public DirectSolver {
 public:
  explicit DirectMumps(const Teuchos::RCP<const Comm>& comm);
  ~DirectMumps() override;

  /// The same structure: the same graph object, or equal row pointers and global columns on
  /// every rank (in any distribution of the rows). Errors: INFOG codes and their meaning.
  void factor(const Teuchos::RCP<const Matrix>& A) override;
  void solve(const Vector& b, Vector& x) override;
  bool factored() const override;
  const char* name() const override { return "MUMPS"; }

 private:
  struct State;
  std::shared_ptr<State> s_;

  bool same_structure(const Teuchos::RCP<const Matrix>& A);
  void analyse(const Teuchos::RCP<const Matrix>& A);
  void run(int job);
};

}  // namespace emc::linalg
