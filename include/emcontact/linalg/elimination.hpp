#pragma once
// Direct elimination as a transformation (ALGORITHM.md §3): du = P dq, the reduced Newton
// system (P^T A P + D) dq = -P^T g keeps the number of equations fixed. A fixed (Dirichlet)
// dof has a zero column in P and a dummy row 1 * dq = 0 (D = 1 there); later, contact slaves
// add rows of P that tie them to their master facet, with D = beta on their dummies.
#include <Teuchos_RCP.hpp>

#include <vector>

#include "emcontact/types.hpp"

namespace emc::linalg {

/// One row block of P: owned dof `row` gets du_row = sum_k weight_k dq_{col_k}.
struct PRow {
  GO row;
  std::vector<GO> cols;
  std::vector<double> weights;
};

class Elimination {
 public:
  explicit Elimination(Teuchos::RCP<const Map> owned);

  /// Rebuilds P and D (call when the constrained set changes, not every Newton iteration).
  /// `fixed`: owned dofs with prescribed zero increment; `rows`: owned dofs whose increment is
  /// a combination of other dofs; `dummy_diag`: (owned dof, D value) for dummy unknowns.
  void set_constraints(const std::vector<GO>& fixed, const std::vector<PRow>& rows,
                       const std::vector<std::pair<GO, double>>& dummy_diag);

  /// Replaces the values of D (fixed dofs keep 1); P is unchanged. For the beta of eq. 44,
  /// which follows the Newton matrix while the active set, hence P, stays the same.
  void set_dummy_values(const std::vector<std::pair<GO, double>>& dummy_diag);

  /// True when P is the identity on every rank (nothing constrained): reduce/expand copy.
  bool identity() const { return identity_; }
  Teuchos::RCP<const Matrix> P() const { return P_; }

  /// P^T A P + D.
  Teuchos::RCP<Matrix> reduce_matrix(const Teuchos::RCP<Matrix>& A) const;
  /// R = P^T g.
  void reduce_residual(const Vector& g, Vector& R) const;
  /// du = P dq.
  void expand(const Vector& dq, Vector& du) const;

 private:
  Teuchos::RCP<const Map> owned_;
  Teuchos::RCP<Matrix> P_, D_;
  std::vector<GO> fixed_;
  bool identity_ = true;
};

}  // namespace emc::linalg
