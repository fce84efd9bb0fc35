// Step control (docs/THEORY.md §1.8): a step whose Newton fails is retried with dt/2 and dt grows
// back; no step is accepted unconverged, so conservation holds through the cuts; a run that
// cannot continue stops with a clear error after writing the monitors it had.
#include <gtest/gtest.h>

#include <cmath>

#include "emcontact/error.hpp"
#include "run_case.hpp"

using emc::testing::drifts;
using emc::testing::run_case;

// With at most 4 Newton iterations, most 0.04 s steps of the fast tumbling box fail and are
// cut to 0.02 s; after `grow after` good steps dt is restored to 0.04 s (and cut again).
TEST(StepControl, CutsAndGrowsBackWithoutLosingConservation) {
  const auto rows = run_case(
      "tumbling.xml",
      {"Time/dt=0.04", "Time/end=0.4", "Solver/Newton/max iterations=4",
       "Solver/Newton/relative tolerance=1e-8", "Bodies/block/Initial/angular velocity={0,0,12}"},
      "out_step_control");
  double dt_min = 1, dt_max = 0;
  for (std::size_t k = 1; k < rows.size(); ++k) {
    dt_min = std::min(dt_min, rows[k].dt);
    dt_max = std::max(dt_max, rows[k].dt);
  }
  std::printf("dt between %.4g and %.4g over %zu steps\n", dt_min, dt_max, rows.size() - 1);
  EXPECT_LT(dt_min, 0.04 * 0.75);             // some steps were cut
  EXPECT_NEAR(dt_max, 0.04, 1e-12);           // and dt grew back to the nominal one
  EXPECT_NEAR(rows.back().time, 0.4, 1e-12);  // and the run still reaches its end
  const auto d = drifts(rows);
  std::printf("drifts through the cuts: E %.3e L %.3e J %.3e\n", d.E, d.L, d.J);
  EXPECT_LT(d.E, 1e-7);  // Newton rtol 1e-8 here
  EXPECT_LT(d.L, 1e-7);
}

TEST(StepControl, RunThatCannotContinueStopsWithMessageAndKeepsMonitors) {
  try {
    run_case("tumbling.xml",
             {"Time/dt=0.04", "Solver/Newton/max iterations=1", "Time/max step cuts=1",
              "Bodies/block/Initial/angular velocity={0,0,12}"},
             "out_step_fail");
    FAIL() << "the run should have stopped";
  } catch (const emc::RunError& e) {
    const std::string msg = e.what();
    std::printf("message: %s\n", msg.c_str());
    EXPECT_NE(msg.find("could not be solved"), std::string::npos);
    EXPECT_NE(msg.find("max step cuts"), std::string::npos);
    EXPECT_NE(msg.find("Newton did not converge"), std::string::npos);
    EXPECT_NE(msg.find("checkpoint.h5"), std::string::npos);  // the last step, to restart from
  }
  const std::string out = emc::testing::run_directory("out_step_fail");
  EXPECT_TRUE(std::filesystem::exists(out + "/checkpoint.h5"));
  const auto rows = emc::output::read_monitors(out + "/monitors.csv");
  EXPECT_GE(rows.size(), 1u);  // the initial state (and any accepted step) is on disk
}
