// Settling to static equilibrium before t = 0 (docs/THEORY.md §6.7).
#include <Teuchos_CommHelpers.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "emcontact/error.hpp"
#include "emcontact/parallel.hpp"
#include "emcontact/time/stepper.hpp"

namespace emc::time {
namespace {

/// The set of active slave nodes (global ids) over every rank, for "did it change".
std::vector<double> active_nodes(const State& s, const Comm& comm) {
  std::vector<double> mine;
  for (std::size_t k = 0; k < s.contact_nodes.size(); ++k)
    if (s.contact_status[k] == 1) mine.push_back(s.contact_nodes[k]);
  auto all = allgather(comm, mine);
  std::sort(all.begin(), all.end());
  return all;
}

/// The largest extent of the bodies along x, y or z (X: reference positions, dof 3 n + c).
double model_size(const Vector& X) {
  const auto x = X.getLocalViewHost(Tpetra::Access::ReadOnly);
  const auto& map = *X.getMap();
  double mine[6] = {-1e300, -1e300, -1e300, -1e300, -1e300, -1e300}, most[6];
  for (std::size_t i = 0; i < x.extent(0); ++i) {
    const int c = static_cast<int>(map.getGlobalElement(static_cast<LO>(i)) % 3);
    mine[c] = std::max(mine[c], x(i, 0));
    mine[3 + c] = std::max(mine[3 + c], -x(i, 0));
  }
  Teuchos::reduceAll(*map.getComm(), Teuchos::REDUCE_MAX, 6, mine, most);
  return std::max({most[0] + most[3], most[1] + most[4], most[2] + most[5]});
}

}  // namespace

// §6.7: from (u_k, V = 0) a step of size h gives u_{k+1}; for a mode of frequency w the error
// of the mid-point configuration (u_k + u_{k+1}) / 2 is that of u_k times 4 / (4 + (w h)^2),
// and a configuration the step leaves in place is in static equilibrium (the algorithmic
// internal force of a step that does not move is the internal force). h doubles after each
// step that keeps the active set while the change shrinks, up to 1e4 dt, and goes back to dt
// when the set changes (a long step from V = 0 lets a free node fall g h^2 / 2, beyond the
// reach of activation) or the change grows; rest is checked at steps of dt.
SettleReport Stepper::settle(const SettleOptions& o) {
  SettleReport r;
  if (o.max_steps <= 0) return r;
  const Comm& comm = *s_.u->getMap()->getComm();
  const Vector V_initial(*s_.V, Teuchos::Copy);
  Vector u1(s_.u->getMap()), uk(s_.u->getMap());
  std::vector<double> held = active_nodes(s_, comm);
  double h = dt_, last = 1e300, last_dt = 1e300;
  const double size = model_size(*newton_.disc().reference_positions());
  for (; r.steps < o.max_steps; ++r.steps) {
    s_.V->putScalar(0.0);
    uk.assign(*s_.u);
    StepReport rep;
    if (!solve_step(h, u1, rep)) {
      if (h > dt_) {  // too long a step: shorter
        h = std::max(dt_, h / 4);
        continue;
      }
      throw RunError("settling (Time/settle steps) step " + std::to_string(r.steps + 1) +
                     " could not be solved: " + rep.last_failure);
    }
    r.newton_iterations += rep.newton_iterations;
    r.largest_h = std::max(r.largest_h, h);
    s_.u->update(0.5, u1, 0.5);        // the mid-point configuration
    if (!(s_.u->normInf() <= size)) {  // no static state near the start (a free fall)
      ++r.steps;
      r.moved_away = true;
      break;
    }
    u1.update(-1.0, uk, 1.0);
    const double scale = std::max(s_.u->normInf(), 1e-300);
    r.change = u1.normInf() / scale;
    u1.scale(2.0 / h);  // the velocity the step from rest gave
    const auto m = newton_.disc().monitors(*s_.u, u1);
    r.kinetic = m.kinetic / std::max(m.elastic, 1e-300);
    auto now = active_nodes(s_, comm);
    const bool same = now == held;
    held = std::move(now);
    if (same && h == dt_) {
      // at rest; or settled up to a slow steady free motion (a frictionless slide or twist
      // under a constant net tangential force or torque: the same change at every step of dt,
      // whose kinetic energy is below 1e-6 of the elastic energy, an acceleration below about
      // 1e-3 g for a body loaded by its weight; not a free fall, which has no elastic energy)
      r.steady = std::fabs(r.change - last_dt) <= 1e-3 * r.change && r.kinetic <= 1e-6;
      if (r.kinetic <= o.tolerance || r.steady) {
        r.converged = true;
        ++r.steps;
        break;
      }
      last_dt = r.change;
    }
    // longer steps while the change shrinks; back to dt to check for rest (the change is at
    // round-off), when the change grows (a free motion's grows as h^2) or the set changes
    const bool longer = same && r.change < 2 * last && r.change > 1e-13;
    last = same ? r.change : 1e300;
    h = longer ? std::min(2 * h, 1e4 * dt_) : dt_;
  }
  s_.V->assign(V_initial);
  s_.last_increment = Teuchos::null;
  s_.last_h = 0;
  s_.last_iterations = 0;
  s_.newton_contraction = 0;
  s_.dissipated = 0;
  s_.dt = dt_;
  s_.good_steps = 0;
  return r;
}

}  // namespace emc::time
