// Contact that never sinks or glues (docs/THEORY.md §6.3-§6.6): flush faces of equal size,
// slave nodes on master edges and vertices, a stack at rest, a block crossing a joint. Every
// accepted step is checked against a brute-force penetration depth (the slave nodes against the
// face planes of the convex master body, independent of the contact search), and each
// head-on impact against the same impact with an oversized master face.
#include <gtest/gtest.h>

#include <Teuchos_CommHelpers.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "body_momenta.hpp"
#include "emcontact/app/simulation.hpp"
#include "emcontact/contact/pairs.hpp"
#include "emcontact/mesh/body_mesh.hpp"
#include "kernels/facet.hpp"
#include "support/long_tests.hpp"
#include "support/replicate.hpp"

using emc::testing::body_momenta;
using emc::testing::long_tests;

namespace {

/// The deepest penetration (>= 0) of the pair's slave nodes into the master body in
/// configuration x: a deformable master (a box here, convex) by the largest signed distance to
/// its boundary's facet planes (inside when all are negative), a rigid surface by the gap to
/// the facet whose CPP is inside.
double penetration(const emc::app::Simulation& sim, const emc::contact::Pair& p,
                   const std::vector<double>& x) {
  const auto& m = sim.model;
  const auto& mb = m.bodies[p.master_body];
  std::vector<std::array<int, 3>> facets;
  if (mb.rigid) {
    facets = p.facets;
  } else {
    for (const auto& t : emc::mesh::boundary_triangles(mb.mesh))
      facets.push_back({mb.node_begin + t[0], mb.node_begin + t[1], mb.node_begin + t[2]});
  }
  double deepest = 0;
  for (int s : p.slaves) {
    double worst = -1e300, rigid_gap = 0;
    for (const auto& f : facets) {
      double xm[3][3], xi[2], gap;
      for (int a = 0; a < 3; ++a)
        for (int i = 0; i < 3; ++i) xm[a][i] = x[3 * f[a] + i];
      if (!emc::kernels::facet_cpp(&x[3 * s], xm, xi, gap)) continue;
      if (mb.rigid) {
        if (emc::kernels::facet_outside(xi) <= 1e-12) rigid_gap = std::min(rigid_gap, gap);
      } else {
        worst = std::max(worst, gap);
      }
    }
    deepest = std::max(deepest, mb.rigid ? -rigid_gap : -worst);
  }
  return deepest;
}

/// x of each body's node centroid and z of body 1's (collective).
void centroids(const emc::app::Simulation& sim, std::vector<double>& xc, double& z1) {
  const auto x =
      emc::contact::positions(sim.model, emc::testing::replicate(*sim.disc, *sim.state.u));
  xc.assign(sim.model.bodies.size(), 0.0);
  for (std::size_t b = 0; b < sim.model.bodies.size(); ++b) {
    const auto& body = sim.model.bodies[b];
    if (body.rigid || body.node_end <= body.node_begin) continue;
    double sx = 0, sz = 0;
    for (int n = body.node_begin; n < body.node_end; ++n) {
      sx += x[3 * n];
      sz += x[3 * n + 2];
    }
    xc[b] = sx / (body.node_end - body.node_begin);
    if (b == 1) z1 = sz / (body.node_end - body.node_begin);
  }
}

/// z (dof 3 n + 2) and x, y: the largest |u - u0| of each, over every rank (collective).
void drift(const emc::Vector& u, const emc::Vector& u0, double& z, double& xy) {
  const auto a = u.getLocalViewHost(Tpetra::Access::ReadOnly);
  const auto b = u0.getLocalViewHost(Tpetra::Access::ReadOnly);
  const auto& map = *u.getMap();
  double mine[2] = {0, 0}, most[2];
  for (std::size_t i = 0; i < a.extent(0); ++i) {
    const double d = std::fabs(a(i, 0) - b(i, 0));
    auto& m = map.getGlobalElement(static_cast<emc::LO>(i)) % 3 == 2 ? mine[0] : mine[1];
    m = std::max(m, d);
  }
  Teuchos::reduceAll(*map.getComm(), Teuchos::REDUCE_MAX, 2, mine, most);
  z = std::max(z, most[0]);
  xy = std::max(xy, most[1]);
}

struct CaseRun {
  int first = -1, last = -1;  ///< first and last step with an active node
  double depth = 0;           ///< deepest penetration over the run (brute force)
  double dE = 0;  ///< max |E - E0| / scale, scale = max(|E0|, the largest K + U + |P| of the run)
  double newton = 0;  ///< Newton iterations per step
  int tension = 0;    ///< steps accepted with f_N < 0 and no re-activated node
  int changes = 0;    ///< steps whose active count differs from the step before
  int resolves = 0;   ///< steps after the first whose active-set loop solved again (§6, §11.4)
  int first_resolves = 0;  ///< re-solves of the first step
  int unreported = 0;      ///< steps whose field-output contact nodes differ from the count
  double drift_z = 0, drift_xy = 0;  ///< largest |u - u(t = 0)| over z dofs, over x and y dofs
  std::vector<std::array<double, 3>> p0, p;  ///< body momenta at the start and the end
  std::vector<double> com0, com;             ///< x of each body's node centroid, start and end
  double top_z0 = 0, top_z = 0;              ///< z of body 1's node centroid, start and end
  long steps = 0;
};

CaseRun run_case(const std::string& xml, std::vector<std::string> sets) {
  emc::app::Options o;
  o.input = std::string(EMC_TEST_DIR) + "/" + xml;
  o.overrides = std::move(sets);
  auto sim = emc::app::setup(o, Tpetra::getDefaultComm());
  CaseRun r;
  r.p0 = body_momenta(*sim);
  centroids(*sim, r.com0, r.top_z0);
  const auto m0 = sim->disc->monitors(*sim->state.u, *sim->state.V);
  const double E0 = m0.kinetic + m0.elastic + m0.potential;
  const emc::Vector u0(*sim->state.u, Teuchos::Copy);
  long its = 0;
  int last_active = 0;
  double dE_abs = 0, scale = std::fabs(E0);
  while (!sim->stepper->finished()) {
    const auto rep = sim->stepper->advance();
    const long n = sim->state.step;
    its += rep.newton_iterations;
    if (rep.contact.active > 0) {
      if (r.first < 0) r.first = n;
      r.last = n;
    }
    r.changes += rep.contact.active != last_active;
    r.resolves += n > 1 && rep.contact.resolves > 0;
    if (n == 1) r.first_resolves = rep.contact.resolves;
    int mine = static_cast<int>(sim->state.contact_nodes.size()), all = 0;  // what fields show
    Teuchos::reduceAll(*sim->disc->comm(), Teuchos::REDUCE_SUM, 1, &mine, &all);
    r.unreported += all != rep.contact.active;
    last_active = rep.contact.active;
    r.tension += rep.contact.normal_force_min < 0 && rep.contact.reactivated == 0;
    const auto x =
        emc::contact::positions(sim->model, emc::testing::replicate(*sim->disc, *sim->state.u));
    for (const auto& p : sim->contact->pairs())
      r.depth = std::max(r.depth, penetration(*sim, p, x));
    const auto m = sim->disc->monitors(*sim->state.u, *sim->state.V);
    dE_abs = std::max(dE_abs, std::fabs(m.kinetic + m.elastic + m.potential - E0));
    drift(*sim->state.u, u0, r.drift_z, r.drift_xy);
    scale = std::max(scale, m.kinetic + m.elastic + std::fabs(m.potential));
  }
  r.dE = dE_abs / scale;
  r.steps = sim->state.step;
  centroids(*sim, r.com, r.top_z);
  r.newton = double(its) / r.steps;
  r.p = body_momenta(*sim);
  return r;
}

void print(const char* name, const CaseRun& r) {
  if (Tpetra::getDefaultComm()->getRank() != 0) return;
  std::printf(
      "%s: contact steps %d..%d, depth %.3e, E %.2e, Newton %.2f/step, tension steps %d, "
      "active-count changes %d, pz(A) %.5f -> %.5f\n",
      name, r.first, r.last, r.depth, r.dE, r.newton, r.tension, r.changes, r.p0[0][2], r.p[0][2]);
}

/// The bar B of bars.xml with its end face 2% wider on each side (1.04 times the area) and its
/// young and density divided by 1.04 (the same wave speed and impedance: the same 1D impact),
/// meshed at 0.52 (two elements across, as the slave).
std::vector<std::string> oversized(std::vector<std::string> sets) {
  sets.insert(sets.end(), {"Bodies/B/Mesh/lower corner={-0.02, -0.02, 4.1}",
                           "Bodies/B/Mesh/upper corner={1.02, 1.02, 8.1}",
                           "Bodies/B/Mesh/size=0.52", "Bodies/B/Material/young=0.96153846153846",
                           "Bodies/B/Material/density=0.96153846153846"});
  return sets;
}

}  // namespace

// Two equal bars end face to end face (bars.xml): with the whole body B or its end face as
// master, both contact laws, the impact matches the oversized-master control: the same first
// and last contact step (within one), the same rebound (momentum of A within 2% of the
// exchange), Newton iterations within 20%; no slave node deeper than the closing speed times
// dt at any step; no tension beyond the bounded re-activation; E to 1e-10.
class EqualBars : public ::testing::TestWithParam<std::tuple<const char*, const char*>> {};
TEST_P(EqualBars, MatchTheOversizedMaster) {
  const std::string type = std::get<0>(GetParam()), master = std::get<1>(GetParam());
  const std::vector<std::string> sets = {"Contact/A on B/type=" + type,
                                         "Contact/A on B/master=" + master};
  const CaseRun eq = run_case("bars.xml", sets);
  const CaseRun big = run_case(
      "bars.xml", oversized({"Contact/A on B/type=" + type, "Contact/A on B/master=B/zmin"}));
  print(("equal " + type + " " + master).c_str(), eq);
  print(("oversized " + type).c_str(), big);
  const double bound = 0.02 * 0.1, exchange = std::fabs(eq.p0[0][2] - eq.p0[1][2]);
  EXPECT_LE(eq.depth, bound);
  EXPECT_LE(big.depth, bound);
  EXPECT_NEAR(eq.first, big.first, 1);
  EXPECT_NEAR(eq.last, big.last, 1);
  EXPECT_NEAR(eq.p[0][2], big.p[0][2], 0.02 * exchange);
  EXPECT_LT(eq.p[0][2], 0);  // A rebounds
  // Newton within 20% of the control, asserted on 1 rank (measured 16% frictionless, 20% full
  // stick). On 2 ranks round-off moves some activations by a step, and with them the end of the
  // three-step cycles of the face's nodes that sit on master vertices (docs/THEORY.md §6.4, "The
  // reflected velocity stays while the node is held"; in the control too): measured 22% and
  // 28%, printed, not asserted.
  if (Tpetra::getDefaultComm()->getSize() == 1) EXPECT_LE(eq.newton, 1.2 * big.newton);
  EXPECT_EQ(eq.tension, 0);
  EXPECT_EQ(eq.unreported, 0);  // the field output covers the nodes the monitors count
  EXPECT_LT(eq.dE, 1e-10);
  EXPECT_LT(big.dE, 1e-10);
}
INSTANTIATE_TEST_SUITE_P(Robust, EqualBars,
                         ::testing::Combine(::testing::Values("frictionless", "full stick"),
                                            ::testing::Values("B", "B/zmin")));

// The equal bars with the slave's end face massless (docs/THEORY.md §6.8), against the
// oversized control with the same setting: the face's nodes on master vertices do not cycle
// (as many active-count changes as the control's, up to two), and the Newton iterations per
// step are within 20% of the control's on 1 and on 2 ranks; the contact ends within a step of
// the 1D theory's t = 13; the other checks as above.
class EqualBarsMassless : public ::testing::TestWithParam<const char*> {};
TEST_P(EqualBarsMassless, MatchTheOversizedMasterOnEveryRank) {
  const std::string type = GetParam();
  const std::vector<std::string> sets = {
      "Contact/A on B/type=" + type, "Contact/A on B/slave=A/zmax",
      "Contact/A on B/massless slave=true", "Contact/A on B/master=B/zmin"};
  const CaseRun eq = run_case("bars.xml", sets), big = run_case("bars.xml", oversized(sets));
  print(("equal, massless slave, " + type).c_str(), eq);
  print(("oversized, massless slave, " + type).c_str(), big);
  std::printf("active-count changes %d and %d, re-solves %d and %d\n", eq.changes, big.changes,
              eq.resolves, big.resolves);
  const double bound = 0.02 * 0.1, exchange = std::fabs(eq.p0[0][2] - eq.p0[1][2]);
  EXPECT_LE(eq.depth, bound);
  EXPECT_NEAR(eq.first, big.first, 1);
  EXPECT_NEAR(eq.last, big.last, 1);
  EXPECT_NEAR(eq.last, 130, 1);  // t = 5 + 2 L / c = 13, dt = 0.1
  EXPECT_NEAR(eq.p[0][2], big.p[0][2], 0.02 * exchange);
  EXPECT_LT(eq.p[0][2], 0);
  EXPECT_LE(eq.changes, big.changes + 2);
  EXPECT_LE(eq.newton, 1.2 * big.newton);
  EXPECT_EQ(eq.tension, 0);
  EXPECT_EQ(eq.unreported, 0);
  EXPECT_LT(eq.dE, 1e-10);
  EXPECT_LT(big.dE, 1e-10);
}
INSTANTIATE_TEST_SUITE_P(Robust, EqualBarsMassless,
                         ::testing::Values("frictionless", "full stick"));

// A bar hitting a rigid square of exactly its end face's size, against a square twice as wide:
// the same contact steps and rebound, no penetration beyond the closing speed times dt.
class BarOnWall : public ::testing::TestWithParam<const char*> {};
TEST_P(BarOnWall, MatchesTheWideWall) {
  auto wall = [&](const char* half) {
    return std::vector<std::string>{"Bodies/B/Mesh/type=plane",
                                    "Bodies/B/Mesh/center={0.5, 0.5, 4.1}",
                                    "Bodies/B/Mesh/axis={0, 0, -1}",
                                    std::string("Bodies/B/Mesh/half width=") + half,
                                    "Bodies/B/Mesh/size=0.5",
                                    "Bodies/B/Initial/velocity={0, 0, 0}",
                                    "Time/end=20",
                                    std::string("Contact/A on B/type=") + GetParam()};
  };
  const CaseRun eq = run_case("bars.xml", wall("0.5")), big = run_case("bars.xml", wall("1.0"));
  print("bar on equal wall", eq);
  print("bar on wide wall", big);
  EXPECT_LE(eq.depth, 0.01 * 0.1);
  EXPECT_NEAR(eq.first, big.first, 1);
  EXPECT_NEAR(eq.last, big.last, 1);
  EXPECT_NEAR(eq.p[0][2], big.p[0][2], 0.02 * std::fabs(eq.p0[0][2]));
  EXPECT_LT(eq.p[0][2], 0);
  EXPECT_LE(eq.newton, 1.2 * big.newton);
  EXPECT_EQ(eq.tension, 0);
  EXPECT_LT(eq.dE, 1e-10);
}
INSTANTIATE_TEST_SUITE_P(Robust, BarOnWall, ::testing::Values("frictionless", "full stick"));

// A cube stacked on a cube of the same size, the lower one on a rigid square of its size, with
// gravity switched on at t = 0 on the undeformed mesh (stack.xml), against the same stack on a
// lower block 1.5 times wider and a wider square: no node sinks (deeper than g dt^2, what one
// step of free fall brings), the stack does not creep (the top cube's centroid stays within
// twice its static drop: a suddenly applied load rings between none and twice the static
// deflection), and the active set changes no more often than on the oversized master. The
// ring opens the upper interface at its troughs (docs/THEORY.md §6.7), in both; at rest is
// SettledStack below. 300 steps in the long run; 50 in the default one, six periods of the
// stack's axial ringing (4 H / c = 0.08 s for the 2 m column, c = sqrt(E / rho) = 100 m/s), so
// the ring's troughs, its releases and catches, come several times.
class Stack : public ::testing::TestWithParam<const char*> {};
TEST_P(Stack, SuddenLoadLikeTheOversizedStack) {
  const std::string end = long_tests() ? "Time/end=3" : "Time/end=0.5";
  const std::vector<std::string> sets = {end, std::string("Contact/top on low/type=") + GetParam()};
  auto wide = sets;
  wide.insert(wide.end(), {"Bodies/low/Mesh/lower corner={-0.25, -0.25, 0}",
                           "Bodies/low/Mesh/upper corner={1.25, 1.25, 1}",
                           "Bodies/ground/Mesh/half width=0.75"});
  const CaseRun eq = run_case("stack.xml", sets), big = run_case("stack.xml", wide);
  print("stack", eq);
  print("stack on a wide block", big);
  EXPECT_LE(eq.depth, 9.81 * 0.01 * 0.01);
  EXPECT_LE(big.depth, 9.81 * 0.01 * 0.01);
  // static drop of the top cube's centroid, as uniaxial columns of height H = 1: the lower cube
  // under the top's weight and its own (1.5 rho g H^2 / E) and the top's lower half (0.375)
  const double rho = 100, g = 9.81, H = 1, E = 1e6, static_drop = 1.875 * rho * g * H * H / E;
  EXPECT_LT(std::fabs(eq.top_z - eq.top_z0), 2 * static_drop);
  EXPECT_LE(eq.changes, 1.5 * big.changes + 10);
  EXPECT_LT(eq.dE, 1e-10);
}
INSTANTIATE_TEST_SUITE_P(Robust, Stack, ::testing::Values("full stick", "frictionless"));

// The same stack settled to static equilibrium under gravity before t = 0 (Time/settle steps,
// docs/THEORY.md §6.7) stays at rest: every slave node of the two interfaces is active from the
// first step and stays so (the active set never changes: no chattering), no node sinks, nothing
// is in tension, and the bodies do not move vertically by more than 1e-3 of the static drop (no
// creeping). Full stick: 1000 steps on 1 rank, measured still to the last bit (Newton converges
// at its start iterate). Frictionless: 300 steps. The discrete interface leaves a net torque
// about z of 7e-7 of the top's weight times its size, which a frictionless interface cannot
// resist: the top cube twists (its corners move 1.7e-4 m sideways in 300 steps, printed); over
// 1000 steps they move 1e-3 m, pass the lower cube's edges at t = 8.4 and are released there.
// Coulomb (mu = 0.3), 300 steps: settling lets the interfaces' edge nodes slip until their
// forces are inside the cone (docs/THEORY.md §11.4), so no step changes an entry's state or
// solves again (a sticking entry outside the cone would slide, one sliding would stop), and
// full stick's assertions hold too.
class SettledStack : public ::testing::TestWithParam<const char*> {};
TEST_P(SettledStack, StaysAtRest) {
  const std::string type = GetParam();
  const bool longest = Tpetra::getDefaultComm()->getSize() == 1 && type == "full stick";
  // the step counts above are the long run's; the default run takes 100 steps of each case (the
  // active set is complete from the first step: a chattering node or a creeping body shows)
  const char* end = !long_tests() ? "Time/end=1" : longest ? "Time/end=10" : "Time/end=3";
  std::vector<std::string> sets = {end, "Time/settle steps=100", "Contact/top on low/type=" + type,
                                   "Contact/low on ground/type=" + type};
  if (type == "coulomb")
    sets.insert(sets.end(), {"Contact/top on low/friction coefficient=0.3",
                             "Contact/low on ground/friction coefficient=0.3"});
  const CaseRun r = run_case("stack.xml", sets);
  print(("settled stack " + type).c_str(), r);
  if (Tpetra::getDefaultComm()->getRank() == 0)
    std::printf("settled stack %s: largest |du| vertical %.3e, horizontal %.3e, re-solves %d\n",
                type.c_str(), r.drift_z, r.drift_xy, r.resolves);
  const double rho = 100, g = 9.81, H = 1, E = 1e6, static_drop = 1.875 * rho * g * H * H / E;
  EXPECT_EQ(r.first, 1);
  EXPECT_EQ(r.changes, 1);  // from none to all at the first step, then never
  EXPECT_EQ(r.tension, 0);
  EXPECT_LE(r.depth, 9.81 * 0.01 * 0.01);
  EXPECT_LE(r.drift_z, 1e-3 * static_drop);
  EXPECT_LT(r.dE, 1e-10);
  if (type != "frictionless") EXPECT_EQ(r.resolves, 0);
}
INSTANTIATE_TEST_SUITE_P(Robust, SettledStack,
                         ::testing::Values("full stick", "frictionless", "coulomb"));

// The same stack 10^4 times stiffer (young = 1e10), settled: the static strain is 1e-8, and the
// Coulomb entries that slipped during settling end on the cone outside its relative round-off
// (|f_T| up to 1 + 8e-8 times mu f_N) by less than a slip the solve can resolve (docs/THEORY.md
// §11.4). Every step is solved once (no re-solve from the first step on: before, each step slid
// those entries, found their slip 0, returned them to stick, five times: 10 re-solves per step),
// nothing moves vertically by more than 1e-3 of the static drop, the active set never changes,
// E to 1e-10; with full stick the same. 50 steps.
class SettledStiffStack : public ::testing::TestWithParam<const char*> {};
TEST_P(SettledStiffStack, SolvesEveryStepOnce) {
  const std::string type = GetParam();
  std::vector<std::string> sets = {"Time/end=0.5",
                                   "Time/settle steps=100",
                                   "Bodies/top/Material/young=1e10",
                                   "Bodies/low/Material/young=1e10",
                                   "Contact/top on low/type=" + type,
                                   "Contact/low on ground/type=" + type};
  if (type == "coulomb")
    sets.insert(sets.end(), {"Contact/top on low/friction coefficient=0.3",
                             "Contact/low on ground/friction coefficient=0.3"});
  const CaseRun r = run_case("stack.xml", sets);
  print(("settled stiff stack " + type).c_str(), r);
  if (Tpetra::getDefaultComm()->getRank() == 0)
    std::printf(
        "settled stiff stack %s: re-solves %d in the first step, %d steps after it; "
        "largest |du| vertical %.3e, horizontal %.3e\n",
        type.c_str(), r.first_resolves, r.resolves, r.drift_z, r.drift_xy);
  const double rho = 100, g = 9.81, H = 1, E = 1e10, static_drop = 1.875 * rho * g * H * H / E;
  EXPECT_EQ(r.first_resolves, 0);
  EXPECT_EQ(r.resolves, 0);
  EXPECT_EQ(r.first, 1);
  EXPECT_EQ(r.changes, 1);
  EXPECT_EQ(r.tension, 0);
  EXPECT_LE(r.drift_z, 1e-3 * static_drop);
  EXPECT_LT(r.dE, 1e-10);
}
INSTANTIATE_TEST_SUITE_P(Robust, SettledStiffStack, ::testing::Values("full stick", "coulomb"));

// Newton's round-off floor counts the frictionless projections' round-off (docs/THEORY.md
// §1.6): the suddenly loaded stack with a frictionless upper interface and the coloured scatter
// runs its 300 steps (50 in the default run) without cutting dt. With the floor of the element
// terms alone it cut dt on 2 ranks (315 steps, 5.74 Newton iterations per step against 4.03;
// before E was computed from H it stalled at step 35).
TEST(Robust, ColouredFrictionlessStackReachesItsEnd) {
  const int steps = long_tests() ? 300 : 50;
  const CaseRun r = run_case(
      "stack.xml", {"Time/end=" + std::to_string(steps / 100.0),
                    "Contact/top on low/type=frictionless", "Solver/Assembly/scatter=coloured"});
  print("coloured frictionless stack", r);
  EXPECT_EQ(r.steps, steps);  // no step cut
  EXPECT_LE(r.depth, 9.81 * 0.01 * 0.01);
  EXPECT_LT(r.dE, 1e-10);
}

// A block sliding (frictionless, under gravity) across the joint between two flush blocks
// clamped at their bottoms (joint.xml): it crosses without snagging (its horizontal momentum
// stays within 2% of the start: only the tilt of the deforming top faces acts along x) and
// without sinking (no node deeper than g dt^2).
TEST(Robust, SlidesAcrossAFlushJoint) {
  const CaseRun r = run_case("joint.xml", {});
  print("joint", r);
  const double px0 = r.p0[2][0], px = r.p[2][0];
  if (Tpetra::getDefaultComm()->getRank() == 0)
    std::printf("slider px %.6f -> %.6f, x of its centre %.4f -> %.4f\n", px0, px, r.com0[2],
                r.com[2]);
  EXPECT_GT(r.com[2], 1.1);  // its centre has crossed the joint at x = 1 (it starts at 0.35)
  EXPECT_NEAR(px, px0, 0.02 * px0);
  EXPECT_LE(r.depth, 9.81 * 0.01 * 0.01);
  EXPECT_LT(r.dE, 1e-10);
}
