// Schema of the `Time` section and of `Solver/Newton`.
#include "emcontact/time/parameters.hpp"

#include <cmath>

#include "emcontact/input/validators.hpp"

namespace emc::time {

Teuchos::RCP<const Teuchos::ParameterList> valid_parameters() {
  using namespace emc::input;
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("Time"));
  // beyond 1e30 s the inertia terms of the residual underflow: a step "converges" unmoved
  const auto time_range = double_range(std::nextafter(0.0, 1.0), 1e30);
  pl->set("dt", 0.01,
          "Nominal time step [s]; the step is halved on failure (see max step cuts). At most "
          "1e9 steps: dt >= end / 1e9.",
          time_range);
  pl->set("end", 1.0, "End time [s] (the run starts at t = 0); must be >= dt.", time_range);
  pl->set("max step cuts", 6, "How many times a failed step may halve dt before the run fails.",
          int_range(0, 20));
  pl->set("grow after", 4,
          "Successful sub-steps after which dt doubles back toward the nominal dt.",
          int_at_least(1));
  pl->set("settle steps", 0,
          "Start at rest in static equilibrium under the loads (docs/THEORY.md §6.7): before "
          "t = 0, at most this many steps from zero velocity, each followed by the mid-point "
          "configuration, with the step size growing from dt while the active set holds; then "
          "the bodies' Initial velocities are applied. For bodies that touch their supports at "
          "the start (a stack, a block on the ground); a body without support has no static "
          "equilibrium and the run stops. 0: start from the undeformed mesh (a load applied "
          "suddenly at t = 0 makes the bodies ring).",
          int_at_least(0));
  pl->set(
      "settle tolerance", 1e-12,
      "Settling ends when a step of dt from rest gives a kinetic energy below this "
      "fraction of the elastic energy with the same active set, or the same displacement "
      "at every step of dt (a steady free motion: a frictionless slide or twist under a constant "
      "tangential force).",
      positive_double());
  pl->set("integrator", std::string("energy-momentum"), "Time integrator.",
          string_choice("integrator", {"energy-momentum", "midpoint"},
                        {"energy-momentum conserving scheme (conserves energy and momenta)",
                         "implicit midpoint rule"},
                        std::vector<kernels::Integrator>{kernels::Integrator::energy_momentum,
                                                         kernels::Integrator::midpoint}));
  return pl;
}

Teuchos::RCP<const Teuchos::ParameterList> valid_newton_parameters() {
  using namespace emc::input;
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("Newton"));
  pl->set("relative tolerance", 1e-10,
          "Newton converges when the residual norm falls below this fraction of the "
          "step's initial residual norm (or below the absolute tolerance).",
          positive_double());
  pl->set("absolute tolerance", 0.0,
          "Absolute tolerance of the Newton residual norm (0 = not used).", double_at_least(0.0));
  pl->set("max iterations", 25, "Newton iterations per step before the step counts as failed.",
          int_at_least(1));
  pl->set("adaptive linear tolerance", true,
          "Solve each Newton iteration's linear system only to a hundredth of the residual the "
          "quadratically converging Newton step leaves anyway (estimated from the residual "
          "history), never tighter than Solver/Linear/tolerance requires and never below the "
          "round-off floor; false: every solve to Solver/Linear/tolerance.");
  pl->set("warm re-solves", true,
          "Start each re-solve of a step's active-set loop (after contact nodes were activated "
          "or released, docs/THEORY.md §6) from the last converged solve of the step, the new "
          "constraints applied to it, the relative tolerance taken from the largest first "
          "residual of the step's solves; false: every solve starts from u_n.");
  pl->set("search tolerance", 1e-4,
          "Relative tolerance of the solves that only search a step's contact set (docs/THEORY.md "
          "§6.9): each solve of the active-set loop stops at this fraction of the largest first "
          "residual of the step's solves, and only the settled set is solved on to the relative "
          "tolerance (and checked again there). Effective with warm re-solves and above the "
          "relative tolerance; 0: every solve to the relative tolerance.",
          double_at_least(0.0));
  return pl;
}

Settings read_settings(const Teuchos::ParameterList& time, const Teuchos::ParameterList& newton) {
  Settings s;
  s.step.dt = time.get<double>("dt");
  s.step.end = time.get<double>("end");
  s.step.max_cuts = time.get<int>("max step cuts");
  s.step.grow_after = time.get<int>("grow after");
  s.settle.max_steps = time.get<int>("settle steps");
  s.settle.tolerance = time.get<double>("settle tolerance");
  s.integrator = Teuchos::getIntegralValue<kernels::Integrator>(time, "integrator");
  NewtonOptions& o = s.newton;
  o.rtol = newton.get<double>("relative tolerance");
  o.atol = newton.get<double>("absolute tolerance");
  o.max_iterations = newton.get<int>("max iterations");
  o.adaptive_linear_tolerance = newton.get<bool>("adaptive linear tolerance");
  o.warm_resolves = newton.get<bool>("warm re-solves");
  o.search_rtol = newton.get<double>("search tolerance");
  return s;
}

}  // namespace emc::time
