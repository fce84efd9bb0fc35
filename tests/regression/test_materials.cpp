// Neo-Hookean and Mooney-Rivlin bodies (docs/THEORY.md §12) in whole runs, on 1 and 2 ranks:
// E, L and J of a free tumbling body at large rotation, E through impacts with full stick and
// frictionless contact (bodies of two models together, and with an SVK one), E + D with Coulomb
// friction: each to the Newton tolerance (rtol 1e-12 in these cases) and round-off, asserted at
// 1e-10 as the SVK cases are (test_conservation, test_contact_coulomb).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "run_case.hpp"

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

// The tumbling box (23 rad in 5 s, no loads): E, L, J conserved; its elastic energy is the
// model's (it differs from SVK's by more than 1e-4 of its largest value at some step).
TEST_P(Materials, TumblingBoxConservesEnergyAndMomenta) {
  if (!one_rank()) GTEST_SKIP() << "asserted on 1 rank (test_conservation's case)";
  const auto rows = run_case("tumbling.xml", model_of("block", GetParam(), 1e5, 0.3),
                             "out_tumbling_" + GetParam());
  const auto svk = run_case("tumbling.xml", {}, "out_tumbling_svk_" + GetParam());
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

INSTANTIATE_TEST_SUITE_P(Models, Materials, ::testing::Values("neo-hookean", "mooney-rivlin"),
                         [](const auto& info) {
                           return info.param == "neo-hookean" ? std::string("NeoHookean")
                                                              : std::string("MooneyRivlin");
                         });

}  // namespace
