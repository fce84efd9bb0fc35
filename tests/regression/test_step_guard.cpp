// A step size that cannot advance time (below the round-off of t, or not finite, as
// from a corrupt state) stops the run with a RunError instead of looping forever.
#include <gtest/gtest.h>

#include <Tpetra_Core.hpp>
#include <cmath>
#include <limits>
#include <string>

#include "emcontact/app/simulation.hpp"
#include "emcontact/error.hpp"

namespace {

std::unique_ptr<emc::app::Simulation> box() {
  emc::app::Options o;
  o.input = std::string(EMC_TEST_DIR) + "/tumbling.xml";
  o.overrides = {"Time/dt=1e-5", "Time/end=2000"};
  return emc::app::setup(o, Tpetra::getDefaultComm());
}

void expect_stops(double t, double dt) {
  auto sim = box();
  sim->state.t = t;
  sim->state.dt = dt;
  try {
    sim->stepper->advance();
    FAIL() << "a step of " << dt << " at t = " << t << " was taken";
  } catch (const emc::RunError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot advance time"), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(StepGuard, StepBelowTheRoundOffOfTStops) {
  expect_stops(1000.0, 1e-14);
}

TEST(StepGuard, NonFiniteStepStops) {
  expect_stops(0.0, std::numeric_limits<double>::quiet_NaN());
  expect_stops(std::numeric_limits<double>::quiet_NaN(), 1e-5);
}
