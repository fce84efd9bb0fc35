#pragma once
// A sparse direct solver that keeps its analysis while the matrix structure stays the same and
// its numeric factors until asked to factor anew, so that the factors of an earlier matrix can
// serve as a preconditioner (as_operator). Behind it: MUMPS (any number of ranks) and UMFPACK
// (one rank); LinearSolver decides when to factor (src/linalg/direct_solve.cpp).
#include "emcontact/types.hpp"

namespace emc::linalg {

class DirectSolver {
 public:
  DirectSolver() = default;
  virtual ~DirectSolver() = default;
  DirectSolver(const DirectSolver&) = delete;  // it owns the package's factors
  DirectSolver& operator=(const DirectSolver&) = delete;

  /// Numeric factorisation of A, after a new analysis if A's structure differs from the one
  /// analysed last. The rows of A must be numbered 0..N-1. Throws LinearSolveError on a
  /// failure of the package (its code and what it means).
  virtual void factor(const Teuchos::RCP<const Matrix>& A) = 0;
  /// x = (LU)^-1 b with the last factors (collective).
  virtual void solve(const Vector& b, Vector& x) = 0;
  virtual bool factored() const = 0;
  /// The package's name ("MUMPS", "UMFPACK").
  virtual const char* name() const = 0;

  /// The current factors as a Tpetra operator ((LU)^-1), e.g. a preconditioner of a later
  /// matrix; it refers to this object and is valid while this object lives.
  Teuchos::RCP<Operator> as_operator();

  int analyses() const { return analyses_; }
  int factorisations() const { return factorisations_; }

 protected:
  Teuchos::RCP<const Map> rows_;  ///< the row map of the matrix analysed last
  int analyses_ = 0, factorisations_ = 0;
};

/// GMRES right-preconditioned by the factors M (at most `cap` iterations, from x = 0), then at
/// most two corrections solved the same way for the true residual b - A x: Belos tests the
/// residual GMRES updates, which drifts from the true one when M's solves are inexact (factors
/// of an earlier matrix, or UMFPACK's diagonal-preferring pivots on the ill-conditioned hollow
/// cylinders: "converged" with a true residual of 3e-7 against 1e-10). GMRES that used up its
/// cap unconverged is corrected only if `refine_unconverged` (fresh factors; reused ones are
/// factored anew instead); one that stopped before the cap (its test met on the residual it
/// updates) is corrected within what is left of the cap. Returns the GMRES iterations;
/// `true_residual`: ||b - A x|| / ||b|| at the end (||b - A x|| if b = 0), or -1 if
/// unconverged GMRES was not corrected.
int gmres_on_factors(const Teuchos::RCP<Matrix>& A, const Teuchos::RCP<Operator>& M,
                     const Vector& b, Vector& x, double tol, int cap, bool refine_unconverged,
                     bool& converged, double& true_residual);

}  // namespace emc::linalg
