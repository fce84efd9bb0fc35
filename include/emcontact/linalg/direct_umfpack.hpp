#pragma once
// SuiteSparse UMFPACK (Debian's libsuitesparse-dev) as the direct solver on one rank: the
// multifrontal LU of a general sparse matrix, with its symbolic analysis (column ordering,
// frontal structure) kept while the matrix structure stays the same. Its triangular solves
// cost a third to a half of MUMPS's on the examples' systems of 2-6k unknowns
// (perf/README.md, "Sparse direct solvers"), which is what GMRES on reused factors repeats.
#include <memory>

#include "emcontact/linalg/direct_solver.hpp"

namespace emc::linalg {

class DirectUmfpack : public DirectSolver {
 public:
  /// Throws InputError on more than one rank (UMFPACK is sequential).
  explicit DirectUmfpack(const Teuchos::RCP<const Comm>& comm);
  ~DirectUmfpack() override;

  /// The same structure: the same graph object, or equal row pointers and global columns.
  /// Errors: UMFPACK's status code and its meaning (a singular matrix is one).
  void factor(const Teuchos::RCP<const Matrix>& A) override;
  void solve(const Vector& b, Vector& x) override;
  bool factored() const override;
  const char* name() const override { return "UMFPACK"; }

 private:
  struct State;
  std::unique_ptr<State> s_;

  bool same_structure(const Matrix& A) const;
  void analyse(const Teuchos::RCP<const Matrix>& A);
};

}  // namespace emc::linalg
