// Frictionless contact by direct elimination (docs/THEORY.md §5, §6), whole runs.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "body_momenta.hpp"
#include "emcontact/app/simulation.hpp"
#include "kernels/tet4.hpp"
#include "run_case.hpp"
#include "support/long_tests.hpp"

using emc::testing::body_momenta;
using emc::testing::diff3;
using emc::testing::drifts;
using emc::testing::norm3;
using emc::testing::run_case;

// Two deformable blocks colliding off-centre and sliding past each other, no loads, no rigid
// surface: L, J and E conserved to 1e-8 at every step through first contact, sliding and
// release (the contact force is normal, does no work and has no moment about the mid-point).
TEST(Frictionless, TwoDeformableBodiesConserveEJL) {
  const auto rows =
      run_case("two_blocks.xml", {"Contact/A on B/type=frictionless"}, "out_two_blocks_fl");
  const double p_scale = 8.0 * std::hypot(0.5, 0.1) + 8.0 * std::hypot(0.3, 0.1);
  double dL = 0;
  for (const auto& r : rows) dL = std::max(dL, norm3(diff3(r.L, rows[0].L)) / p_scale);
  const auto d = drifts(rows);
  int contact = 0, released_after = 0;
  for (std::size_t k = 1; k < rows.size(); ++k) {
    contact += rows[k].active_contacts > 0;
    released_after += contact > 0 && rows[k].active_contacts == 0;
  }
  std::printf("two blocks frictionless: %d contact steps, %d after release; E %.3e L %.3e J %.3e\n",
              contact, released_after, d.E, dL, d.J);
  EXPECT_GT(contact, 3);
  EXPECT_GT(released_after, 3);  // they separate again
  EXPECT_LT(d.E, 1e-8);
  EXPECT_LT(dL, 1e-8);
  EXPECT_LT(d.J, 1e-8);
}

// The same with the slave's nodes massless (docs/THEORY.md §6.8): the modified mass matrix is
// symmetric and a scalar times I_3 per node pair, so the scheme still conserves E, L and J.
TEST(Frictionless, MasslessSlaveConservesEJL) {
  const auto rows = run_case(
      "two_blocks.xml", {"Contact/A on B/type=frictionless", "Contact/A on B/massless slave=true"},
      "out_two_blocks_fl_massless");
  const double p_scale = 8.0 * std::hypot(0.5, 0.1) + 8.0 * std::hypot(0.3, 0.1);
  double dL = 0;
  int contact = 0;
  for (const auto& r : rows) {
    dL = std::max(dL, norm3(diff3(r.L, rows[0].L)) / p_scale);
    contact += r.active_contacts > 0;
  }
  const auto d = drifts(rows);
  std::printf("two blocks frictionless, massless slave: %d contact steps; E %.3e L %.3e J %.3e\n",
              contact, d.E, dL, d.J);
  EXPECT_GT(contact, 3);
  EXPECT_LT(d.E, 1e-8);
  EXPECT_LT(dL, 1e-8);
  EXPECT_LT(d.J, 1e-8);
}

// A block landing and sliding on a fixed frictionless plane under gravity: the tangential
// momentum (Lx, Ly) and the spin about the normal (Jz) are unchanged, E is conserved, no
// accepted active node pulls (f_N >= 0) and none penetrates.
TEST(Frictionless, BlockSlidingOnPlane) {
  const auto rows = run_case("drop.xml",
                             {"Contact/block on ground/type=frictionless",
                              "Bodies/block/Initial/angular velocity={0.5,0.3,2}"},
                             "out_slide_fl");
  const auto& r0 = rows.front();
  const double mass = 1000 * 0.2 * 0.2 * 0.2, p_scale = mass * 0.3;
  double dLt = 0, dJz = 0, dE = 0, fmin = 0, gmin = 0;
  int contact = 0;
  for (const auto& r : rows) {
    dLt = std::max({dLt, std::fabs(r.L[0] - r0.L[0]), std::fabs(r.L[1] - r0.L[1])});
    dJz = std::max(dJz, std::fabs(r.J[2] - r0.J[2]));
    dE = std::max(dE, std::fabs(r.total - r0.total) / std::fabs(r0.total));
    if (r.active_contacts > 0) {
      ++contact;
      fmin = std::min(fmin, r.normal_force_min);
      gmin = std::min(gmin, r.gap_min);
    }
  }
  std::printf(
      "sliding: %d contact steps; |dLx,dLy| %.3e (of %.3e) |dJz| %.3e (of %.3e) E %.3e; "
      "min f_N %.3e, min gap %.3e\n",
      contact, dLt, p_scale, dJz, std::fabs(r0.J[2]), dE, fmin, gmin);
  EXPECT_GT(contact, 50);
  EXPECT_LT(dLt, 1e-10 * p_scale);
  EXPECT_LT(dJz, 1e-10 * std::fabs(r0.J[2]));
  EXPECT_LT(dE, 1e-8);
  EXPECT_GE(fmin, 0.0);
  EXPECT_GE(gmin, -1e-12 * 0.2);
}

// Newton converges quadratically in a frictionless contact step with a deforming master
// (the exact linearisation of §5, with direct linear solves): order estimates on the last
// iterations above round-off, of whole solves (no search solves, docs/THEORY.md §6.9).
TEST(Frictionless, NewtonQuadraticWithDeformableMaster) {
  emc::app::Options o;
  o.input = std::string(EMC_TEST_DIR) + "/two_blocks.xml";
  o.overrides = {"Contact/A on B/type=frictionless", "Solver/Newton/relative tolerance=1e-15",
                 "Solver/Newton/max iterations=40", "Solver/Linear/type=klu2",
                 "Solver/Newton/search tolerance=0"};
  auto sim = emc::app::setup(o, Tpetra::getDefaultComm());
  double best = 0;
  int checked = 0;
  while (!sim->stepper->finished() && checked < 4) {
    const auto rep = sim->stepper->advance();
    if (rep.contact.active < 5 || rep.contact.resolves > 0) continue;
    const auto& r = sim->newton->last().residuals;
    std::printf("step %ld (%d active):", sim->state.step, rep.contact.active);
    for (double x : r) std::printf(" %.2e", x);
    std::printf("\n");
    for (std::size_t k = 1; k + 1 < r.size(); ++k)
      if (r[k + 1] > 1e-11 * r[0] && r[k] < r[k - 1] && r[k] < 1e-2 * r[0])
        best = std::max(best, std::log(r[k + 1] / r[k]) / std::log(r[k] / r[k - 1]));
    ++checked;
  }
  std::printf("best order estimate %.2f\n", best);
  EXPECT_EQ(checked, 4);
  EXPECT_GT(best, 1.7);
}

// A chain (docs/THEORY.md §3.5): on the three disks a disk's bottom nodes are slaves on the plane
// and masters of the disk behind. The outer slave's X terms carried through the chained master's
// row of P keep Newton quadratic there: the accepted solve of every step with a chain needs at
// most 6 iterations (to the round-off floor, 9-10 decades below the first residual), where the
// terms left out gave linear convergence at a ratio near 0.2 (10-11 iterations). Whole solves
// from u_n: no warm re-solves or search solves (docs/THEORY.md §6.1, §6.9), whose accepted
// solve starts near its solution.
TEST(Frictionless, NewtonFastWhereAMasterIsAnActiveSlave) {
  emc::app::Options o;
  o.input = std::string(EMC_TEST_DIR) + "/../../inputs/three_disks.xml";
  o.overrides = {"Output/every=0",        "Output/plot=false",
                 "Output/progress=false", "Solver/Linear/type=klu2",
                 "Time/end=0.22",         "Solver/Newton/warm re-solves=false"};
  auto sim = emc::app::setup(o, Tpetra::getDefaultComm());
  int chained = 0, worst = 0;
  while (!sim->stepper->finished()) {
    sim->stepper->advance();
    std::set<int> slaves;
    for (const auto& a : sim->state.active) slaves.insert(a.slave);
    bool chain = false;
    for (const auto& a : sim->state.active)
      for (int n : sim->contact->pairs()[a.pair].facets[a.facet]) chain |= slaves.count(n) > 0;
    if (!chain) continue;
    ++chained;
    worst = std::max(worst, sim->newton->last().iterations);
  }
  std::printf("steps with a chain %d, most Newton iterations of their accepted solve %d\n", chained,
              worst);
  EXPECT_GT(chained, 0);
  EXPECT_LE(worst, 6);
}

// The paper's first example (inputs/three_disks.xml): disk 1 passes its momentum to disk 2,
// which passes it to disk 3. Equal rigid masses in a head-on elastic impact exchange their
// momenta exactly; elastic disks keep part of the energy as vibration (about 8% of it after
// the impacts here) and the contact events of these stiff rims are sensitive to round-off in
// which step a node activates (two Newton start guesses gave disk 3 92.6% and 86.8%), so the
// bound is: disk 3 ends with more than 80% of the momentum, the others with less than 15%.
// E, Lx (along the plane) and Jz (about its normal) are conserved, the plane being
// frictionless. Disk 1 also starts 1e-10 slower: its rim then first touches disk 2 inside a
// step rather than exactly at its end; with disk 2's whole boundary as master (as the input
// has it) the rim's edge nodes lie in the planes of disk 2's faces, at gap 0 from them, and
// were never caught before docs/THEORY.md §6.3 (disk 1 passed through disk 2).
class ThreeDisks : public ::testing::TestWithParam<const char*> {};
TEST_P(ThreeDisks, PassTheirMomentum) {
  // the default suite runs the slower disk (which also checks the in-step first touch); the long
  // one both
  if (std::string(GetParam()) == "1" && !emc::testing::long_tests())
    GTEST_SKIP() << "the long run's case (ctest -C long -L long)";
  emc::app::Options o;
  o.input = std::string(EMC_TEST_DIR) + "/../../inputs/three_disks.xml";
  o.overrides = {"Output/every=0", "Output/plot=false", "Output/progress=false",
                 std::string("Bodies/disk1/Initial/velocity={") + GetParam() + ", 0, 0}"};
  auto sim = emc::app::setup(o, Tpetra::getDefaultComm());
  const auto m0 = sim->disc->monitors(*sim->state.u, *sim->state.V);
  const double p0 = body_momenta(*sim)[0][0];
  double dE = 0, dLx = 0, dJz = 0;
  while (!sim->stepper->finished()) {
    sim->stepper->advance();
    const auto m = sim->disc->monitors(*sim->state.u, *sim->state.V);
    const double E0 = m0.kinetic + m0.elastic + m0.potential;
    dE = std::max(dE, std::fabs(m.kinetic + m.elastic + m.potential - E0) / E0);
    dLx = std::max(dLx, std::fabs(m.L[0] - m0.L[0]) / std::fabs(m0.L[0]));
    dJz = std::max(dJz, std::fabs(m.J[2] - m0.J[2]));
  }
  const auto p = body_momenta(*sim);
  std::printf("three disks: px/p0 = %.4f %.4f %.4f; drifts E %.3e Lx %.3e Jz %.3e (of |J| %.3e)\n",
              p[0][0] / p0, p[1][0] / p0, p[2][0] / p0, dE, dLx, dJz, std::fabs(m0.J[1]));
  EXPECT_GT(p[2][0], 0.8 * p0);
  EXPECT_LT(std::fabs(p[0][0]), 0.15 * p0);
  EXPECT_LT(std::fabs(p[1][0]), 0.15 * p0);
  EXPECT_LT(dE, 1e-8);
  EXPECT_LT(dLx, 1e-8);
  EXPECT_LT(dJz, 1e-8 * std::fabs(m0.J[1]));
}
INSTANTIATE_TEST_SUITE_P(Frictionless, ThreeDisks, ::testing::Values("1", "0.9999999999"));
