// Neo-Hookean and Mooney-Rivlin bodies (docs/THEORY.md §12) in whole runs, on 1 and 2 ranks:
// E, L and J of a free tumbling body at large rotation, E through impacts with full stick and
// frictionless contact (bodies of two models together, and with an SVK one; a massless slave;
// gap closure), E + D with Coulomb friction, settling: each to the Newton tolerance (rtol 1e-12 in
// these cases) and round-off, asserted at 1e-10 as the SVK cases are (test_conservation,
// test_contact_coulomb).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "run_case.hpp"
#include "support/long_tests.hpp"

using emc::output::MonitorRow;
using emc::testing::drifts;
using emc::testing::run_case;

namespace {

std::string suffix() {
  return "_np" + std::to_string(Tpetra::getDefaultComm()->getSize());
}
bool one_rank() {
  return Tpetra::getDefaultComm()->getSize() == 1;
}

/// The overrides that make body `body` of model `model` (Mooney-Rivlin with c2 = mu / 8).
std::vector<std::string> model_of(const std::string& body, const std::string& model, double young,
                                  double poisson) {
  std::vector<std::string> s = {"Bodies/" + body + "/Material/model=" + model};
  if (model == "mooney-rivlin")
    s.push_back("Bodies/" + body + "/Material/c2=" + std::to_string(young / (16 * (1 + poisson))));
  return s;
}

/// max over the steps of |E_n + D_n - E_0| / max(K + W + |Pi|).
double energy_error(const std::vector<MonitorRow>& rows) {
  double scale = 0, worst = 0;
  for (const auto& r : rows)
    scale = std::max(scale, r.kinetic + r.elastic + std::fabs(r.potential));
  for (const auto& r : rows)
    worst = std::max(worst, std::fabs(r.total + r.dissipated - rows[0].total) / scale);
  return worst;
}

class Materials : public ::testing::TestWithParam<std::string> {};

// The tumbling box (no loads; 23 rad in 5 s in the long run, 9 rad in 2 s in the default one):
// E, L, J conserved; its elastic energy is the model's (it differs from SVK's by more than 1e-4
// of its largest value at some step).
TEST_P(Materials, TumblingBoxConservesEnergyAndMomenta) {
  if (!one_rank()) GTEST_SKIP() << "asserted on 1 rank (test_conservation's case)";
  const std::string end = emc::testing::long_tests() ? "Time/end=5" : "Time/end=2";
  auto sets = model_of("block", GetParam(), 1e5, 0.3);
  sets.push_back(end);
  const auto rows = run_case("tumbling.xml", sets, "out_tumbling_" + GetParam());
  const auto svk = run_case("tumbling.xml", {end}, "out_tumbling_svk_" + GetParam());
  ASSERT_EQ(rows.size(), svk.size());
  const auto d = drifts(rows);
  double wmax = 0, dW = 0;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    wmax = std::max(wmax, rows[k].elastic);
    dW = std::max(dW, std::fabs(rows[k].elastic - svk[k].elastic));
  }
  std::printf("%s tumbling: drift E %.3e L %.3e J %.3e; max |W - W_svk| / max W = %.3e\n",
              GetParam().c_str(), d.E, d.L, d.J, dW / wmax);
  EXPECT_LT(d.E, 1e-10);
  EXPECT_LT(d.L, 1e-10);
  EXPECT_LT(d.J, 1e-10);
  EXPECT_GT(wmax, 1e-3 * rows[0].total);
  EXPECT_GT(dW, 1e-4 * wmax);
}

// Full stick: the drop with its spin onto the rigid ground, through impact and rebound.
TEST_P(Materials, FullStickDropConservesEnergy) {
  auto sets = model_of("block", GetParam(), 5e5, 0.3);
  sets.push_back("Time/end=0.4");
  const auto rows = run_case("drop.xml", sets, "out_drop_" + GetParam() + suffix());
  int contact_steps = 0;
  for (const auto& r : rows) contact_steps += r.active_contacts > 0;
  const double e = energy_error(rows);
  std::printf("%s drop: max |E - E0| / max(K + W + |Pi|) = %.3e, %d steps in contact\n",
              GetParam().c_str(), e, contact_steps);
  EXPECT_LT(e, 1e-10);
  EXPECT_GT(contact_steps, 5);
}

// Frictionless between two deformable bodies of different models (this model on A, SVK on B;
// on 1 rank also this model on A and the other new model on B): E conserved through the
// collision.
TEST_P(Materials, FrictionlessBlocksOfMixedModelsConserveEnergy) {
  const std::string other = GetParam() == "neo-hookean" ? "mooney-rivlin" : "neo-hookean";
  std::vector<std::string> b_models = {"svk"};
  if (one_rank()) b_models.push_back(other);  // 2 ranks: the SVK mix (a run's time saved)
  for (const std::string& b_model : b_models) {
    auto sets = model_of("A", GetParam(), 2e4, 0.3);
    for (const auto& s : model_of("B", b_model, 2e4, 0.3)) sets.push_back(s);
    sets.push_back("Time/end=0.3");  // the collision is over by t = 0.2
    const auto rows =
        run_case("two_blocks.xml", sets, "out_two_blocks_" + GetParam() + "_" + b_model + suffix());
    int contact_steps = 0;
    for (const auto& r : rows) contact_steps += r.active_contacts > 0;
    const double e = energy_error(rows);
    std::printf("%s on %s blocks: max |E - E0| / max(K + W + |Pi|) = %.3e, %d steps in contact\n",
                GetParam().c_str(), b_model.c_str(), e, contact_steps);
    EXPECT_LT(e, 1e-10);
    EXPECT_GT(contact_steps, 5);
  }
}

// Coulomb: the stiff block sliding to rest (mu = 0.3): E + D = E0, D > 0 and non-decreasing.
TEST_P(Materials, CoulombSlideBalancesEnergyAndDissipation) {
  if (!one_rank()) GTEST_SKIP() << "asserted on 1 rank (2 ranks: test_contact_coulomb's SVK cases)";
  auto sets = model_of("block", GetParam(), 1e7, 0.3);
  sets.push_back("Time/end=0.3");
  const auto rows = run_case("slide.xml", sets, "out_slide_" + GetParam() + suffix());
  bool monotone = true;
  for (std::size_t k = 1; k < rows.size(); ++k)
    monotone &= rows[k].dissipated >= rows[k - 1].dissipated;
  const double e = energy_error(rows);
  std::printf("%s slide: max |E + D - E0| / max(K + W + |Pi|) = %.3e, D = %.4e\n",
              GetParam().c_str(), e, rows.back().dissipated);
  EXPECT_LT(e, 1e-10);
  EXPECT_TRUE(monotone);
  EXPECT_GT(rows.back().dissipated, 0.1 * rows[0].kinetic);
}

// The frictionless blocks, both of this model, with a massless slave (docs/THEORY.md §6.8) and
// with gap closure (§7): E, L, J through the collision (the massless slave's moved mass keeps L
// and J exact), and every active gap closed to round-off at every step of the closed run.
TEST_P(Materials, MasslessSlaveAndGapClosureConserve) {
  if (!one_rank()) GTEST_SKIP() << "asserted on 1 rank (2 ranks: the SVK cases of these options)";
  auto both = model_of("A", GetParam(), 2e4, 0.3);
  for (const auto& s : model_of("B", GetParam(), 2e4, 0.3)) both.push_back(s);
  both.push_back("Contact/A on B/type=frictionless");
  both.push_back("Time/end=0.3");  // the collision is over by t = 0.2
  for (const std::string option : {"massless slave", "close gap"}) {
    auto sets = both;
    sets.push_back("Contact/A on B/" + option + "=true");
    const auto rows = run_case("two_blocks.xml", sets,
                               "out_two_blocks_" + GetParam() + "_" + option.substr(0, 5));
    int contact_steps = 0;
    double gap = 0;
    for (const auto& r : rows)
      if (r.active_contacts > 0) {
        ++contact_steps;
        gap = std::max(gap, r.gap_max);
      }
    const auto d = drifts(rows);
    std::printf(
        "%s blocks, %s: E %.3e L %.3e J %.3e, largest active gap %.2e, %d steps in "
        "contact\n",
        GetParam().c_str(), option.c_str(), d.E, d.L, d.J, gap, contact_steps);
    EXPECT_GT(contact_steps, 5);
    EXPECT_LT(d.E, 1e-10);
    EXPECT_LT(d.L, 1e-10);
    EXPECT_LT(d.J, 1e-10);
    if (option == "close gap") EXPECT_LE(gap, 1e-9);
  }
}

// Settling (docs/THEORY.md §6.7): a block set down on the ground under gravity reaches static
// equilibrium, then stays there (no kinetic energy, every step at rest, no Newton iteration).
TEST_P(Materials, SettledBlockStaysAtRest) {
  if (!one_rank()) GTEST_SKIP() << "asserted on 1 rank";
  auto sets = model_of("block", GetParam(), 5e5, 0.3);
  for (const char* s :
       {"Bodies/block/Mesh/lower corner={-0.1, -0.1, 0}",
        "Bodies/block/Mesh/upper corner={0.1, 0.1, 0.2}", "Bodies/block/Initial/velocity={0, 0, 0}",
        "Bodies/block/Initial/angular velocity={0, 0, 0}", "Time/settle steps=100",
        "Time/end=0.05"})
    sets.push_back(s);
  const auto rows = run_case("drop.xml", sets, "out_settled_" + GetParam());
  double kinetic = 0;
  int contact_steps = 0;
  for (const auto& r : rows) {
    kinetic = std::max(kinetic, r.kinetic);
    contact_steps += r.active_contacts > 0;
  }
  std::printf("%s settled block: elastic energy %.6e, largest kinetic %.3e\n", GetParam().c_str(),
              rows.back().elastic, kinetic);
  EXPECT_GT(rows.back().elastic, 0);  // it carries its weight
  EXPECT_LE(kinetic, 1e-12 * rows.back().elastic);
  EXPECT_EQ(contact_steps, static_cast<int>(rows.size()) - 1);
}

INSTANTIATE_TEST_SUITE_P(Models, Materials, ::testing::Values("neo-hookean", "mooney-rivlin"),
                         [](const auto& info) {
                           return info.param == "neo-hookean" ? std::string("NeoHookean")
                                                              : std::string("MooneyRivlin");
                         });

}  // namespace
