// Where slave nodes enter the master (docs/THEORY.md §6.3, §6.6), whole runs: a face lying on a
// tilted rigid plane is accepted at t = 0 and rests or slides as it must.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "emcontact/app/simulation.hpp"

namespace {

std::unique_ptr<emc::app::Simulation> setup(const std::string& xml, std::vector<std::string> sets) {
  emc::app::Options o;
  o.input = std::string(EMC_TEST_DIR) + "/" + xml;
  o.overrides = std::move(sets);
  return emc::app::setup(o, Tpetra::getDefaultComm());
}

double energy(const emc::app::Simulation& sim) {
  const auto m = sim.disc->monitors(*sim.state.u, *sim.state.V);
  return m.kinetic + m.elastic + m.potential;
}

/// K + W + |Pi|: the energy error's scale where E0 is 0 (a body at rest, the potential's origin).
double energy_scale(const emc::app::Simulation& sim) {
  const auto m = sim.disc->monitors(*sim.state.u, *sim.state.V);
  return m.kinetic + m.elastic + std::fabs(m.potential);
}

std::array<double, 3> centre_of_mass(const emc::app::Simulation& sim) {
  const auto m = sim.disc->monitors(*sim.state.u, *sim.state.V);
  return {m.moment[0] / m.mass, m.moment[1] / m.mass, m.moment[2] / m.mass};
}

}  // namespace

// A puck's bottom face lying on a rigid plane tilted by 30 and by 7 degrees (tilted_plane.xml,
// the same axis for both): its centroid is 1e-17 off the plane either way by round-off, and the
// face is accepted. With full stick it rests: E to 1e-10 (of the largest K + W + |Pi|: E0 = 0
// at rest) over 8 steps, and its centre of mass moves less than 1e-3 of its radius along the
// slope (the elastic settling under gravity). Frictionless, it slides down the slope as a free
// body: 0.5 g sin(angle) t^2 to 1e-6 of it.
class TiltedPlane : public ::testing::TestWithParam<double> {};
TEST_P(TiltedPlane, AFaceLyingOnItIsAcceptedAndRestsOrSlides) {
  const double angle = GetParam() * M_PI / 180, s = std::sin(angle), c = std::cos(angle);
  char axis[128];
  std::snprintf(axis, sizeof axis, "{%.17g, 0, %.17g}", s, c);
  const double down[3] = {c, 0, -s};  // down the slope
  for (const char* type : {"full stick", "frictionless"}) {
    auto sim = setup("tilted_plane.xml",
                     {std::string("Bodies/puck/Mesh/axis=") + axis,
                      std::string("Bodies/slope/Mesh/axis=") + axis,
                      std::string("Contact/puck on slope/type=") + type, "Time/end=0.04"});
    const double E0 = energy(*sim);
    const auto com0 = centre_of_mass(*sim);
    double dE = 0, scale = 0;
    while (!sim->stepper->finished()) {
      sim->stepper->advance();
      dE = std::max(dE, std::fabs(energy(*sim) - E0));
      scale = std::max(scale, energy_scale(*sim));
    }
    dE /= scale;
    const auto com = centre_of_mass(*sim);
    double along = 0;
    for (int i = 0; i < 3; ++i) along += (com[i] - com0[i]) * down[i];
    const double t = sim->state.t, free = 0.5 * 9.81 * s * t * t;
    std::printf("%s at %g degrees: dE %.2e, down the slope %.6e (free slide %.6e)\n", type,
                GetParam(), dE, along, free);
    EXPECT_LT(dE, 1e-10) << type;
    if (std::string(type) == "full stick")
      EXPECT_LT(std::fabs(along), 1e-3 * 0.1);
    else
      EXPECT_NEAR(along, free, 1e-6 * free);
  }
}
INSTANTIATE_TEST_SUITE_P(Entry, TiltedPlane, ::testing::Values(30.0, 7.0));
