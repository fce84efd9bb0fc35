#pragma once
// MUMPS (Debian's MPI build, called through its C interface) as the direct solver on 1 and N
// ranks: the matrix goes in distributed (each rank its own rows, ICNTL(18) = 3), the right-hand
// side and the solution are gathered on rank 0 (ICNTL(20) = ICNTL(21) = 0). The analysis
// (ordering, symbolic factorisation) is kept while the matrix structure stays the same; the
// numeric factorisation is redone on request only, and the factors of an earlier matrix
// can serve as a preconditioner (as_operator).
#include <memory>

#include "emcontact/types.hpp"

namespace emc::linalg {

class DirectMumps {
 public:
  explicit DirectMumps(const Teuchos::RCP<const Comm>& comm);
  ~DirectMumps();
  DirectMumps(const DirectMumps&) = delete;
  DirectMumps& operator=(const DirectMumps&) = delete;

  /// Numeric factorisation of A, after a new analysis if A's structure differs from the one
  /// analysed last (the same graph object, or equal row pointers and global columns on every
  /// rank). The rows of A must be numbered 0..N-1 (in any distribution). Throws
  /// LinearSolveError on a MUMPS error (INFOG codes and their meaning).
  void factor(const Teuchos::RCP<const Matrix>& A);
  /// x = (LU)^-1 b with the last factors (collective).
  void solve(const Vector& b, Vector& x);
  /// The current factors as a Tpetra operator ((LU)^-1), e.g. a preconditioner of a later
  /// matrix; it refers to this object and is valid while this object lives.
  Teuchos::RCP<Operator> as_operator();
  bool factored() const;

  int analyses() const { return analyses_; }
  int factorisations() const { return factorisations_; }

 private:
  struct State;
  std::shared_ptr<State> s_;
  int analyses_ = 0, factorisations_ = 0;

  bool same_structure(const Teuchos::RCP<const Matrix>& A);
  void analyse(const Teuchos::RCP<const Matrix>& A);
  void run(int job);
};

}  // namespace emc::linalg
