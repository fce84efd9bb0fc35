// Schema of the `Time` section.
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
  pl->set("integrator", std::string("energy-momentum"), "Time integrator.",
          string_choice("integrator", {"energy-momentum", "midpoint"},
                        {"energy-momentum conserving scheme (conserves energy and momenta)",
                         "implicit midpoint rule"}));
  pl->set("max step cuts", 6, "How many times a failed step may halve dt before the run fails.",
          int_range(0, 20));
  pl->set("grow after", 4,
          "Successful sub-steps after which dt doubles back toward the nominal dt.",
          int_at_least(1));
  return pl;
}

}  // namespace emc::time
