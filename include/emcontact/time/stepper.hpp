#pragma once
// Time stepping with the energy-momentum (or mid-point) scheme (docs/THEORY.md §1.4, eq. 19):
// V_{n+1} = 2 (u_{n+1} - u_n)/dt - V_n, with the active-set loop of contact (§6) around
// Newton. A step whose Newton fails is retried with dt/2 (up to `max step cuts` times); dt
// doubles back toward the nominal dt after `grow after` good steps.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "emcontact/contact/active_set.hpp"
#include "emcontact/contact/contact.hpp"
#include "emcontact/time/newton.hpp"
#include "emcontact/time/restoration.hpp"

namespace emc::time {

/// Everything that defines the solution at t_n.
struct State {
  Teuchos::RCP<Vector> u, V;  ///< owned displacement and velocity
  double t = 0;
  long step = 0;
  double dt = 0;       ///< current step size (may be below the nominal one after cuts)
  int good_steps = 0;  ///< accepted steps since the last change of dt
  std::vector<contact::Active> active;  ///< my active slave nodes at t_n (§6.1)
  std::vector<double> normal_force;     ///< their f_N at the accepted step (§4)
  /// Every node of mine active at the accepted solve of the last step (the monitors'
  /// active_contacts), with its f_N and whether it stays active (1) or is released at the end
  /// of the step (2: pinned in tension, or off its master; §6.4-§6.5).
  std::vector<int> contact_nodes, contact_status;
  std::vector<double> contact_force;
  std::vector<int> contact_slip;  ///< per contact_nodes: 1 sliding (Coulomb, docs/THEORY.md §11)
  double dissipated = 0;          ///< energy dissipated by friction since t = 0 (§11.2)
  Teuchos::RCP<Vector> last_increment;  ///< u_n - u_{n-1}, for the predictor (null at start)
  double last_h = 0;                    ///< the step size of that increment
  int last_iterations = 0;              ///< Newton iterations of the last accepted solve
  double newton_contraction = 0;        ///< Newton's r_1 / r_0^2 estimate (Newton::contraction)
};

struct StepReport {
  double dt = 0;
  int newton_iterations = 0;
  int linear_iterations = 0;
  int cuts = 0;
  int closure_fallbacks = 0;  ///< solves repeated closing less (docs/THEORY.md §7.2)
  double closure_energy = 0;  ///< energy given back by the velocity update (docs/THEORY.md §7.4)
  double dissipated = 0;      ///< energy friction dissipated in the step (docs/THEORY.md §11.2)
  std::string last_failure;
  contact::StepContactStats contact;
};

struct SettleReport {
  int steps = 0;              ///< settling steps taken
  int newton_iterations = 0;  ///< over all of them
  double change = 0;          ///< max |u_{k+1} - u_k| / max |u| of the last one
  double kinetic = 0;         ///< the kinetic energy it gave, over the elastic energy
  double largest_h = 0;       ///< the largest step size used
  bool steady = false;        ///< settled up to a steady free motion (the same change per dt)
  bool converged = false;     ///< at rest (kinetic <= tolerance) or steady
  bool moved_away = false;    ///< stopped: a body moved farther than the bodies' extent
};

class Stepper {
 public:
  /// `steps`: the time loop's settings; `fixed` the owned Dirichlet dofs; `contact` may be
  /// null (no contact pairs).
  Stepper(const StepOptions& steps, Newton& newton, linalg::Elimination& elim,
          std::vector<GO> fixed, contact::Contact* contact, State& state);

  bool finished() const;
  /// Advances to the next accepted step. Throws RunError if dt cannot be cut any further.
  StepReport advance();
  /// Brings the state at t = 0 to rest in static equilibrium under the loads (docs/THEORY.md
  /// §6.7): steps from V = 0, each followed by u = (u_k + u_{k+1}) / 2 and V = 0, with a step
  /// size that grows from dt while the active set holds. The input's initial velocity is put
  /// back at the end; t, the step count and the dissipated energy stay 0.
  SettleReport settle(const SettleOptions& o);
  /// Before the first step (docs/THEORY.md §1.6): throws InputError naming `file` and the
  /// parameter if a body's inertia (2/dt^2) M is below the round-off of its stiffness in the
  /// Newton matrix (its motion would be lost: `Bodies/<body>/Material/density`), or if
  /// `Solver/Newton/absolute tolerance` is not below the size of the residual's terms (it would
  /// accept any iterate).
  void check_start(const std::string& file);
  double nominal_dt() const { return dt_; }
  double end() const { return end_; }

 private:
  Newton& newton_;
  linalg::Elimination& elim_;
  std::vector<GO> fixed_;
  contact::Contact* contact_;
  State& s_;
  double dt_, end_;
  int max_cuts_, grow_after_;
  int last_set_iterations_ = 0;  ///< Newton iterations of the accepted set (search + final)
  std::unique_ptr<contact::ActiveSetLoop> loop_;    ///< with contact pairs only
  std::unique_ptr<EnergyRestoration> restoration_;  ///< with `close gap` pairs only
  Teuchos::RCP<Vector> closure_p_;                  ///< the step's impulse direction (§7.4)
  contact::ClosureWork closure_work_;               ///< the step's contact work W_c (§7.4)
  double dissipated_ = 0;                           ///< the solved step's friction work (§11)
  std::string crossing_;  ///< the run's last step cut for a crossing, for a later failure's message

  void start_iterate(double h, bool no_contact, Vector& u1) const;
  void check_step_size(double h) const;
  bool solve_step(double h, Vector& u1, StepReport& rep);
  bool crossed_too_deep(const Vector& u0, const Vector& u1, double h,
                        const std::vector<int>& active, StepReport& rep) const;
  bool restore_energy(Vector& V1, StepReport& rep);
};

}  // namespace emc::time
