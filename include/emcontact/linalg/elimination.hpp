#pragma once
// Direct elimination as a transformation (docs/THEORY.md §3): du = P dq, the reduced Newton
// system (P^T A P + D) dq = -P^T g keeps the number of equations fixed. A fixed (Dirichlet)
// dof has a zero column in P and a dummy row 1 * dq = 0 (D = 1 there); later, contact slaves
// add rows of P that tie them to their master facet, with D = beta on their dummies.
#include <Kokkos_Core.hpp>
#include <Teuchos_RCP.hpp>
#include <vector>

#include "emcontact/linalg/masked_reduction.hpp"
#include "emcontact/linalg/structured_reduction.hpp"
#include "emcontact/types.hpp"

namespace emc::linalg {

/// What constraints do inside Newton (implemented by contact): set the iterate-dependent
/// parts of the elimination before the reduction, and restore the nonlinear constraints after
/// the update u += P dq (docs/THEORY.md §3.4, §5.3 update steps 2-3).
class ConstraintHooks {
 public:
  virtual ~ConstraintHooks() = default;
  /// Before the first residual: the start iterate u1 may be projected.
  virtual void start(const Vector& u0, Vector& u1) = 0;
  /// After assembly of A and g at the iterate u1, before P^T g and P^T A Pt + X + D.
  /// g may be changed: forces the constraints add (Coulomb friction, docs/THEORY.md §11) are
  /// subtracted from it, so that P^T g is the reduced residual.
  virtual void before_reduce(const Vector& u0, const Vector& u1, Vector& g, const Matrix& A) = 0;
  /// After u1 += P dq.
  virtual void after_update(const Vector& u0, Vector& u1) = 0;
  /// This rank's share (a sum of squares) of the reduced residual that restoring the constraints
  /// leaves at every iterate (the projection's round-off; Newton's floor, docs/THEORY.md §1.6).
  virtual double residual_roundoff() const { return 0; }
  /// Whether the solve is to be given up at this (unconverged) iterate with residual r (r0 at
  /// the start): a constraint state it assumed cannot hold (Coulomb slip with no sliding
  /// solution, docs/THEORY.md §11.4). Collective.
  virtual bool abandon(int /*iteration*/, double /*r*/, double /*r0*/) { return false; }
};

class Elimination {
 public:
  explicit Elimination(Teuchos::RCP<const Map> owned);

  /// Sets P and D. P's graph is rebuilt only when the constrained dofs or the columns of a
  /// special row change; otherwise the special rows' values are rewritten in place.
  /// `fixed`: owned dofs with prescribed zero increment; `rows`: owned dofs whose increment is
  /// a combination of other dofs; `dummy_diag`: (owned dof, D value) for dummy unknowns.
  void set_constraints(const std::vector<GO>& fixed, const std::vector<PRow>& rows,
                       const std::vector<std::pair<GO, double>>& dummy_diag);

  /// Replaces the values of D (fixed dofs keep 1); P is unchanged. For the beta of eq. 44,
  /// which follows the Newton matrix while the active set, hence P, stays the same.
  void set_dummy_values(const std::vector<std::pair<GO, double>>& dummy_diag);
  /// The dummies of the set just given to set_constraints: owned dofs, a slave's three in a
  /// row, whose D set_dummy_betas writes (D = 0 there until then).
  void set_dummies(const std::vector<GO>& dummies);
  /// D = beta(k) on the three dummies of slave k (set_dummies), the rest of D unchanged
  /// (docs/THEORY.md §3.2): beta follows A at every Newton iterate, so on the masked path it
  /// is one kernel on D's vector, with no host pass.
  void set_dummy_betas(Kokkos::View<const double*, ExecSpace> beta);

  /// The exact linearisation of frictionless contact (§5): the right factor Pt (rows that differ
  /// from P; empty: Pt = P) and the variation X of P^T. Reset by set_constraints.
  /// pl_rows (Coulomb friction, docs/THEORY.md §11.3): rows of the left factor that differ from
  /// P's (the same columns): the reduction is then Pl^T A Pt + X + D.
  void set_linearisation(const std::vector<PRow>& pt_rows, const std::vector<Entry>& X,
                         const std::vector<PRow>& pl_rows = {});

  /// True when P is the identity on every rank (nothing constrained): reduce/expand copy.
  bool identity() const { return identity_; }
  /// P as a matrix: null when P is a 0/1 diagonal (masked: applied as the keep vector).
  Teuchos::RCP<const Matrix> P() const { return P_; }
  /// Times the structured path (P^T A Pt + X + D) built its pattern: once per active set.
  int pattern_builds() const { return structured_reduction_.builds(); }
  /// Keep the reduced matrix's graph across active sets while it has their entries (for a
  /// direct solver: its analysis is kept; docs/THEORY.md §3.6).
  void keep_graph(bool on) { structured_reduction_.keep_graph(on); }
  /// Drops the kept graph (at a checkpoint, so that a restart continues bit for bit).
  void forget_graph() { structured_reduction_.forget(); }
  /// Times the reduced matrix's graph was built, for tests.
  int graph_builds() const { return structured_reduction_.graph_builds(); }
  /// Times P's graph was built (set_constraints with a new pattern), for tests.
  int p_builds() const { return p_builds_; }

  /// P^T A Pt + X + D (Pt = P and X = 0 unless set_linearisation was called). Off the masked
  /// path, the returned matrix is refilled by the next call while the pattern holds.
  Teuchos::RCP<Matrix> reduce_matrix(const Teuchos::RCP<Matrix>& A) const;
  /// R = P^T g.
  void reduce_residual(const Vector& g, Vector& R) const;
  /// How reduce_residual forms P^T g (docs/THEORY.md §9): true, through P^T formed as a matrix
  /// once per change of P; false, through Tpetra's transposed apply. By default true on
  /// threaded backends only (where the transposed apply sums with atomics); tests set both.
  void form_transpose(bool on) { form_transpose_ = on; }
  /// du = P dq.
  void expand(const Vector& dq, Vector& du) const;

 private:
  Teuchos::RCP<const Map> owned_;
  Teuchos::RCP<Matrix> P_;
  /// P^T as a matrix of its own (with form_transpose_; null until reduce_residual needs it
  /// after P changed): on threaded backends Tpetra's transposed apply sums a column with
  /// atomics, in an order that varies from run to run; a product with P^T's rows sums each in a
  /// fixed order.
  mutable Teuchos::RCP<Matrix> PT_;
  bool form_transpose_ = ExecSpace().concurrency() > 1;
  Teuchos::RCP<const Vector> keep_;          ///< 1 where P's row is e_i, 0 on fixed and slave rows
  std::vector<std::pair<GO, double>> diag_;  ///< D's entries (owned dofs)
  Teuchos::RCP<Vector> d_;                   ///< D as a vector (masked path)
  std::vector<LO> d_lids_;                   ///< the rows of d_ that may be non-zero
  std::vector<GO> dummies_;                  ///< set_dummies' dofs
  Kokkos::View<LO*, ExecSpace> dummy_rows_;  ///< their rows of d_ (masked path)
  std::vector<GO> fixed_;
  std::vector<PRow> rows_, pt_rows_;  ///< P's special rows; Pt's that differ
  std::vector<PRow> left_rows_;       ///< the left factor's special rows (P's unless Pl is set)
  std::vector<Entry> X_;
  bool linearised_ = false;  ///< set_linearisation was called (on some rank)
  std::vector<GO> p_key_;    ///< the fixed dofs and the special rows' columns P's graph has
  int p_builds_ = 0;
  bool built_ = false;  ///< P (or, masked, its keep vector) was built for p_key_
  bool identity_ = true;
  bool masked_ = false;  ///< P is diagonal (0/1) on every rank: MaskedReduction, no products
  mutable MaskedReduction masked_reduction_;
  mutable StructuredReduction structured_reduction_;
};

}  // namespace emc::linalg
