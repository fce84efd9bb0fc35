#include "emcontact/contact/active_set.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_TimeMonitor.hpp>
#include <algorithm>
#include <limits>
#include <set>

#include "emcontact/contact/law.hpp"

namespace emc::contact {

ActiveSetLoop::ActiveSetLoop(const Contact& contact, linalg::Elimination& elim,
                             std::vector<GO> fixed)
    : contact_(contact), constraints_(contact, elim, std::move(fixed)) {}

// docs/THEORY.md §6, one step.
bool ActiveSetLoop::solve(const Vector& u0, Vector& u1, const std::vector<Active>& active,
                          const Solve& solve, SettledSet& out, Vector* p) {
  std::vector<Active> trial = active;
  for (auto& a : trial) {  // docs/THEORY.md §11.4: per step
    a.returns = 0;
    a.slid = a.slip;
    if (kept(a.slave)) a.keep_gap = true;  // §7.2, the closure's fallback
  }
  std::set<int> released, pinned;
  out.stats = StepContactStats{};
  std::vector<double> fN;
  const Vector* g = nullptr;
  Positions x0, x1;
  int x0_nodes = -1;  // the contact nodes x0 holds: u0 is the step's, x0 changes with them only
  const auto at_u0 = [&] {
    if (contact_.nodes().builds() == x0_nodes) return;
    x0 = contact_.positions(u0);
    x0_nodes = contact_.nodes().builds();
  };
  // docs/THEORY.md §8: the step's sweeps start at u0; `swept`: u1 is the one of the last
  // selection, whose facets in reach then stand (only the chains of the new set are closed)
  const auto sweep = contact_.sweep_from(u0);
  bool swept = false;
  bool warm = false;      // §6.1-§6.2: a re-solve starts from the last solution
  bool search = search_;  // §6.9: search the set, then solve it to the full tolerance
  bool restated = false;  // §11.4: the last return map changed an entry's state
  for (;;) {
    // docs/THEORY.md §8: the contact nodes within reach of the step (u1: the prediction or the
    // last solution) and of the trial set's chains
    ActiveIndex index = contact_.gather(trial);
    if (swept)
      contact_.reselect(index);
    else
      contact_.select(sweep, u1, index);
    at_u0();
    constraints_.set_start_positions(x0);
    const bool empty = contact_.global_count(static_cast<int>(trial.size())) == 0;
    bool changed;
    {
      static auto timer = Teuchos::TimeMonitor::getNewTimer("emcontact: contact: new P");
      Teuchos::TimeMonitor tm(*timer);  // the rows of P of a new set (§3)
      changed = constraints_.use(&trial, std::move(index));
    }
    g = solve(changed, empty, warm, search, restated);
    constraints_.sync(trial);  // the facets and xi Newton's iterates moved (§5)
    swept = false;             // u1 moved
    warm = g != nullptr;
    if (!g) {
      // docs/THEORY.md §11.4: sliding entries whose slip turned back had no sliding solution:
      // they stick, and the step is solved again
      u1.assign(u0);
      contact_.select(sweep, u1, constraints_.index());
      swept = true;
      at_u0();
      const LawState s{contact_, constraints_.index(), x0, x0, {}, nullptr, &constraints_.state()};
      int back = 0;
      for (const Law* law : contact_.laws()) back += law->after_failure(s, trial);
      if (contact_.global_count(back) == 0) return false;
      ++out.stats.resolves;
      continue;
    }
    contact_.select(sweep, u1, constraints_.index());  // the exact sweep of the solution
    swept = true;
    at_u0();
    x1 = contact_.positions(u1);
    auto fresh = contact_.detect(x0, x1, trial);
    fN = contact_.normal_forces(*g, x0, x1, trial);
    set_normal_forces(constraints_.state(), fN);
    int n_state = 0;  // docs/THEORY.md §11.4: the return map (stick <-> slip)
    {
      const LawState s{
          contact_, constraints_.index(), x0, x1, {}, constraints_.matrix(), &constraints_.state()};
      for (const Law* law : contact_.laws()) {
        n_state += law->settle(s, trial, *g);
        law->activate(s, fresh, *g);
      }
    }
    std::vector<Active> next;
    int n_release = 0;
    for (std::size_t k = 0; k < trial.size(); ++k) {
      const int s = trial[k].slave;
      // §6.4: tensile (or, frictionless, off its master by more than tol_f) -> release
      if (contact_.law(trial[k].pair).releases(trial[k], fN[k]) && !pinned.count(s)) {
        released.insert(s);
        ++n_release;
      } else {
        next.push_back(trial[k]);
      }
    }
    for (auto a : fresh) {
      if (kept(a.slave)) a.keep_gap = true;  // §7.2, the closure's fallback
      if (released.count(a.slave)) {         // released in this step and penetrating again: keep it
        pinned.insert(a.slave);
        ++out.stats.reactivated;
      }
      next.push_back(a);
    }
    const int changes = contact_.global_count(static_cast<int>(fresh.size()) + n_release + n_state);
    restated = contact_.global_count(n_state) > 0;
    if (changes == 0 && !search) break;
    if (changes == 0) {  // §6.9: settled at the search tolerance; now solve it to the full one
      search = false;
      continue;
    }
    std::sort(next.begin(), next.end());
    trial = std::move(next);
    ++out.stats.resolves;
  }
  accept(x0, x1, *g, trial, fN, out, p);  // the contact nodes of the last detection
  return true;
}

int ActiveSetLoop::keep_gaps(const std::vector<int>& slaves) {
  int added = 0;
  for (int s : slaves)
    if (!kept(s)) {
      kept_.insert(std::lower_bound(kept_.begin(), kept_.end(), s), s);
      ++added;
    }
  return contact_.global_count(added);
}

bool ActiveSetLoop::kept(int slave) const {
  return std::binary_search(kept_.begin(), kept_.end(), slave);
}

// §6.5: accept; nodes still in tension (only pinned ones can be) leave for the next step.
void ActiveSetLoop::accept(Positions x0, Positions x1, const Vector& g, std::vector<Active>& trial,
                           const std::vector<double>& fN, SettledSet& out, Vector* p) {
  out.active.clear();
  out.normal_force.clear();
  out.nodes.clear();
  out.status.clear();
  out.slip.clear();
  out.force.assign(fN.begin(), fN.end());
  for (std::size_t k = 0; k < trial.size(); ++k) {
    const bool stays = !contact_.law(trial[k].pair).releases(trial[k], fN[k]);
    out.nodes.push_back(trial[k].slave);
    out.status.push_back(stays ? 1 : 2);
    if (stays) {
      out.active.push_back(trial[k]);
      out.normal_force.push_back(fN[k]);
    }
  }
  {  // docs/THEORY.md §11.2: the energy friction dissipated over the step
    const LawState s{contact_, constraints_.index(), x0, x1, {}, nullptr, &constraints_.state()};
    double d = 0;
    for (const Law* law : contact_.laws()) d += law->dissipation(s, trial, g);
    Teuchos::reduceAll(*contact_.disc_comm(), Teuchos::REDUCE_SUM, 1, &d, &out.dissipated);
    double cone = constraints_.state().cone;  // §11.4: how far a sticking Coulomb entry is
                                              // outside its cone
    Teuchos::reduceAll(*contact_.disc_comm(), Teuchos::REDUCE_MAX, 1, &cone, &out.stats.cone_ratio);
  }
  for (const auto& a : trial) out.slip.push_back(a.slip ? 1 : 0);
  if (p) {  // docs/THEORY.md §7.4: the work the closure made the contact forces do
    out.closure = contact_.closure_work(g, x0, x1, trial, *p);
    contact_.mark_kept_gaps(out.active, x1);
  }
  out.stats.active = contact_.global_count(static_cast<int>(trial.size()));
  out.stats.reactivated = contact_.global_count(out.stats.reactivated);
  contact_.gap_range(x1, trial, out.stats.gap_min, out.stats.gap_max);
  // §6.5: the smallest f_N (> 0 compressive, < 0 tensile) of every node active at the accepted
  // solve, those released at the end of the step included; 0 when none is active
  double fmin = std::numeric_limits<double>::infinity(), gmin = fmin;
  for (double f : fN) fmin = std::min(fmin, f);
  Teuchos::reduceAll(*contact_.disc_comm(), Teuchos::REDUCE_MIN, 1, &fmin, &gmin);
  out.stats.normal_force_min = out.stats.active > 0 ? gmin : 0.0;
}

}  // namespace emc::contact
