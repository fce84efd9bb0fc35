// Activation rule of docs/THEORY.md §6.3 on hand-made geometry, without MPI: which master facet
// a slave node enters over a step, near the edges and vertices of a master cube, and the
// clamped CPP against a brute-force closest point.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "emcontact/contact/detection.hpp"
#include "kernels/facet.hpp"

using emc::contact::entered_facet;
using emc::contact::EntryRule;
using emc::contact::FacetGrid;
using emc::contact::Hit;
using emc::contact::Pair;

namespace {

/// The unit cube [x0, x0 + 1] x [0, 1] x [0, 1] as 12 outward triangles; the slave node is
/// node 8 (its positions at t_n and t_{n+1} are set by the test).
struct Cube {
  Pair pair;
  std::vector<double> x0, x1;
  explicit Cube(double ox = 0) {
    for (int k = 0; k < 8; ++k)
      x0.insert(x0.end(), {ox + (k & 1), double(k >> 1 & 1), double(k >> 2)});
    x0.insert(x0.end(), {0, 0, 0});
    // each face as two triangles, counter-clockwise seen from outside
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) {
      pair.facets.push_back({q[0], q[1], q[2]});
      pair.facets.push_back({q[0], q[2], q[3]});
    }
    pair.slaves = {8};
    pair.dmax = 0.5;
    pair.edge = 1;
    x1 = x0;
  }
  Hit enter(const double y0[3], const double y1[3], const double ns[3]) {
    for (int i = 0; i < 3; ++i) {
      x0[24 + i] = y0[i];
      x1[24 + i] = y1[i];
    }
    const FacetGrid grid(pair.facets, x1, pair.dmax);
    return entered_facet(grid, pair, x0, x1, 8, ns, emc::contact::entry_rule(pair));
  }
  /// The outward normal of facet f (in x0).
  std::array<double, 3> normal(int f) const {
    double xm[3][3];
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < 3; ++i) xm[a][i] = x0[3 * pair.facets[f][a] + i];
    const auto fc = emc::kernels::facet(xm);
    return {fc.n[0], fc.n[1], fc.n[2]};
  }
};

const double r2 = 1 / std::sqrt(2.0);

}  // namespace

TEST(EnteredFacet, FaceInterior) {
  Cube c;
  const double y0[3] = {0.3, 0.6, 1.01}, y1[3] = {0.3, 0.6, 0.999}, ns[3] = {0, 0, -1};
  const Hit h = c.enter(y0, y1, ns);
  ASSERT_GE(h.facet, 0);
  EXPECT_NEAR(c.normal(h.facet)[2], 1, 1e-15);
  EXPECT_NEAR(h.gap, -1e-3, 1e-12);
}

// Two equal bars end to end: the slave face's edge node lies 5e-4 beside the master's face
// (in front of its side face) as it crosses the end face's plane. The end face takes it
// through the edge extension; the side face does not face it (the slave's normal there is the
// mean of its end and side faces). The closest valid facet of §2 alone is the side face at
// g_N = +5e-4: the node was never caught and sank.
TEST(EnteredFacet, EdgeNodeOfAnEqualFace) {
  Cube c;
  const double y0[3] = {1 + 5e-4, 0.5, -0.01}, y1[3] = {1 + 5e-4, 0.5, 1e-3};
  const double ns[3] = {r2, 0, r2};
  const Hit h = c.enter(y0, y1, ns);
  ASSERT_GE(h.facet, 0);
  EXPECT_NEAR(c.normal(h.facet)[2], -1, 1e-15);
  EXPECT_NEAR(h.gap, -1e-3, 1e-12);
  const FacetGrid grid(c.pair.facets, c.x1, c.pair.dmax);
  const Hit closest = grid.locate(y1);
  EXPECT_NEAR(c.normal(closest.facet)[0], 1, 1e-15);
  EXPECT_GT(closest.gap, 0);
}

// A node entering exactly at a vertex and exactly on an edge of the top face is caught.
TEST(EnteredFacet, VertexAndEdge) {
  Cube c;
  const double ns[3] = {0, 0, -1};
  for (const double* y : {(const double[3]){0, 0, 0}, (const double[3]){0.5, 1, 0}}) {
    const double y0[3] = {y[0], y[1], 1.01}, y1[3] = {y[0], y[1], 0.998};
    const Hit h = c.enter(y0, y1, ns);
    ASSERT_GE(h.facet, 0);
    EXPECT_NEAR(c.normal(h.facet)[2], 1, 1e-15);
    EXPECT_NEAR(h.gap, -2e-3, 1e-12);
  }
}

// The bottom rim node of a disk reaching the next disk's rim (three_disks): it lies in the
// plane of the master's bottom face (g_N = -1e-10 there, its CPP inside once it has entered).
// The rim face is the one crossed; the bottom face does not face the node.
TEST(EnteredFacet, RimNodeInTheMastersFacePlane) {
  Cube c;
  const double y0[3] = {-0.01, 0.5, 1e-10}, y1[3] = {2e-3, 0.5, 1e-10}, ns[3] = {r2, 0, -r2};
  const Hit h = c.enter(y0, y1, ns);
  ASSERT_GE(h.facet, 0);
  EXPECT_NEAR(c.normal(h.facet)[0], -1, 1e-15);
  EXPECT_NEAR(h.gap, -2e-3, 1e-12);
}

// A block sliding over the joint onto the next block (joint.xml): its leading edge node,
// hovering 1e-4 above the top face, passes the side face's top edge. The side face would take
// it through the edge extension (the node is 2e-2 behind its plane), but the node lies on the
// top face: it passes over the edge, no snag.
TEST(EnteredFacet, NoSnagOverAJoint) {
  Cube c(1.0);
  const double y0[3] = {0.99, 0.5, 1 + 1e-4}, y1[3] = {1.02, 0.5, 1 + 1e-4};
  const double ns[3] = {r2, 0, -r2};
  EXPECT_LT(c.enter(y0, y1, ns).facet, 0);
  // dipping below the top face on the way, it enters the top face, not the side
  const double y2[3] = {1.02, 0.5, 1 - 1e-4};
  const Hit h = c.enter(y0, y2, ns);
  ASSERT_GE(h.facet, 0);
  EXPECT_NEAR(c.normal(h.facet)[2], 1, 1e-15);
}

// A node hovering over the top face near its edge, moving away from the edge: it is behind the
// side face's plane and approaches it, but the side face does not face it and it never crossed
// it; and a node already behind a face that moves out of it is left free.
TEST(EnteredFacet, HoveringAndLeavingNodesAreNotCaught) {
  Cube c;
  const double ns[3] = {0, 0, -1};
  const double y0[3] = {0.996, 0.5, 1 + 1e-4}, y1[3] = {0.99, 0.5, 1 + 1e-4};
  EXPECT_LT(c.enter(y0, y1, ns).facet, 0);
  const double z0[3] = {0.5, 0.5, 0.99}, z1[3] = {0.5, 0.5, 0.995};
  EXPECT_LT(c.enter(z0, z1, ns).facet, 0);
}

// The bottom rim node of a cylinder whose outer face is the slave (hollow_cylinders), pressed
// against the master's side face (+x), slides below the master's bottom face and comes back up
// through it, 5e-4 inside the side face's plane. The bottom face is at the node's side (n_f .
// n_s = 0): it is crossed strictly inside, and catches the node at the depth of this step's
// crossing (1e-3), not the side face from beside at the 6e-4 the node had gone under.
TEST(EnteredFacet, CornerNodeRisingThroughASideFacet) {
  Cube c;
  const double ns[3] = {-1, 0, 0};
  const double y0[3] = {1 - 5e-4, 0.5, -1e-3}, y1[3] = {1 - 6e-4, 0.5, 1e-3};
  const Hit h = c.enter(y0, y1, ns);
  ASSERT_GE(h.facet, 0);
  EXPECT_NEAR(c.normal(h.facet)[2], -1, 1e-15);
  EXPECT_NEAR(h.gap, -1e-3, 1e-12);
  // the same motion without the rise stays outside the master: not caught
  const double z0[3] = {1 - 5e-4, 0.5, -1e-3}, z1[3] = {1 - 6e-4, 0.5, -2e-3};
  EXPECT_LT(c.enter(z0, z1, ns).facet, 0);
}

// A cube whose +x face leans inward (its top edge moved to x = 0.95): the edge with the bottom
// face is acute, and the +x face's prism reaches below the bottom face's plane. A node there,
// 2e-3 behind the +x face with its CPP inside it but 5e-5 below the bottom face, is outside the
// master: it is not caught from beside on the +x face. Above the bottom face it is inside and
// is caught.
TEST(EnteredFacet, NodeInTheSliverOfAnAcuteEdge) {
  Cube c;
  for (int k : {5, 7}) c.x0[3 * k] = c.x1[3 * k] = 0.95;
  const auto n = c.normal(10);  // the +x face's first triangle
  ASSERT_GT(n[0], 0.99);
  const double d[3] = {-n[2], 0, n[0]};  // up the face
  auto at = [&](double depth, double up, double y[3]) {
    const double e[3] = {1, 0.5, 0};
    for (int i = 0; i < 3; ++i) y[i] = e[i] - depth * n[i] + up * d[i];
  };
  double y0[3], y1[3];
  at(1.5e-3, 5e-5, y0);
  at(2e-3, 5e-5, y1);
  ASSERT_LT(y1[2], 0);  // below the bottom face's plane
  const double ns[3] = {-1, 0, 0};
  EXPECT_LT(c.enter(y0, y1, ns).facet, 0);
  at(1.5e-3, 2e-4, y0);
  at(2e-3, 2e-4, y1);
  ASSERT_GT(y1[2], 0);
  const Hit h = c.enter(y0, y1, ns);
  ASSERT_GE(h.facet, 0);
  EXPECT_GT(c.normal(h.facet)[0], 0.99);
}

// A node sliding along the top face as it enters it (the corner of a tumbling cube landing on
// a block): it crosses the face's plane over one of the face's two triangles and ends strictly
// inside the other, beyond the first one's edge extension. Neither triangle took it both by its
// crossing point and by its end CPP, so it stayed free inside the master (caught a step later
// from beside, 3.1e-3 deep). It is caught on the triangle it ends in, at its depth there.
TEST(EnteredFacet, NodeSlidingOverTheEdgeBetweenTwoFacets) {
  Cube c;
  const double ns[3] = {0, 0, -1};
  const double y0[3] = {0.6, 0.4, 1.001}, y1[3] = {0.4, 0.6, 0.997};
  const Hit h = c.enter(y0, y1, ns);
  ASSERT_EQ(h.facet, 3);  // (4, 7, 6): y > x on the top face
  EXPECT_NEAR(h.gap, -3e-3, 1e-12);
  // the same slide above the face is not caught
  const double z1[3] = {0.4, 0.6, 1.0005};
  EXPECT_LT(c.enter(y0, z1, ns).facet, 0);
}

// A node crossing the top face strictly inside, near its edge, and ending beyond the edge
// extension, outside the master beside the side face (two equal cubes dropped flat, the upper
// face's corner passing the lower cube's top edge): it went through the master's edge region
// and is caught on the face it crossed, with its gap there. Crossing the plane beside the face
// (in its edge extension) and ending beyond it is passing over the edge: not caught.
TEST(EnteredFacet, NodeThroughTheEdgeOfTheMaster) {
  Cube c;
  const double ns[3] = {0, 0, -1};
  const double y0[3] = {0.99, 0.5, 1 + 4e-4}, y1[3] = {1.011, 0.5, 1 - 2.6e-3};
  const Hit h = c.enter(y0, y1, ns);
  ASSERT_GE(h.facet, 0);
  EXPECT_NEAR(c.normal(h.facet)[2], 1, 1e-15);
  EXPECT_NEAR(h.gap, -2.6e-3, 1e-12);
  const double z0[3] = {1.002, 0.5, 1 + 4e-4};
  EXPECT_LT(c.enter(z0, y1, ns).facet, 0);
}

namespace {

/// crossed_too_deep for node 8 of the cube moving from y0 to y1 (x0 and x1 of the cube as set).
emc::contact::Crossing crossing(Cube& c, const double y0[3], const double y1[3]) {
  for (int i = 0; i < 3; ++i) {
    c.x0[24 + i] = y0[i];
    c.x1[24 + i] = y1[i];
  }
  return emc::contact::crossed_too_deep(c.pair, c.x0, c.x1, 8, emc::contact::entry_rule(c.pair));
}

}  // namespace

// A node that crosses a facet and ends behind it deeper than the max penetration (0.5 for the
// unit cube) is found, with its depth and the drop of its gap: through the whole cube, into it
// beyond dmax, and up through the bottom face. Within dmax it is activation's; beside the cube,
// starting behind a face, or leaving the cube it is not a crossing.
TEST(CrossedTooDeep, ThroughOrTooDeepIntoTheMaster) {
  Cube c;
  const double above[3] = {0.3, 0.6, 1.01};
  for (double z : {-0.5, 0.4}) {
    const double y1[3] = {0.3, 0.6, z};
    const auto k = crossing(c, above, y1);
    ASSERT_GE(k.facet, 0) << z;
    EXPECT_NEAR(c.normal(k.facet)[2], 1, 1e-15);
    EXPECT_NEAR(k.gap, z - 1, 1e-14);
    EXPECT_NEAR(k.closing, 1.01 - z, 1e-14);
  }
  const double below[3] = {0.7, 0.2, -0.01}, up[3] = {0.7, 0.2, 0.6};
  const auto b = crossing(c, below, up);
  ASSERT_GE(b.facet, 0);
  EXPECT_NEAR(c.normal(b.facet)[2], -1, 1e-15);
  const double shallow[3] = {0.3, 0.6, 0.6}, beside0[3] = {1.01, 0.5, 2},
               beside1[3] = {1.01, 0.5, -1};
  EXPECT_LT(crossing(c, above, shallow).facet, 0);
  EXPECT_LT(crossing(c, beside0, beside1).facet, 0);
  const double inside[3] = {0.5, 0.5, 0.9}, out[3] = {0.5, 0.5, -2};
  EXPECT_LT(crossing(c, inside, out).facet, 0);  // behind the top face at t_n; leaves the cube
  // exactly through an edge shared by two facets of the top face (its diagonal) and a vertex
  const double e0[3] = {0.25, 0.25, 1.5}, e1[3] = {0.25, 0.25, -0.5};
  EXPECT_GE(crossing(c, e0, e1).facet, 0);
  const double v0[3] = {1, 1, 1.5}, v1[3] = {1 - 1e-3, 1 - 1e-3, 0.2};
  EXPECT_GE(crossing(c, v0, v1).facet, 0);
}

// The master moves: a node at rest that the cube sweeps over in one step (the cube from above
// it to below it) crossed its bottom face; the grid of the sweeps finds the facet, which is
// nowhere near the node at either end of the step.
TEST(CrossedTooDeep, AMasterSweepingOverTheNode) {
  Cube c;
  for (int k = 0; k < 8; ++k) {
    c.x0[3 * k + 2] += 1.5;  // z from 1.5 to 2.5
    c.x1[3 * k + 2] -= 3;    // z from -3 to -2
  }
  const double y[3] = {0.4, 0.4, 0.5};
  const auto k = crossing(c, y, y);
  ASSERT_GE(k.facet, 0);
  EXPECT_NEAR(c.normal(k.facet)[2], -1, 1e-15);
  EXPECT_NEAR(k.gap, -3.5, 1e-14);
}

// facet_clamp gives the closest point of the triangle (brute force over a fine sampling).
TEST(FacetClamp, MatchesBruteForce) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> d(-1, 1);
  for (int t = 0; t < 50; ++t) {
    double xm[3][3], y[3], xi[2], gap;
    for (auto& p : xm)
      for (double& v : p) v = d(rng);
    for (double& v : y) v = 1.5 * d(rng);
    const auto m = emc::kernels::facet_metric(xm);
    ASSERT_TRUE(emc::kernels::facet_cpp(y, xm, m, xi, gap));
    emc::kernels::facet_clamp(m, xi);
    auto dist = [&](double a, double b) {
      double s = 0;
      for (int i = 0; i < 3; ++i) {
        const double p = (1 - a - b) * xm[0][i] + a * xm[1][i] + b * xm[2][i];
        s += (y[i] - p) * (y[i] - p);
      }
      return s;
    };
    double best = 1e300;
    const int n = 400;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) best = std::min(best, dist(double(i) / n, double(j) / n));
    EXPECT_LE(emc::kernels::facet_outside(xi), 1e-15);
    EXPECT_LE(dist(xi[0], xi[1]), best + 1e-12);
  }
}
