#pragma once
// The active-set loop of a step (docs/THEORY.md §6): solve with a trial set, activate the slave
// nodes that entered a facet (§6.3), release those in tension or off their master (§6.4), and
// solve again until the set is settled; then accept (§6.5). The time stepper only asks "solve
// this step" and reads what was settled.
#include <functional>
#include <string>
#include <vector>

#include "emcontact/contact/constraints.hpp"
#include "emcontact/contact/contact.hpp"

namespace emc::contact {

/// What a settled step leaves for t_{n+1}.
struct SettledSet {
  std::vector<Active> active;        ///< my entries that stay active (§6.5)
  std::vector<double> normal_force;  ///< their f_N at the accepted solve
  /// Every entry of mine active at the accepted solve (the monitors' active_contacts), with its
  /// f_N and whether it stays active (1) or is released at the end of the step (2).
  std::vector<int> nodes, status;
  std::vector<double> force;
  std::vector<int> slip;  ///< per entry of `nodes`: 1 sliding (Coulomb, docs/THEORY.md §11)
  double dissipated = 0;  ///< the energy friction dissipated over the step (global)
  StepContactStats stats;
  ClosureWork closure;  ///< docs/THEORY.md §7.4 (with `close gap` pairs)
};

class ActiveSetLoop {
 public:
  ActiveSetLoop(const Contact& contact, linalg::Elimination& elim, std::vector<GO> fixed);

  /// Newton's hooks for the constraints of the trial set.
  linalg::ConstraintHooks* hooks() { return &constraints_; }

  /// One Newton solve of the step with the trial set applied (P rebuilt if `changed`; `empty`:
  /// no rank has an active entry). `warm`: u1 holds the last converged solve of the step, the
  /// start iterate (docs/THEORY.md §6.1-§6.2); else u1 is reset to the step's start iterate.
  /// `search`: the solve only searches the set (docs/THEORY.md §6.9), to a looser tolerance.
  /// `restated`: the last solve's return map changed an entry's state (stick <-> slip): a warm
  /// solve then takes at least one Newton iterate (docs/THEORY.md §11.4).
  /// Returns the contactless residual at the solution, or null if Newton failed.
  using Solve =
      std::function<const Vector*(bool changed, bool empty, bool warm, bool search, bool restated)>;

  /// docs/THEORY.md §6.9: the solves search the set to a looser tolerance and the settled set
  /// is solved to the full one and checked again (the Solve honours `search`; needs warm).
  void set_search(bool on) { search_ = on; }

  /// docs/THEORY.md §7.2, the closure's fallback: my slaves `slaves` keep their gap (no
  /// closure work) in the solves that follow, until clear_kept. Collective: returns how many
  /// slaves this added on all ranks.
  int keep_gaps(const std::vector<int>& slaves);
  void clear_kept() { kept_.clear(); }

  /// §6: the step from u0 with the set `active` at t_n; u1 holds a prediction of u_{n+1} on
  /// entry (the reach of the contact nodes) and the solution on return. p (or null): the
  /// closure's impulse direction (docs/THEORY.md §7.4). False if a solve failed.
  bool solve(const Vector& u0, Vector& u1, const std::vector<Active>& active, const Solve& solve,
             SettledSet& out, Vector* p);

 private:
  const Contact& contact_;
  ActiveConstraints constraints_;
  bool search_ = false;
  std::vector<int> kept_;  ///< slaves whose gap the closure's fallback keeps (sorted)

  bool kept(int slave) const;
  void accept(Positions x0, Positions x1, const Vector& g, std::vector<Active>& trial,
              const std::vector<double>& fN, SettledSet& out, Vector* p);
};

}  // namespace emc::contact
