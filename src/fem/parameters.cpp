// Schema of the body, load, Dirichlet and assembly parts of the input.
#include "emcontact/fem/parameters.hpp"

#include "emcontact/fem/scatter.hpp"
#include "emcontact/input/validators.hpp"
#include "kernels/em_tet4.hpp"

namespace emc::fem {

using namespace emc::input;

Teuchos::RCP<const Teuchos::ParameterList> valid_body_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("<body>"));
  auto& mat = pl->sublist("Material", false, "Saint-Venant-Kirchhoff material of the body.");
  mat.set("young", 1e6, "Young's modulus [Pa].", positive_double());
  mat.set("poisson", 0.3, "Poisson's ratio.", double_range(0.0, std::nextafter(0.5, 0.0)));
  mat.set("density", 1000.0, "Mass density in the reference configuration [kg/m^3].",
          positive_double());
  auto& init = pl->sublist("Initial", false, "Initial rigid motion of the body.");
  init.set("velocity", vec3(0, 0, 0), "Initial velocity of the centre of mass [m/s].", vector3());
  init.set("angular velocity", vec3(0, 0, 0),
           "Initial angular velocity about the centre of mass [rad/s].", vector3());
  return pl;
}

Teuchos::RCP<const Teuchos::ParameterList> valid_load_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("Loads"));
  pl->set("gravity", vec3(0, 0, 0), "Gravitational acceleration [m/s^2].", vector3());
  return pl;
}

Teuchos::RCP<const Teuchos::ParameterList> valid_dirichlet_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("<condition>"));
  pl->set("body", std::string(""), "Required: the name of the body (a sublist of Bodies).",
          any_string());
  pl->set("surface", std::string(""),
          "Required: a named surface of the body's mesh (a Gmsh physical surface, a generator "
          "face such as xmin or bottom, or boundary); its displacement is fixed to zero.",
          any_string());
  return pl;
}

Teuchos::RCP<const Teuchos::ParameterList> valid_time_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("Time"));
  pl->set("integrator", std::string("energy-momentum"), "Time integrator.",
          string_choice("integrator", {"energy-momentum", "midpoint"},
                        {"energy-momentum conserving scheme (conserves energy and momenta)",
                         "implicit midpoint rule"},
                        std::vector<kernels::Integrator>{kernels::Integrator::energy_momentum,
                                                         kernels::Integrator::midpoint}));
  return pl;
}

Teuchos::RCP<const Teuchos::ParameterList> valid_assembly_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("Assembly"));
  pl->set(
      "scatter", std::string("auto"),
      "How the element loops add into the rows their elements share: coloured runs are "
      "reproducible bit for bit with any number of threads (docs/THEORY.md §9) and slower than "
      "atomic in Serial (perf/README.md \"OpenMP threads\"); atomic "
      "runs with several threads differ in the last bits from run to run (with one thread "
      "they add in loop order, as reproducible).",
      string_choice(
          "scatter", {"auto", "coloured", "atomic"},
          {"atomic in Kokkos' Serial backend (plain adds in loop order), coloured on a threaded "
           "backend (also on one thread: its atomic adds are locked instructions)",
           "one loop per colour of 512-element chunks (chunks of a colour share no "
           "node) with plain adds: every row sums in the same order",
           "one loop over all elements with atomic adds: with several threads the "
           "order of the sums varies, and so does the round-off"},
          std::vector<ScatterChoice>{ScatterChoice::automatic, ScatterChoice::coloured,
                                     ScatterChoice::atomic}));
  return pl;
}

}  // namespace emc::fem
