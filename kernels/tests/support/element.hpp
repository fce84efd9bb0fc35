#pragma once
// One skewed tet, random nodal displacements, and the resultant and moment of its nodal forces
// about the mid-point configuration (docs/THEORY.md §1.5, identities 1 and 2), for the element
// kernels' tests.
#include <algorithm>
#include <cmath>
#include <random>

#include "kernels/tet4.hpp"

namespace emc::kernels::test {

struct Element {
  double X[4][3], G[4][3], Ve;
};

/// A skewed tet.
inline Element make_element() {
  Element e{{{0.1, -0.05, 0.02}, {1.1, 0.1, -0.1}, {0.2, 0.9, 0.15}, {-0.1, 0.2, 1.2}}, {}, 0};
  e.Ve = tet_gradients(e.X, e.G);
  return e;
}

/// Displacements uniform in [-amp, amp] (large deformation for amp ~ 0.3).
inline void random_u(std::mt19937& rng, double amp, double u[4][3]) {
  std::uniform_real_distribution<double> d(-amp, amp);
  for (int a = 0; a < 4; ++a)
    for (int i = 0; i < 3; ++i) u[a][i] = d(rng);
}

/// The largest component of sum_A f_A and of sum_A x_{A,n+1/2} x f_A, relative to the largest
/// |f_A,i|.
inline double force_imbalance(const Element& e, const double u0[4][3], const double u1[4][3],
                              const double f[12]) {
  double fmax = 0, sum[3] = {0, 0, 0}, mom[3] = {0, 0, 0};
  for (int a = 0; a < 4; ++a) {
    double x[3];
    for (int i = 0; i < 3; ++i) {
      x[i] = e.X[a][i] + 0.5 * (u0[a][i] + u1[a][i]);
      sum[i] += f[3 * a + i];
      fmax = std::max(fmax, std::fabs(f[3 * a + i]));
    }
    const double* fa = &f[3 * a];
    mom[0] += x[1] * fa[2] - x[2] * fa[1];
    mom[1] += x[2] * fa[0] - x[0] * fa[2];
    mom[2] += x[0] * fa[1] - x[1] * fa[0];
  }
  double worst = 0;
  for (int i = 0; i < 3; ++i) worst = std::max({worst, std::fabs(sum[i]), std::fabs(mom[i])});
  return worst / fmax;
}

/// |f - 2 K0 u| / |2 K0 u|: how far the force f of the displacements u (u0 = u1 = u) is from the
/// linear one (K0 = df/du1 at rest, half the linear stiffness).
inline double linear_force_error(const double K0[12][12], const double u[4][3],
                                 const double f[12]) {
  double err = 0, size = 0;
  for (int r = 0; r < 12; ++r) {
    double lin = 0;
    for (int c = 0; c < 12; ++c) lin += 2 * K0[r][c] * u[c / 3][c % 3];
    err += (f[r] - lin) * (f[r] - lin);
    size += lin * lin;
  }
  return std::sqrt(err / size);
}

}  // namespace emc::kernels::test
