#include "emcontact/time/stepper.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "emcontact/error.hpp"
#include "emcontact/format.hpp"
#include "emcontact/time/timers.hpp"

namespace emc::time {

Stepper::Stepper(const StepOptions& steps, Newton& newton, linalg::Elimination& elim,
                 std::vector<GO> fixed, contact::Contact* contact, State& state)
    : newton_(newton),
      elim_(elim),
      fixed_(std::move(fixed)),
      contact_(contact && !contact->empty() ? contact : nullptr),
      s_(state),
      dt_(steps.dt),
      end_(steps.end),
      max_cuts_(steps.max_cuts),
      grow_after_(steps.grow_after) {
  if (s_.dt <= 0) s_.dt = dt_;
  if (contact_) {
    loop_ = std::make_unique<contact::ActiveSetLoop>(*contact_, elim_, fixed_);
    newton_.set_hooks(loop_->hooks());
    const auto& o = newton_.options();
    loop_->set_search(o.warm_resolves && o.search_rtol > 0 && o.search_rtol > o.rtol);
    if (contact_->closes_gaps()) {
      restoration_ = std::make_unique<EnergyRestoration>(newton_.disc(), fixed_);
      closure_p_ = Teuchos::rcp(new Vector(newton_.disc().owned_map()));
    }
  } else {
    elim_.set_constraints(fixed_, {}, {});
  }
}

void Stepper::check_start(const std::string& file) {
  const StartScales st = newton_.start_scales(*s_.u, *s_.V, dt_);
  const auto& disc = newton_.disc();
  const auto& bodies = disc.model().bodies;
  // the largest inertia share of each body's dofs, over all ranks
  std::vector<double> mine(bodies.size(), 0.0), most(bodies.size(), 0.0);
  const auto share = st.inertia_share->getLocalViewHost(Tpetra::Access::ReadOnly);
  const auto& map = *disc.owned_map();
  for (std::size_t l = 0; l < share.extent(0); ++l) {
    const GO node = map.getGlobalElement(static_cast<LO>(l)) / 3;
    for (std::size_t b = 0; b < bodies.size(); ++b)
      if (node >= bodies[b].node_begin && node < bodies[b].node_end)
        mine[b] = std::max(mine[b], share(l, 0));
  }
  if (!bodies.empty())
    Teuchos::reduceAll(*disc.comm(), Teuchos::REDUCE_MAX, static_cast<int>(bodies.size()),
                       mine.data(), most.data());
  const double eps = std::numeric_limits<double>::epsilon();
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const auto& body = bodies[b];
    if (body.rigid || body.tet_end == body.tet_begin || most[b] >= eps) continue;
    const std::string allowed =
        most[b] > 0 ? format("a density of at least %.2g with this young, mesh and dt",
                             body.density * eps / most[b])
                    : "a density whose inertia is not lost (it underflows to 0 here)";
    throw InputError(
        format("%s: parameter \"Bodies/%s/Material/density\": %.3g gives the body an inertia "
               "(2/dt^2) M below the round-off of its stiffness in the Newton matrix (%.2g of "
               "its diagonal at most, at Time/dt = %.3g): its motion would be lost; allowed: "
               "%s (docs/THEORY.md §1.6)",
               file.c_str(), body.name.c_str(), body.density, most[b], dt_, allowed.c_str()));
  }
  const double atol = newton_.options().atol;
  if (atol > 0 && st.scale > 0 && atol >= st.scale)
    throw InputError(
        format("%s: parameter \"Solver/Newton/absolute tolerance\": %.3g is not below the "
               "size of the residual's terms at the first step (%.3g: inertia, internal and "
               "external forces, docs/THEORY.md §1.6): it would accept any iterate; allowed: "
               "a value well below %.3g, or 0 (the default: the relative tolerance decides)",
               file.c_str(), atol, st.scale, st.scale));
}

bool Stepper::finished() const {
  return s_.t >= end_ - 1e-9 * dt_;
}

// §1: the start iterate must satisfy every constraint. With no active contact, the last step's
// increment (its mid-point velocity, smooth also for the stiff modes that V_n flips every step)
// scaled to h does (fixed dofs never move) and saves a Newton iteration in smooth motion; while
// the last step needed more than 2 iterations (a body ringing after an impact) it costs one, so
// u_n is used then, as with active contact.
void Stepper::start_iterate(double h, bool no_contact, Vector& u1) const {
  u1.assign(*s_.u);
  if (s_.last_increment && s_.last_h > 0 && s_.last_iterations <= 2 && no_contact)
    u1.update(h / s_.last_h, *s_.last_increment, 1.0);
}

// One step of size h with the active-set loop of docs/THEORY.md §6; false if Newton failed.
bool Stepper::solve_step(double h, Vector& u1, StepReport& rep) {
  const Vector& u0 = *s_.u;
  double reference = 0;   // the largest first residual of the step's solves (§6.1-§6.2)
  bool searched = false;  // the last solve was a search solve (§6.9)
  auto newton = [&](bool empty, bool warm, bool search, bool restated) -> bool {
    if (!warm) start_iterate(h, empty, u1);
    const double rtol = search ? newton_.options().search_rtol : 0.0;
    const NewtonResult nr =
        newton_.solve(u0, *s_.V, h, u1, warm ? reference : 0.0, rtol, warm && restated);
    if (!nr.residuals.empty()) reference = std::max(warm ? reference : 0.0, nr.residuals.front());
    rep.newton_iterations += nr.iterations;
    // the accepted set's iterations: a final solve continues its search solve (§6.9)
    last_set_iterations_ = nr.iterations + (searched && !search ? last_set_iterations_ : 0);
    searched = search;
    rep.linear_iterations += nr.linear_iterations;
    if (!nr.converged) rep.last_failure = nr.failure;
    return nr.converged;
  };
  if (!loop_) return newton(true, false, false, false);
  // the prediction of u_{n+1} (the reach of the contact nodes, docs/THEORY.md §8)
  u1.assign(u0);
  if (s_.last_increment && s_.last_h > 0) u1.update(h / s_.last_h, *s_.last_increment, 1.0);
  contact::SettledSet settled;
  Teuchos::TimeMonitor tm(contact_timer());  // the loop's own work; Newton's is its own
  const bool ok = loop_->solve(
      u0, u1, s_.active,
      [&](bool changed, bool empty, bool warm, bool search, bool restated) -> const Vector* {
        contact_timer().stop();  // dropping a stale preconditioner is the linear solver's time
        if (changed) newton_.solver().matrix_changed();  // a new P: the preconditioner is stale
        const bool converged =
            newton(empty, warm && newton_.options().warm_resolves, search, restated);
        contact_timer().start();
        return converged ? &newton_.last_residual() : nullptr;
      },
      settled, restoration_ ? closure_p_.get() : nullptr);
  if (!ok || crossed_too_deep(u0, u1, h, settled.nodes, rep)) return false;
  rep.contact = settled.stats;
  closure_work_ = settled.closure;
  s_.active = std::move(settled.active);
  s_.normal_force = std::move(settled.normal_force);
  s_.contact_nodes = std::move(settled.nodes);
  s_.contact_status = std::move(settled.status);
  s_.contact_force = std::move(settled.force);
  s_.contact_slip = std::move(settled.slip);
  dissipated_ = settled.dissipated;
  return true;
}

// docs/THEORY.md §6.3, §1.8: a slave node that crossed a master facet over the step and ends
// behind it deeper than the pair's max penetration cannot be caught by activation (it went
// through a thin master, or too deep into one): the step fails, to be solved again with dt/2.
// `active`: the entries active at the step's accepted solve (they are held).
bool Stepper::crossed_too_deep(const Vector& u0, const Vector& u1, double h,
                               const std::vector<int>& active, StepReport& rep) const {
  const contact::DeepCrossings d =
      contact_->crossed_too_deep(contact_->positions(u0), contact_->positions(u1), active);
  if (d.count == 0) return false;
  const contact::Pair& p = contact_->pairs()[d.pair];
  rep.last_failure = format(
      "%d slave node%s crossed a master facet and ended deeper behind it than "
      "Contact/%s/max penetration = %.3g (node %d: %.3g behind, approaching at %.3g m/s "
      "over the step of %.3g s); a smaller Time/dt (or a larger max penetration) lets "
      "contact catch %s",
      d.count, d.count == 1 ? "" : "s", p.name.c_str(), p.dmax, d.node, -d.gap, d.closing / h, h,
      d.count == 1 ? "it" : "them");
  return true;
}

// docs/THEORY.md §7.4: V_{n+1} += gamma M^-1 p gives back the energy -W_c the closure took
// (or takes the energy it gave); false when no impulse along p can (the step is cut).
bool Stepper::restore_energy(Vector& V1, StepReport& rep) {
  Teuchos::TimeMonitor tm(contact_timer());
  const double D = -closure_work_.work;
  const Restoration r = restoration_->restore(*closure_p_, D, closure_work_.roundoff, V1);
  if (!r.ok) {
    rep.last_failure = format(
        "the gap closure gave %.3e of energy that no compressive velocity update "
        "along the contact normals can take back",
        closure_work_.work);
    return false;
  }
  rep.closure_energy += r.gamma != 0 ? D : 0.0;
  return true;
}

// A step that cannot advance time (below the round-off of t, or not finite: a corrupt
// state) would loop forever: stop instead.
void Stepper::check_step_size(double h) const {
  if (std::isfinite(h) && h > 0 && s_.t + h > s_.t) return;
  throw RunError(
      format("step %ld at t = %.6g: the step size %.3g cannot advance time (it must be "
             "finite, > 0 and above the round-off of t; Time/dt = %.3g)",
             s_.step + 1, s_.t, h, dt_));
}

StepReport Stepper::advance() {
  StepReport rep;
  const Vector& u0 = *s_.u;
  Vector u1(u0.getMap());
  newton_.set_contraction(s_.newton_contraction);
  // docs/THEORY.md §7.2: the closure's fallback keeps the gaps of the slaves whose closure no
  // impulse could give back, for this step only; at most kFallbacks re-solves before a cut
  constexpr int kFallbacks = 3;
  int fallbacks = 0;
  if (loop_) loop_->clear_kept();
  for (;;) {
    // the last step is shortened to end at Time/end, unless only by round-off of the sum of
    // the steps: then it is dt itself, as in a run with a later end (an extended run goes on
    // exactly as that one)
    const double rest = end_ - s_.t;
    const double h = rest < s_.dt * (1 - 1e-9) ? rest : s_.dt;
    check_step_size(h);
    Vector V1(*s_.V, Teuchos::Copy);
    bool restored = true;
    const bool solved = solve_step(h, u1, rep);
    if (solved) {
      // eq. 19: V_{n+1} = 2 (u_{n+1} - u_n)/dt - V_n
      V1.update(2.0 / h, u1, -2.0 / h, u0, -1.0);
      if (restoration_) restored = restore_energy(V1, rep);
    }
    if (solved && restored) {
      s_.V->assign(V1);
      if (!s_.last_increment) s_.last_increment = Teuchos::rcp(new Vector(u0.getMap()));
      s_.last_increment->update(1.0, u1, -1.0, u0, 0.0);
      s_.last_h = h;
      s_.last_iterations = last_set_iterations_;
      s_.newton_contraction = newton_.contraction();
      s_.u->assign(u1);
      s_.t += h;
      ++s_.step;
      rep.dt = h;
      if (loop_) {  // docs/THEORY.md §11.2: D_{n+1} = D_n + the accepted step's friction work
        rep.dissipated = dissipated_;
        s_.dissipated += dissipated_;
      }
      if (s_.dt < dt_ && ++s_.good_steps >= grow_after_) {
        s_.dt = std::min(2 * s_.dt, dt_);
        s_.good_steps = 0;
      }
      return rep;
    }
    if (solved && !restored && loop_ && fallbacks < kFallbacks &&
        loop_->keep_gaps(closure_work_.unrestorable) > 0) {  // §7.2: the same step, closing less
      ++fallbacks;
      ++rep.closure_fallbacks;
      continue;
    }
    ++rep.cuts;
    if (rep.last_failure.find("crossed a master facet") != std::string::npos) {
      crossing_ = format("at step %ld with dt = %.3g, ", s_.step + 1, s_.dt) + rep.last_failure;
    }
    if (s_.dt < dt_ / std::ldexp(1.0, max_cuts_) * 1.5) {
      const std::string failed = format(
          "step %ld at t = %.6g could not be solved even with dt = %.3g (%d halvings "
          "of dt = %.3g, Time/max step cuts): ",
          s_.step + 1, s_.t, s_.dt, max_cuts_, dt_);
      // an element inverted after slave nodes crossed the master at a larger step: the cause
      // is the crossing (an impact too fast for Time/dt), named with it
      if (rep.last_failure.rfind("element ", 0) == 0 && !crossing_.empty())
        throw RunError(failed + rep.last_failure + ", after the steps had been cut because " +
                       crossing_);
      throw RunError(failed + rep.last_failure);
    }
    s_.dt /= 2;
    s_.good_steps = 0;
  }
}

}  // namespace emc::time
