// Large-strain closed forms and locking of the hyperelastic elements (docs/THEORY.md §12.6): a
// block compressed to half its height between frictionless supports (lateral faces free) against
// the analytic uniaxial-stress solution of each compressible law, and the same block bonded to
// its supports at Poisson's ratios towards 0.5, where P1 tetrahedra lock.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>

#include "kernels/hyperelastic.hpp"
#include "kernels/svk.hpp"
#include "static_block.hpp"

namespace {

using emc::testing::block_mesh;
using emc::testing::StaticBlock;
namespace k = emc::kernels;

/// The root of the increasing function g on [lo, hi] (g(lo) < 0 < g(hi)), by bisection to the
/// last bit.
double root(const std::function<double(double)>& g, double lo, double hi) {
  while (g(hi) <= 0) hi *= 2;
  for (int it = 0; it < 200 && hi - lo > 4e-16 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (g(mid) < 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

/// Uniaxial stress with principal stretches (a, a, s): the lateral stretch a at which the
/// lateral nominal stress is zero, and the axial nominal stress P there.
struct Uniaxial {
  double a, P;
};

/// Neo-Hookean mu/2 (I1 - 3) - mu ln J + lambda/2 ln^2 J: the principal nominal stresses are
/// P_i = mu (l_i - 1/l_i) + lambda ln J / l_i.
Uniaxial neo_hookean_uniaxial(double lambda, double mu, double s) {
  auto P = [&](double li, double a) {
    return mu * (li - 1 / li) + lambda * std::log(a * a * s) / li;
  };
  const double a = root([&](double x) { return P(x, x); }, 1.0, 1.0 / std::sqrt(s));
  return {a, P(s, a)};
}

/// Mooney-Rivlin c1 (I1 - 3) + c2 (I2 - 3) - 2 (c1 + 2 c2) ln J + lambda/2 ln^2 J:
/// P_i = 2 c1 l_i + 2 c2 l_i (l_j^2 + l_k^2) - 2 (c1 + 2 c2) / l_i + lambda ln J / l_i.
Uniaxial mooney_rivlin_uniaxial(double c1, double c2, double lambda, double s) {
  auto P = [&](double li, double others, double a) {
    return 2 * c1 * li + 2 * c2 * li * others - 2 * (c1 + 2 * c2) / li +
           lambda * std::log(a * a * s) / li;
  };
  const double a = root([&](double x) { return P(x, x * x + s * s, x); }, 1.0, 1.0 / std::sqrt(s));
  return {a, P(s, 2 * a * a, a)};
}

/// The node of `m` at the point p (a corner of the box).
int node_at(const emc::mesh::BodyMesh& m, double x, double y, double z) {
  for (int n = 0; n < m.num_nodes(); ++n)
    if (std::fabs(m.X[3 * n] - x) + std::fabs(m.X[3 * n + 1] - y) + std::fabs(m.X[3 * n + 2] - z) <
        1e-12)
      return n;
  return -1;
}

struct Compression {
  double lateral_error;  ///< max |x - diag(a, a, s) X| / H over the nodes
  double force_error;    ///< |R - P L^2| / |P L^2|, R the reaction on the top face
  int nodes;
};

/// The unit cube compressed to height s between frictionless supports, in steps of 0.1 from 1:
/// u_z = 0 on zmin and (s - 1) on zmax, and the rigid in-plane motions held at two corners.
template <class Material>
Compression compress(const Material& material, double size, double s, const Uniaxial& exact) {
  StaticBlock<Material> b(block_mesh(1, 1, size), material);
  const auto& m = b.mesh();
  const auto bottom = emc::mesh::surface_nodes(m, "zmin", "block");
  const auto top = emc::mesh::surface_nodes(m, "zmax", "block");
  const int origin = node_at(m, 0, 0, 0), xcorner = node_at(m, 1, 0, 0);
  EXPECT_GE(origin, 0);
  EXPECT_GE(xcorner, 0);
  for (int n : bottom) b.fixed[3 * n + 2] = 1;
  for (int n : top) b.fixed[3 * n + 2] = 1;
  b.fixed[3 * origin] = b.fixed[3 * origin + 1] = b.fixed[3 * xcorner + 1] = 1;
  for (double h = 0.9; h > s - 1e-12; h -= 0.1) {
    const double hs = std::max(h, s);
    for (int n = 0; n < b.num_nodes(); ++n) b.u[3 * n + 2] = (hs - 1) * b.X(n, 2);
    b.solve(1e-12);
  }
  Compression c{0, 0, b.num_nodes()};
  for (int n = 0; n < b.num_nodes(); ++n)
    for (int i = 0; i < 3; ++i) {
      const double stretch = i < 2 ? exact.a : s;
      c.lateral_error =
          std::max(c.lateral_error, std::fabs(b.X(n, i) + b.u[3 * n + i] - stretch * b.X(n, i)));
    }
  c.force_error = std::fabs(b.resultant(top, 2) - exact.P) / std::fabs(exact.P);
  return c;
}

template <class Material>
void expect_closed_form(const char* name, const Material& material, const Uniaxial& exact) {
  std::printf("%s at s = 0.5: lateral stretch %.12f, nominal stress %.6e Pa\n", name, exact.a,
              exact.P);
  for (double size : {0.25, 0.125}) {
    const Compression c = compress(material, size, 0.5, exact);
    std::printf("  mesh size %.3g (%d nodes): lateral error %.2e, force error %.2e\n", size,
                c.nodes, c.lateral_error, c.force_error);
    // The uniaxial state is homogeneous, so P1 elements hold it exactly on any mesh: what is
    // left is Newton's tolerance (1e-12 of the largest nodal force) through the condition of
    // the stiffness (about 1e3 on these meshes).
    EXPECT_LT(c.lateral_error, 1e-8);
    EXPECT_LT(c.force_error, 1e-8);
  }
}

const k::Lame rubber = k::lame(4e6, 0.45);  // the paper's ball

TEST(Uniaxial, NeoHookeanBlockAtHalfHeightIsTheClosedForm) {
  expect_closed_form("neo-hookean", k::neo_hookean(rubber.lambda, rubber.mu),
                     neo_hookean_uniaxial(rubber.lambda, rubber.mu, 0.5));
}

TEST(Uniaxial, MooneyRivlinBlockAtHalfHeightIsTheClosedForm) {
  const double c2 = rubber.mu / 8, c1 = rubber.mu / 2 - c2, lambda = rubber.lambda - 4 * c2;
  expect_closed_form("mooney-rivlin", k::mooney_rivlin(c1, c2, lambda),
                     mooney_rivlin_uniaxial(c1, c2, lambda, 0.5));
}

/// The reaction on the top face of the unit cube bonded to its supports (every component of
/// zmin and zmax held) and compressed to height s, in kSteps steps (fewer fail at nu = 0.499:
/// the first iterate's volume change makes a pressure of ten times the shear modulus there,
/// whose geometric stiffness makes the tangent indefinite).
double bonded_reaction(double poisson, double size, double s) {
  constexpr int kSteps = 20;
  const k::Lame l = k::lame(4e6, poisson);
  StaticBlock<k::LogHyperelastic> b(block_mesh(1, 1, size), k::neo_hookean(l.lambda, l.mu));
  const auto& m = b.mesh();
  const auto bottom = emc::mesh::surface_nodes(m, "zmin", "block");
  const auto top = emc::mesh::surface_nodes(m, "zmax", "block");
  for (int n : bottom)
    for (int i = 0; i < 3; ++i) b.fixed[3 * n + i] = 1;
  for (int n : top)
    for (int i = 0; i < 3; ++i) b.fixed[3 * n + i] = 1;
  // in five steps, each from the last solution scaled to the new height (the first from the
  // homogeneous compression, whose volume change a nearly incompressible body resists)
  for (int n = 0; n < b.num_nodes(); ++n) b.u[3 * n + 2] = (s - 1) / kSteps * b.X(n, 2);
  for (int step = 1; step <= kSteps; ++step) {
    if (step > 1)
      for (double& v : b.u) v *= step / (step - 1.0);
    b.solve(1e-10);
  }
  return -b.resultant(top, 2);
}

// Locking, measured: the bonded block's reaction at 10% compression on meshes h = 0.25, 0.15
// and 0.1 against the finest, at nu = 0.45, 0.49, 0.499. P1 tetrahedra are too stiff, the more so
// the nearer nu is to 0.5 (their volumetric constraints outnumber the dofs): the coarse meshes'
// excess over the finest grows with nu (docs/user-guide.md, "Materials").
TEST(Locking, CoarseMeshExcessGrowsTowardsIncompressibility) {
  const double sizes[3] = {0.25, 0.15, 0.1};
  double excess_coarse[3];
  int row = 0;
  std::printf("nu      R(h=0.25)/R(h=0.1)-1  R(h=0.15)/R(h=0.1)-1  R(h=0.1) [N]\n");
  for (double nu : {0.45, 0.49, 0.499}) {
    double R[3];
    for (int i = 0; i < 3; ++i) R[i] = bonded_reaction(nu, sizes[i], 0.9);
    std::printf("%-7g %-21.3e %-21.3e %.6e\n", nu, R[0] / R[2] - 1, R[1] / R[2] - 1, R[2]);
    EXPECT_GT(R[0], R[2]);  // too stiff, converging from above
    EXPECT_GT(R[0] / R[2] - 1, R[1] / R[2] - 1);
    excess_coarse[row++] = R[0] / R[2] - 1;
  }
  EXPECT_GT(excess_coarse[2], excess_coarse[1]);
  EXPECT_GT(excess_coarse[1], excess_coarse[0]);
}

}  // namespace
