// Schema of the body, load, Dirichlet and assembly parts of the input.
#include "emcontact/fem/parameters.hpp"

#include "emcontact/fem/material.hpp"
#include "emcontact/fem/scatter.hpp"
#include "emcontact/input/validators.hpp"
#include "kernels/em_tet4.hpp"

namespace emc::fem {

using namespace emc::input;

namespace {

constexpr double kSpeedOfLight = 3e8;  ///< [m/s], the bound of a velocity component
constexpr double kMaxGravity = 1e12;   ///< [m/s^2], about a neutron star's surface gravity

/// A 3-vector whose components are at most `bound` in magnitude.
ValidatorPtr bounded_vector3(double bound) {
  return Teuchos::rcp(new Teuchos::ArrayNumberValidator<double>(
      Teuchos::rcp(new Teuchos::EnhancedNumberValidator<double>(-bound, bound, 1.0))));
}

}  // namespace

Teuchos::RCP<const Teuchos::ParameterList> valid_body_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("<body>"));
  auto& mat = pl->sublist("Material", false,
                          "Hyperelastic material of the body (docs/THEORY.md §1.2, §12).");
  mat.set("model", std::string("svk"),
          "The strain energy W (docs/THEORY.md §12), each with the small-strain Lame constants "
          "lambda, mu of young and poisson. svk: Saint-Venant-Kirchhoff, lambda/2 tr(E)^2 + mu "
          "E:E, for small strains with large rotations (in compression its stress peaks at a "
          "stretch of 0.58 and falls to zero there: a hard impact crushes it); neo-hookean: "
          "mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2, for rubber-like bodies at large strain; "
          "mooney-rivlin: c1 (I1 - 3) + c2 (I2 - 3) - 2 (c1 + 2 c2) ln J + (lambda - 4 c2)/2 (ln "
          "J)^2 with c1 = mu/2 - c2 (c2 = 0: neo-hookean). Energy and momenta are exact with "
          "each.",
          string_choice(
              "model", {"svk", "neo-hookean", "mooney-rivlin"},
              {"Saint-Venant-Kirchhoff", "compressible Neo-Hookean", "compressible Mooney-Rivlin"},
              std::vector<MaterialModel>{MaterialModel::svk, MaterialModel::neo_hookean,
                                         MaterialModel::mooney_rivlin}));
  mat.set("c2", 0.0,
          "Mooney-Rivlin's c2 [Pa] (model mooney-rivlin only; c1 = mu/2 - c2): from 0 to the "
          "smaller of mu/2 (c1 >= 0) and lambda/4 (the ln J term's lambda - 4 c2 >= 0). A fit "
          "with c1, c2 and an initial Poisson ratio nu: young = 4 (c1 + c2) (1 + nu).",
          double_range(0.0, 1e14));
  mat.set("young", 1e6,
          "Young's modulus [Pa] (the small-strain one, of every model). At most "
          "1e14, 100 times diamond's (1.2e12 Pa, the stiffest "
          "solid; 1e13 in CGS units): 1e15 on a 5 cm mesh at dt = 5 ms already makes the Newton "
          "matrix too ill-conditioned for GMRES, 1e308 overflows. At least 1e-6, 1e7 times below "
          "the softest gels (about 10 Pa): below it the elastic forces vanish in the round-off "
          "of the inertia (denormal numbers).",
          double_range(1e-6, 1e14));
  mat.set("poisson", 0.3,
          "Poisson's ratio. At most 0.49999: lambda / mu = 2 nu / (1 - 2 nu) at most 5e4. The "
          "Newton matrix's condition grows with lambda / mu: GMRES with ILU needs cut steps "
          "from 0.4999 on and a direct solver (Solver/Linear/type) from 0.49999 on; at "
          "0.4999999999 even a direct solve loses the energy conservation to round-off (2e-9). "
          "P1 tetrahedra lock long before: rubber is 0.49.",
          double_range(0.0, 0.49999));
  mat.set("density", 1000.0,
          "Mass density in the reference configuration [kg/m^3]. From 1e-12 (the tonne per "
          "cubic millimetre units give steel 7.85e-9) to 1e6, 40 times osmium's (22590, the "
          "densest element): mass times the squared speeds then stays finite (1e308 "
          "overflows the kinetic energy).",
          double_range(1e-12, 1e6));
  auto& init = pl->sublist("Initial", false, "Initial rigid motion of the body.");
  init.set("velocity", vec3(0, 0, 0),
           "Initial velocity of the centre of mass [m/s]: each component at most the speed of "
           "light, 3e8, in magnitude (the model is not relativistic; 1e20 swamps the positions "
           "in round-off).",
           bounded_vector3(kSpeedOfLight));
  init.set("angular velocity", vec3(0, 0, 0),
           "Initial angular velocity about the centre of mass [rad/s] (a step that cannot be "
           "solved names it if it turns the body by more than about 1 rad).",
           vector3());
  return pl;
}

Teuchos::RCP<const Teuchos::ParameterList> valid_load_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("Loads"));
  pl->set("gravity", vec3(0, 0, 0),
          "Gravitational acceleration [m/s^2]: each component at most 1e12 in magnitude, about "
          "the surface gravity of a neutron star (1e300 overflows the load vector).",
          bounded_vector3(kMaxGravity));
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
