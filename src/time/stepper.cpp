#include "emcontact/time/stepper.hpp"

#include <cmath>
#include <cstdio>

#include "emcontact/error.hpp"

namespace emc::time {

Stepper::Stepper(const Teuchos::ParameterList& time, Newton& newton, State& state)
    : newton_(newton),
      s_(state),
      dt_(time.get<double>("dt")),
      end_(time.get<double>("end")),
      max_cuts_(time.get<int>("max step cuts")),
      grow_after_(time.get<int>("grow after")) {
  if (s_.dt <= 0) s_.dt = dt_;
}

bool Stepper::finished() const { return s_.t >= end_ - 1e-9 * dt_; }

StepReport Stepper::advance() {
  StepReport rep;
  const Vector& u0 = *s_.u;
  const Vector& V0 = *s_.V;
  Vector u1(u0.getMap());
  for (;;) {
    const double h = std::min(s_.dt, end_ - s_.t);
    u1.assign(u0);  // u_{n+1}^0 = u_n (ALGORITHM.md §1)
    const NewtonResult nr = newton_.solve(u0, V0, h, u1);
    rep.newton_iterations += nr.iterations;
    rep.linear_iterations += nr.linear_iterations;
    if (nr.converged) {
      // eq. 19: V_{n+1} = 2 (u_{n+1} - u_n)/dt - V_n
      s_.V->update(2.0 / h, u1, -2.0 / h, u0, -1.0);
      s_.u->assign(u1);
      s_.t += h;
      ++s_.step;
      rep.dt = h;
      if (s_.dt < dt_ && ++s_.good_steps >= grow_after_) {
        s_.dt = std::min(2 * s_.dt, dt_);
        s_.good_steps = 0;
      }
      return rep;
    }
    rep.last_failure = nr.failure;
    ++rep.cuts;
    if (s_.dt < dt_ / std::ldexp(1.0, max_cuts_) * 1.5) {
      char buf[256];
      std::snprintf(buf, sizeof buf,
                    "step %ld at t = %.6g could not be solved even with dt = %.3g (%d halvings "
                    "of dt = %.3g, Time/max step cuts): ",
                    s_.step + 1, s_.t, s_.dt, max_cuts_, dt_);
      throw RunError(buf + nr.failure);
    }
    s_.dt /= 2;
    s_.good_steps = 0;
  }
}

}  // namespace emc::time
