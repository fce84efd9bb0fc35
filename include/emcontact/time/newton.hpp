#pragma once
// Newton on the full residual of eq. 20, reduced by the elimination (docs/THEORY.md §1.6, §3):
//   (P^T A P + D) dq = -P^T g,  u_{n+1} += P dq,
// converged when ||P^T g|| <= max(rtol ||P^T g_0||, atol, 100 eps ||scale||), where scale
// bounds the round-off of g's four terms and of the iterate's own rounding and g_0 is the
// solve's start iterate or, for a re-solve of the active-set loop started from the last
// solution, the largest start residual of the step's solves if that is larger; the start
// iterate itself only at the round-off floor (atol applies to Newton's own iterates). No step is
// ever accepted unconverged (a search solve of the active-set loop, docs/THEORY.md §6.9, stops
// earlier, but the step's last solve is a full one).
#include <functional>
#include <string>
#include <vector>

#include "emcontact/fem/discretization.hpp"
#include "emcontact/linalg/elimination.hpp"
#include "emcontact/linalg/linear_solver.hpp"
#include "emcontact/time/settings.hpp"

namespace emc::time {

/// docs/THEORY.md §1.6: the sizes at a step's start (u_{n+1} = u_n) that the tolerances are
/// checked against before the first step.
struct StartScales {
  double scale = 0;  ///< ||scale||: the size of the residual's terms
  /// per owned dof, the inertia of a rigid translation (2/dt^2) sum_j M_ij over the Newton
  /// matrix's diagonal A_ii = (2/dt^2) M_ii + K_ii (0 where A_ii is not > 0)
  Teuchos::RCP<Vector> inertia_share;
};

struct NewtonResult {
  bool converged = false;
  int iterations = 0;             ///< linear solves done
  int linear_iterations = 0;      ///< Krylov iterations summed
  std::vector<double> residuals;  ///< ||P^T g|| per iterate
  double floor = 0;               ///< the round-off floor (or atol) at the last iterate
  int matrices = 0;               ///< Newton matrices assembled
  int extra_assemblies = 0;       ///< matrices assembled after a wrong prediction of convergence
  std::string failure;            ///< why it did not converge
};

class Newton {
 public:
  Newton(const fem::Discretization& disc, linalg::Elimination& elim, linalg::LinearSolver& solver,
         NewtonOptions opt);

  /// Solves eq. 20 for u1 given (u0, V0) at t_n; u1 holds the start guess on entry.
  /// reference > 0: the relative tolerance applies to the larger of it and this solve's first
  /// residual (a re-solve of the step started from the last solution, docs/THEORY.md
  /// §6.1-§6.2), and the start iterate is accepted if it meets that tolerance already.
  /// rtol > 0 replaces the relative tolerance (a search solve, docs/THEORY.md §6.9).
  /// iterate: the start iterate is accepted only if it is a solution to round-off (a re-solve
  /// after a contact entry changed its state, whose new equations the start iterate's residual
  /// at the old tolerance cannot see: docs/THEORY.md §11.4).
  NewtonResult solve(const Vector& u0, const Vector& V0, double dt, Vector& u1,
                     double reference = 0, double rtol = 0, bool iterate = false);

  /// The sizes of the step of dt from (u0, V0) before any iterate (StartScales).
  StartScales start_scales(const Vector& u0, const Vector& V0, double dt);

  /// Constraints that change inside Newton (contact); null: only the fixed elimination.
  void set_hooks(linalg::ConstraintHooks* h) { hooks_ = h; }
  /// The linear solver (the stepper drops its preconditioner when P changes).
  linalg::LinearSolver& solver() { return solver_; }
  /// r_1 / r_0^2 of the last solve from a step's start iterate with two iterates: the first
  /// linear tolerance of the next solve derives from it (part of the state: a restart must
  /// restore it to be bitwise).
  double contraction() const { return contraction_; }
  void set_contraction(double c) { contraction_ = c; }
  /// The result of the last solve (residual history).
  const NewtonResult& last() const { return last_; }
  /// The contactless residual g of eq. 20 at the last iterate (contact forces, §4).
  const Vector& last_residual() const { return *g_; }
  const fem::Discretization& disc() const { return disc_; }
  const NewtonOptions& options() const { return opt_; }

 private:
  NewtonResult iterate(const Vector& u0, const Vector& V0, double dt, Vector& u1, double reference,
                       double rtol, bool once);
  double linear_tolerance(const std::vector<double>& r, double floor) const;
  /// C r_k^2 with C = r_k / r_{k-1}^2 (or the last step's); < 0 when there is no estimate.
  double predicted_next(const std::vector<double>& r) const;

  const fem::Discretization& disc_;
  linalg::Elimination& elim_;
  linalg::LinearSolver& solver_;
  NewtonOptions opt_;
  Teuchos::RCP<FEMatrix> A_;  ///< built once on the FE graph, refilled every iteration
  Teuchos::RCP<Vector> g_;
  Teuchos::RCP<Vector> X_;  ///< reference positions, if the solver builds from positions
  NewtonResult last_;
  double contraction_ = 0;  ///< r_1 / r_0^2 of the last solve that had two iterates
  linalg::ConstraintHooks* hooks_ = nullptr;
};

}  // namespace emc::time
