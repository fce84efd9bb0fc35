// Whole runs without contact asserting the conservation properties of docs/THEORY.md §1.5.
#include <gtest/gtest.h>

#include <cmath>

#include "run_case.hpp"

using emc::testing::drifts;
using emc::testing::run_case;

// A free box tumbling with large rotations (|omega| = 4.6 rad/s for 5 s: about 23 rad), no
// loads: energy-momentum conserves E, L and J to the Newton tolerance (rtol 1e-12 here), far
// below the 1e-10 asserted here; the plain mid-point rule conserves L and J but not E.
TEST(Conservation, TumblingBoxEnergyMomentum) {
  const auto rows = run_case("tumbling.xml", {}, "out_tumbling_em");
  ASSERT_EQ(rows.size(), 501u);  // 500 steps + the initial row
  const auto d = drifts(rows);
  std::printf("energy-momentum: max relative drift E %.3e L %.3e J %.3e\n", d.E, d.L, d.J);
  EXPECT_LT(d.E, 1e-10);
  EXPECT_LT(d.L, 1e-10);
  EXPECT_LT(d.J, 1e-10);
  double wmax = 0;
  for (const auto& r : rows) wmax = std::max(wmax, r.elastic);
  EXPECT_GT(wmax, 1e-3 * rows[0].total);  // genuinely deformed, not a rigid rotation
}

TEST(Conservation, TumblingBoxMidpointLosesEnergyOnly) {
  const auto rows = run_case("tumbling.xml", {"Time/integrator=midpoint"}, "out_tumbling_mid");
  const auto d = drifts(rows);
  std::printf("midpoint: max relative drift E %.3e L %.3e J %.3e\n", d.E, d.L, d.J);
  EXPECT_GT(d.E, 1e-6);  // measurable: at least 10^4 times the energy-momentum bound
  EXPECT_LT(d.L, 1e-10);
  EXPECT_LT(d.J, 1e-10);
}

// Constant gravity on a free spinning body: E = K + W + Pi conserved; the centre of mass
// follows x0 + v0 t + g t^2/2 exactly (the mid-point rule integrates a constant acceleration
// exactly) and L = L0 + M g t.
TEST(Conservation, FreeFallUnderGravity) {
  const double g = -9.81;
  const auto rows = run_case("tumbling.xml",
                             {"Loads/gravity={0,0,-9.81}", "Time/end=1.0",
                              "Bodies/block/Initial/angular velocity={0,0,1}"},
                             "out_free_fall");
  ASSERT_EQ(rows.size(), 101u);
  const auto& r0 = rows.front();
  const double mass = 1000 * 1.0 * 0.5 * 0.3;
  double scale = 0, worst_E = 0, worst_x = 0, worst_L = 0;
  for (const auto& r : rows)
    scale = std::max(scale, r.kinetic + r.elastic + std::fabs(r.potential));
  for (const auto& r : rows) {
    const double t = r.time;
    worst_E = std::max(worst_E, std::fabs(r.total - r0.total) / scale);
    const double z = r0.com[2] + 0.5 * g * t * t, x = r0.com[0] + 0.3 * t, y = r0.com[1] + 0.1 * t;
    worst_x = std::max(
        {worst_x, std::fabs(r.com[2] - z), std::fabs(r.com[0] - x), std::fabs(r.com[1] - y)});
    worst_L = std::max(worst_L, std::fabs(r.L[2] - (r0.L[2] + mass * g * t)) / (mass * 9.81));
  }
  std::printf("gravity: E drift %.3e (of max K+W+|Pi|), com error %.3e m, Lz error %.3e\n", worst_E,
              worst_x, worst_L);
  EXPECT_LT(worst_E, 1e-10);
  EXPECT_LT(worst_x, 1e-10 * 4.905);  // relative to the fall distance g t^2 / 2 at t = 1
  EXPECT_LT(worst_L, 1e-10);
  EXPECT_NEAR(rows.back().com[2] - r0.com[2], 0.5 * g, 1e-9);
}

// Fixed nodes (Dirichlet, eliminated through P^T A P) do no work: a cantilever swinging under
// gravity conserves E although L is not conserved (the support reacts).
TEST(Conservation, CantileverWithDirichletConservesEnergy) {
  const auto rows = run_case("cantilever.xml", {}, "out_cantilever");
  ASSERT_GT(rows.size(), 50u);
  const auto& r0 = rows.front();
  double scale = 0, worst = 0, wmax = 0;
  for (const auto& r : rows)
    scale = std::max(scale, r.kinetic + r.elastic + std::fabs(r.potential));
  for (const auto& r : rows) {
    worst = std::max(worst, std::fabs(r.total - r0.total) / scale);
    wmax = std::max(wmax, r.elastic);
  }
  std::printf("cantilever: E drift %.3e of %.3e, max W %.3e, final Lz %.3e\n", worst, scale, wmax,
              rows.back().L[2]);
  EXPECT_LT(worst, 1e-10);
  EXPECT_GT(wmax, 0.1 * scale);                                // the beam bends substantially
  EXPECT_GT(std::fabs(rows.back().com[2] - r0.com[2]), 1e-3);  // and sags
}
