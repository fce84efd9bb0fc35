// Full stick contact by direct elimination (docs/THEORY.md §4, §6), whole runs.
#include <gtest/gtest.h>

#include <Teuchos_CommHelpers.hpp>
#include <array>
#include <cmath>
#include <limits>

#include "emcontact/app/simulation.hpp"
#include "run_case.hpp"

using emc::testing::drifts;
using emc::testing::norm3;
using emc::testing::run_case;

namespace {

/// Number of separate contact periods (runs of steps with active nodes).
int impacts(const std::vector<emc::output::MonitorRow>& rows) {
  int n = 0;
  for (std::size_t k = 1; k < rows.size(); ++k)
    n += rows[k].active_contacts > 0 && rows[k - 1].active_contacts == 0;
  return n;
}

}  // namespace

// A block dropped on a fixed rigid plane under gravity, through at least two impacts: E is
// conserved at every step to 1e-8 of E0 (the contact force does no work: the slave moves with
// its frozen CPP), and the block leaves the plane between impacts.
TEST(FullStick, BlockDroppedOnRigidPlane) {
  const auto rows = run_case("drop.xml", {}, "out_drop");
  const auto& r0 = rows.front();
  double worst = 0;
  for (const auto& r : rows)
    worst = std::max(worst, std::fabs(r.total - r0.total) / std::fabs(r0.total));
  std::printf("drop: %zu steps, %d impacts, max |E-E0|/|E0| = %.3e\n", rows.size() - 1,
              impacts(rows), worst);
  EXPECT_LT(worst, 1e-8);
  // no active slave node penetrates: the slave moves with its frozen CPP (§4)
  double gmin = 0;
  for (const auto& r : rows)
    if (r.active_contacts > 0) gmin = std::min(gmin, r.gap_min);
  std::printf("drop: most negative gap of an active node %.3e m\n", gmin);
  EXPECT_GE(gmin, -1e-12 * 0.2);
  EXPECT_GE(impacts(rows), 2);  // left the plane between: contact stopped and started again
  // the block bounced: its centre of mass went back up after the first impact
  std::size_t k1 = 1;
  while (k1 < rows.size() && rows[k1].active_contacts == 0) ++k1;
  double zmax_after = -1e300;
  for (std::size_t k = k1; k < rows.size(); ++k) zmax_after = std::max(zmax_after, rows[k].com[2]);
  EXPECT_GT(zmax_after, rows[k1].com[2] + 0.01);
}

// Two deformable blocks with full stick between them and no loads: L conserved to 1e-10
// through the impact, E conserved; J may change (full stick does not conserve it, §4).
TEST(FullStick, TwoDeformableBodiesConserveLinearMomentumAndEnergy) {
  const auto rows = run_case("two_blocks.xml", {}, "out_two_blocks");
  const auto d = drifts(rows);
  // |L0| of the pair can be small: judge L against the sum of the bodies' momenta (8 kg each)
  const double p_scale = 8.0 * std::hypot(0.5, 0.1) + 8.0 * std::hypot(0.3, 0.1);
  double dL = 0;
  for (const auto& r : rows)
    dL = std::max(dL, norm3(emc::testing::diff3(r.L, rows[0].L)) / p_scale);
  int contact_steps = 0;
  for (const auto& r : rows) contact_steps += r.active_contacts > 0;
  std::printf("two blocks: %d contact steps, drifts E %.3e L %.3e (of sum |m v|) J %.3e\n",
              contact_steps, d.E, dL, d.J);
  EXPECT_GT(contact_steps, 3);
  EXPECT_LT(dL, 1e-10);
  EXPECT_LT(d.E, 1e-8);
}

// The dropped block (re-solves at every impact) run two ways, a and b: the same active set at
// every step and the same state to the Newton tolerance (1e-10 relative here, so 1e-8 of the
// energy scale); the Newton iterations of both are printed.
static void expect_same_drop(const std::vector<std::string>& a, const std::vector<std::string>& b,
                             const char* what) {
  const std::string out = std::string("out_drop_") + what;
  const auto ra = run_case("drop.xml", a, out + "_a");
  const auto rb = run_case("drop.xml", b, out + "_b");
  ASSERT_EQ(ra.size(), rb.size());
  long its_a = 0, its_b = 0, resolves = 0;
  double worst = 0;
  const double scale = std::fabs(rb.front().total);
  for (std::size_t k = 0; k < ra.size(); ++k) {
    EXPECT_EQ(ra[k].active_contacts, rb[k].active_contacts) << "step " << k;
    worst = std::max({worst, std::fabs(ra[k].kinetic - rb[k].kinetic) / scale,
                      std::fabs(ra[k].elastic - rb[k].elastic) / scale,
                      norm3(emc::testing::diff3(ra[k].com, rb[k].com)) / 0.2});
    its_a += ra[k].newton_iterations;
    its_b += rb[k].newton_iterations;
    resolves += rb[k].contact_resolves;
  }
  std::printf(
      "drop, %s: %ld re-solves; Newton iterations %ld (a) against %ld (b); largest "
      "difference %.3e\n",
      what, resolves, its_a, its_b, worst);
  EXPECT_GT(resolves, 0);  // the comparison exercised the re-solves
  EXPECT_LT(worst, 1e-8);
}

// docs/THEORY.md §6.1-§6.2: a re-solve of the active-set loop started from the last solution
// (the entries activated since moved onto their constraint, Solver/Newton/warm re-solves)
// reaches the solution a start from u_n reaches: full stick's constraints are linear in the
// positions with xi frozen, so the step's solution for a given set is unique.
TEST(FullStick, WarmResolvesReachTheColdSolution) {
  expect_same_drop({"Solver/Newton/search tolerance=0"}, {"Solver/Newton/warm re-solves=false"},
                   "warm");
}

// docs/THEORY.md §6.9: the active-set loop's search solves (to 1e-4 of the step's reference
// residual, Solver/Newton/search tolerance) and the final solve of the settled set reach the
// solution of whole solves.
TEST(FullStick, SearchSolvesReachTheWholeSolution) {
  expect_same_drop({}, {"Solver/Newton/search tolerance=0"}, "search");
}

// docs/THEORY.md §6.8: with the slave surface massless the initial velocity (a translation and
// a spin about the centre of the modified mass) carries exactly the body's m v (8 kg times
// 0.3 m/s along x), and energy is conserved through the impacts as with the consistent mass.
TEST(FullStick, MasslessSlaveKeepsMomentumAndEnergy) {
  const auto rows =
      run_case("drop.xml", {"Contact/block on ground/massless slave=true"}, "out_drop_massless");
  const auto& r0 = rows.front();
  double worst = 0;
  for (const auto& r : rows)
    worst = std::max(worst, std::fabs(r.total - r0.total) / std::fabs(r0.total));
  std::printf(
      "drop, massless slave: L0 = (%.15g, %.3g, %.3g), %d impacts, max |E-E0|/|E0| = %.3e\n",
      r0.L[0], r0.L[1], r0.L[2], impacts(rows), worst);
  EXPECT_NEAR(r0.L[0], 8.0 * 0.3, 1e-12);
  EXPECT_NEAR(r0.L[1], 0.0, 1e-12);
  EXPECT_NEAR(r0.L[2], 0.0, 1e-12);
  EXPECT_LT(worst, 1e-8);
  EXPECT_GE(impacts(rows), 2);
}

namespace {

/// The setup of `xml` with `sets` (no step taken).
std::unique_ptr<emc::app::Simulation> setup_case(const std::string& xml,
                                                 std::vector<std::string> sets) {
  emc::app::Options o;
  o.input = std::string(EMC_TEST_DIR) + "/" + xml;
  o.overrides = std::move(sets);
  return emc::app::setup(o, Tpetra::getDefaultComm());
}

/// The moments of body b's mass matrix (docs/THEORY.md §6.8), from Discretization::apply_mass:
/// G_pq = phi_p^T M phi_q with phi = (1, X, Y, Z) on the body's nodes (one component; M is a
/// scalar times I_3 per node pair): G_00 the mass, G_0i the first moments, G_ij the second.
std::array<std::array<double, 4>, 4> mass_moments(const emc::app::Simulation& sim, int b) {
  const auto& disc = *sim.disc;
  const auto& body = sim.model.bodies[b];
  std::array<emc::Vector, 4> phi = {emc::Vector(disc.owned_map()), emc::Vector(disc.owned_map()),
                                    emc::Vector(disc.owned_map()), emc::Vector(disc.owned_map())};
  for (int p = 0; p < 4; ++p) {
    auto h = phi[p].getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (std::size_t i = 0; i < h.extent(0); ++i) {
      const emc::GO dof = disc.owned_map()->getGlobalElement(static_cast<emc::LO>(i));
      const long long n = dof / 3;
      const bool mine = dof % 3 == 0 && n >= body.node_begin && n < body.node_end;
      h(i, 0) = !mine ? 0.0 : p == 0 ? 1.0 : sim.model.X[3 * n + p - 1];
    }
  }
  std::array<std::array<double, 4>, 4> G{};
  emc::Vector Mphi(disc.owned_map());
  for (int q = 0; q < 4; ++q) {
    disc.apply_mass(phi[q], Mphi);
    for (int p = 0; p < 4; ++p) G[p][q] = phi[p].dot(Mphi);
  }
  return G;
}

}  // namespace

// docs/THEORY.md §6.8: moving the slave surface's mass onto the nodes behind it keeps the body's
// mass, centre of mass and inertia: every moment of M' up to the second equals the consistent
// mass's to round-off (1e-12 of sqrt(G_pp G_qq)), for a whole-body slave (the dropped block),
// its bottom face, and the end face of a bar (two elements across).
TEST(FullStick, MasslessSlaveKeepsTheMassMoments) {
  struct Case {
    const char* xml;
    std::vector<std::string> sets;
    int body;
  };
  const std::vector<Case> cases = {
      {"drop.xml", {"Contact/block on ground/massless slave=true"}, 0},
      {"drop.xml",
       {"Contact/block on ground/massless slave=true", "Contact/block on ground/slave=block/zmin"},
       0},
      {"bars.xml", {"Contact/A on B/massless slave=true", "Contact/A on B/slave=A/zmax"}, 0},
      {"two_blocks.xml", {"Contact/A on B/massless slave=true"}, 0}};
  for (const auto& c : cases) {
    auto without = c.sets;
    without.erase(without.begin());  // the same pair, the consistent mass
    const auto G = mass_moments(*setup_case(c.xml, c.sets), c.body);
    const auto G0 = mass_moments(*setup_case(c.xml, without), c.body);
    double worst = 0;
    for (int p = 0; p < 4; ++p)
      for (int q = 0; q < 4; ++q)
        worst = std::max(worst, std::fabs(G[p][q] - G0[p][q]) / std::sqrt(G0[p][p] * G0[q][q]));
    std::printf("%s %s: mass %.6g (consistent %.6g), centre z %.6f (%.6f), worst moment %.2e\n",
                c.xml, c.sets.back().c_str(), G[0][0], G0[0][0], G[0][3] / G[0][0],
                G0[0][3] / G0[0][0], worst);
    EXPECT_LT(worst, 1e-12) << c.xml << " " << c.sets.back();
  }
}

// docs/THEORY.md §6.8: the initial velocity of a translating and spinning block (drop.xml: v and
// omega about the centre of mass) carries the same L and J (about the origin) and the same
// kinetic energy with the slave surface massless as with the consistent mass, to 1e-9; the
// centre of mass is the same.
TEST(FullStick, MasslessSlaveKeepsTheInitialMomenta) {
  const std::vector<std::string> spin = {"Bodies/block/Initial/angular velocity={0.5,-0.3,2}"};
  auto with = spin;
  with.push_back("Contact/block on ground/massless slave=true");
  auto a = setup_case("drop.xml", with), b = setup_case("drop.xml", spin);
  const auto m = a->disc->monitors(*a->state.u, *a->state.V);
  const auto m0 = b->disc->monitors(*b->state.u, *b->state.V);
  const double L0 = std::sqrt(m0.L[0] * m0.L[0] + m0.L[1] * m0.L[1] + m0.L[2] * m0.L[2]);
  const double J0 = std::sqrt(m0.J[0] * m0.J[0] + m0.J[1] * m0.J[1] + m0.J[2] * m0.J[2]);
  const double size = 0.2;  // the block's edge: the scale of the centre of mass
  double dL = 0, dJ = 0, dc = 0;
  for (int i = 0; i < 3; ++i) {
    dL = std::max(dL, std::fabs(m.L[i] - m0.L[i]) / L0);
    dJ = std::max(dJ, std::fabs(m.J[i] - m0.J[i]) / J0);
    dc = std::max(dc, std::fabs(m.moment[i] / m.mass - m0.moment[i] / m0.mass) / size);
  }
  const double dK = std::fabs(m.kinetic - m0.kinetic) / m0.kinetic;
  std::printf("massless slave at t = 0: L %.2e, J %.2e, K %.2e, centre of mass %.2e (relative)\n",
              dL, dJ, dK, dc);
  EXPECT_LT(dL, 1e-9);
  EXPECT_LT(dJ, 1e-9);
  EXPECT_LT(dK, 1e-9);
  EXPECT_LT(dc, 1e-9);
}

namespace {

/// The smallest entry of every rank's v (infinity if none). Collective.
double global_min(const std::vector<double>& v) {
  double mine = std::numeric_limits<double>::infinity(), all = mine;
  for (double x : v) mine = std::min(mine, x);
  Teuchos::reduceAll(*Tpetra::getDefaultComm(), Teuchos::REDUCE_MIN, 1, &mine, &all);
  return all;
}

/// Steps the case to its end; per step, the monitors' normal_force_min against the smallest
/// normal force of the nodes active at the accepted solve (SettledSet::force, those released at
/// the end of the step included; docs/THEORY.md §6.5): the smallest and largest value over the
/// steps with active nodes, the mismatches, and the steps without active nodes where it is not 0.
struct ForceMin {
  double lowest = std::numeric_limits<double>::infinity(), highest = -lowest;
  int active_steps = 0, mismatches = 0, nonzero_without_contact = 0;
};
ForceMin step_force_min(const std::string& xml, std::vector<std::string> sets) {
  auto sim = setup_case(xml, std::move(sets));
  ForceMin r;
  while (!sim->stepper->finished()) {
    const auto rep = sim->stepper->advance();
    const double f = rep.contact.normal_force_min;
    if (rep.contact.active == 0) {
      r.nonzero_without_contact += f != 0;
      continue;
    }
    ++r.active_steps;
    r.mismatches += f != global_min(sim->state.contact_force);
    r.lowest = std::min(r.lowest, f);
    r.highest = std::max(r.highest, f);
  }
  return r;
}

}  // namespace

// docs/THEORY.md §6.5: normal_force_min is the smallest f_N of the nodes active at the accepted
// solve (f_N > 0 compressive), 0 in a step without one. A block settled on the rigid ground:
// positive at every step, the least loaded node's force (its monitors column too); the first
// impacts of the three disks (inputs/three_disks.xml, frictionless; MUMPS, which runs on any
// number of ranks, for its UMFPACK), where nodes released in
// tension and re-activated in the same step are still in tension at the accepted solve and leave
// at the end of the step (docs/THEORY.md §6.4): negative in those steps.
TEST(FullStick, NormalForceMinIsTheSmallestNormalForce) {
  const std::vector<std::string> rest = {"Bodies/block/Mesh/lower corner={-0.1, -0.1, 0}",
                                         "Bodies/block/Mesh/upper corner={0.1, 0.1, 0.2}",
                                         "Bodies/block/Initial/velocity={0, 0, 0}",
                                         "Bodies/block/Initial/angular velocity={0, 0, 0}",
                                         "Time/settle steps=100",
                                         "Time/end=0.05"};
  const ForceMin block = step_force_min("drop.xml", rest);
  const ForceMin disks =
      step_force_min("../../inputs/three_disks.xml",
                     {"Output/every=0", "Time/end=0.12", "Solver/Linear/type=mumps"});
  std::printf(
      "resting block: %d steps in contact, normal_force_min in [%.4g, %.4g], %d mismatches\n"
      "three disks: %d steps in contact, normal_force_min in [%.4g, %.4g], %d mismatches\n",
      block.active_steps, block.lowest, block.highest, block.mismatches, disks.active_steps,
      disks.lowest, disks.highest, disks.mismatches);
  EXPECT_EQ(block.active_steps, 10);
  EXPECT_EQ(block.mismatches, 0);
  EXPECT_GT(block.lowest, 0);
  EXPECT_GT(disks.active_steps, 0);
  EXPECT_EQ(disks.mismatches, 0);
  EXPECT_EQ(disks.nonzero_without_contact, 0);
  EXPECT_LT(disks.lowest, 0);  // a node in tension at the accepted solve
  // the column of monitors.csv is the same value
  const auto rows = run_case("drop.xml", rest, "out_rest_force_min");
  for (std::size_t k = 1; k < rows.size(); ++k) EXPECT_GT(rows[k].normal_force_min, 0) << k;
}
