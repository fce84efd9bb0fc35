// Element kernels without MPI or Tpetra (docs/THEORY.md §1.4-§1.5): exact tangent against central
// finite differences, the per-element energy identity (eq. 25), vanishing sum and moment of
// the internal forces, consistent mass.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kernels/em_tet4.hpp"
#include "kernels/monitors.hpp"
#include "kernels/newton_tet4.hpp"

namespace k = emc::kernels;

namespace {

struct Element {
  double X[4][3], G[4][3], Ve;
};

/// A skewed tet and random displacements of size `amp` (large deformation for amp ~ 0.3).
Element make_element() {
  Element e{{{0.1, -0.05, 0.02}, {1.1, 0.1, -0.1}, {0.2, 0.9, 0.15}, {-0.1, 0.2, 1.2}}, {}, 0};
  e.Ve = k::tet_gradients(e.X, e.G);
  return e;
}

void random_u(std::mt19937& rng, double amp, double u[4][3]) {
  std::uniform_real_distribution<double> d(-amp, amp);
  for (int a = 0; a < 4; ++a)
    for (int i = 0; i < 3; ++i) u[a][i] = d(rng);
}

double frob(const double A[12][12]) {
  double s = 0;
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j) s += A[i][j] * A[i][j];
  return std::sqrt(s);
}

const k::Lame kMat = k::lame(200.0, 0.3);

class Integrators : public ::testing::TestWithParam<k::Integrator> {};

/// |A - the central finite-difference Jacobian of newton_tet4's residual in u1| / |A|.
double jacobian_error(const Element& e, double rho, const double grav[3], double dt,
                      const k::ElementState& s, int massless, const double A[12][12]) {
  const double h = 1e-6;
  double diff[12][12];
  for (int c = 0; c < 12; ++c) {
    k::ElementState p = s, m = s;
    p.u1[c / 3][c % 3] += h;
    m.u1[c / 3][c % 3] -= h;
    double rp[12], rm[12];
    k::newton_tet4(e.G, e.Ve, kMat, rho, grav, k::Integrator::energy_momentum, dt, p, rp, nullptr,
                   nullptr, massless);
    k::newton_tet4(e.G, e.Ve, kMat, rho, grav, k::Integrator::energy_momentum, dt, m, rm, nullptr,
                   nullptr, massless);
    for (int q = 0; q < 12; ++q) diff[q][c] = A[q][c] - (rp[q] - rm[q]) / (2 * h);
  }
  return frob(diff) / frob(A);
}

}  // namespace

TEST(Tet4, GradientsSumToZeroAndVolume) {
  Element e = make_element();
  EXPECT_GT(e.Ve, 0);
  EXPECT_NEAR(e.Ve, k::tet_volume(e.X), 1e-15);
  for (int j = 0; j < 3; ++j) EXPECT_NEAR(e.G[0][j] + e.G[1][j] + e.G[2][j] + e.G[3][j], 0, 1e-14);
  // grad of x_i itself is the identity: sum_A X_A,i G_A,j = delta_ij
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double s = 0;
      for (int a = 0; a < 4; ++a) s += e.X[a][i] * e.G[a][j];
      EXPECT_NEAR(s, i == j ? 1.0 : 0.0, 1e-14);
    }
  double Xinv[4][3] = {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}};
  double Ginv[4][3];
  EXPECT_LT(k::tet_gradients(Xinv, Ginv), 0);  // inverted element is reported
}

// Tangent vs central finite differences of the force (relative 1e-6; step 1e-6 gives a
// truncation error ~1e-12 |f'''| and a round-off ~1e-16/1e-6 = 1e-10 relative).
TEST_P(Integrators, TangentMatchesFiniteDifferences) {
  Element e = make_element();
  std::mt19937 rng(7);
  double u0[4][3], u1[4][3], f[12], K[12][12], Kfd[12][12];
  random_u(rng, 0.3, u0);
  random_u(rng, 0.3, u1);
  k::em_tet4(e.G, e.Ve, kMat, GetParam(), u0, u1, f, K);
  const double h = 1e-6;
  for (int c = 0; c < 12; ++c) {
    double up[4][3], um[4][3], fp[12], fm[12];
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) up[a][i] = um[a][i] = u1[a][i];
    up[c / 3][c % 3] += h;
    um[c / 3][c % 3] -= h;
    k::em_tet4(e.G, e.Ve, kMat, GetParam(), u0, up, fp, nullptr);
    k::em_tet4(e.G, e.Ve, kMat, GetParam(), u0, um, fm, nullptr);
    for (int r = 0; r < 12; ++r) Kfd[r][c] = (fp[r] - fm[r]) / (2 * h);
  }
  double diff[12][12];
  for (int r = 0; r < 12; ++r)
    for (int c = 0; c < 12; ++c) diff[r][c] = K[r][c] - Kfd[r][c];
  EXPECT_LT(frob(diff) / frob(K), 1e-6);
  // the tangent is genuinely non-symmetric for energy-momentum
  if (GetParam() == k::Integrator::energy_momentum) {
    double asym[12][12];
    for (int r = 0; r < 12; ++r)
      for (int c = 0; c < 12; ++c) asym[r][c] = K[r][c] - K[c][r];
    EXPECT_GT(frob(asym) / frob(K), 1e-3);
  }
}

// Sum of forces and moment of forces about the mid-point configuration vanish (eq. 25).
TEST_P(Integrators, ForcesAndMomentsVanish) {
  Element e = make_element();
  std::mt19937 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    double u0[4][3], u1[4][3], f[12];
    random_u(rng, 0.4, u0);
    random_u(rng, 0.4, u1);
    k::em_tet4(e.G, e.Ve, kMat, GetParam(), u0, u1, f, nullptr);
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
    for (int i = 0; i < 3; ++i) {
      EXPECT_LT(std::fabs(sum[i]), 1e-13 * fmax);
      EXPECT_LT(std::fabs(mom[i]), 1e-13 * fmax);
    }
  }
}

// A body near rest: the force of a displacement gradient |H| ~ 1e-12 is the linear one,
// 2 K(0) u (K = df/du1 is half the linear stiffness at u0 = u1 = 0), to O(|H|) = 1e-12
// relative; tolerance 1e-10. E from F^T F - I would cancel against I and miss it by about
// eps / |H| ~ 1e-4, a force noise on every node above Newton's round-off floor (§1).
TEST_P(Integrators, ForceOfATinyStrainIsLinearToRoundOff) {
  Element e = make_element();
  std::mt19937 rng(5);
  double zero[4][3] = {}, u[4][3], f0[12], K0[12][12], f[12];
  k::em_tet4(e.G, e.Ve, kMat, GetParam(), zero, zero, f0, K0);
  for (int trial = 0; trial < 10; ++trial) {
    random_u(rng, 1e-12, u);
    k::em_tet4(e.G, e.Ve, kMat, GetParam(), u, u, f, nullptr);
    double err = 0, norm = 0;
    for (int r = 0; r < 12; ++r) {
      double lin = 0;
      for (int c = 0; c < 12; ++c) lin += 2 * K0[r][c] * u[c / 3][c % 3];
      err += (f[r] - lin) * (f[r] - lin);
      norm += lin * lin;
    }
    EXPECT_LT(std::sqrt(err / norm), 1e-10) << "trial " << trial;
  }
}

INSTANTIATE_TEST_SUITE_P(Both, Integrators,
                         ::testing::Values(k::Integrator::energy_momentum,
                                           k::Integrator::midpoint));

// f . (u1 - u0) = W1 - W0 to round-off for energy-momentum (eq. 25); the plain mid-point
// rule misses it by far more than round-off for large strains.
TEST(EnergyMomentum, EnergyIdentityToRoundOff) {
  Element e = make_element();
  std::mt19937 rng(3);
  double worst_em = 0, best_mid = 1e300;
  for (int trial = 0; trial < 50; ++trial) {
    double u0[4][3], u1[4][3], f[12];
    random_u(rng, 0.3, u0);
    random_u(rng, 0.3, u1);
    const double W0 = k::tet4_energy(e.G, e.Ve, kMat, u0);
    const double W1 = k::tet4_energy(e.G, e.Ve, kMat, u1);
    for (auto integ : {k::Integrator::energy_momentum, k::Integrator::midpoint}) {
      k::em_tet4(e.G, e.Ve, kMat, integ, u0, u1, f, nullptr);
      double work = 0;
      for (int a = 0; a < 4; ++a)
        for (int i = 0; i < 3; ++i) work += f[3 * a + i] * (u1[a][i] - u0[a][i]);
      const double rel = std::fabs(work - (W1 - W0)) / (std::fabs(W0) + std::fabs(W1));
      if (integ == k::Integrator::energy_momentum)
        worst_em = std::max(worst_em, rel);
      else
        best_mid = std::min(best_mid, rel);
    }
  }
  EXPECT_LT(worst_em, 1e-13);
  EXPECT_GT(best_mid, 1e-8);
}

// Consistent mass: sum_AB M_AB = rho V_e; the Newton kernel's matrix equals the central
// finite-difference Jacobian of its residual (inertia + internal - external).
TEST(NewtonTet4, MassAndJacobian) {
  Element e = make_element();
  double msum = 0;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) msum += k::mass_ab(7.0, e.Ve, a, b);
  EXPECT_NEAR(msum, 7.0 * e.Ve, 1e-14);

  std::mt19937 rng(5);
  k::ElementState s;
  random_u(rng, 0.2, s.u0);
  random_u(rng, 0.5, s.V0);
  random_u(rng, 0.2, s.u1);
  const double grav[3] = {0.1, -0.2, -9.81}, dt = 0.05, rho = 7.0;
  double r[12], A[12][12] = {}, scale[12];
  k::newton_tet4(e.G, e.Ve, kMat, rho, grav, k::Integrator::energy_momentum, dt, s, r, A, scale);
  EXPECT_LT(jacobian_error(e, rho, grav, dt, s, 0, A), 1e-6);
  for (int q = 0; q < 12; ++q) EXPECT_GE(scale[q], std::fabs(r[q]));
}

// Monitors of a rigid translation: kinetic = 1/2 m v^2, L = m v, J = sum x x p.
TEST(Monitors, RigidTranslation) {
  Element e = make_element();
  double u[4][3] = {}, V[4][3];
  for (int a = 0; a < 4; ++a) {
    V[a][0] = 1.0;
    V[a][1] = -2.0;
    V[a][2] = 0.5;
  }
  const double grav[3] = {0, 0, -10}, rho = 3.0;
  k::Monitors m;
  k::monitors_tet4(e.X, e.G, e.Ve, kMat, rho, grav, u, V, m);
  const double mass = rho * e.Ve;
  EXPECT_NEAR(m.kinetic, 0.5 * mass * 5.25, 1e-14);
  EXPECT_NEAR(m.L[1], -2.0 * mass, 1e-14);
  EXPECT_NEAR(m.elastic, 0.0, 1e-20);
  EXPECT_NEAR(m.potential, 0.0, 1e-20);
  // J = m xc x v for a rigid translation (consistent mass has the exact centroid)
  double xc[3] = {0, 0, 0};
  for (int a = 0; a < 4; ++a)
    for (int i = 0; i < 3; ++i) xc[i] += e.X[a][i] / 4;
  EXPECT_NEAR(m.J[2], mass * (xc[0] * V[0][1] - xc[1] * V[0][0]), 1e-14);
}

// docs/THEORY.md §6.8, massless nodes (every pattern of 1 to 3 of the 4): M' is symmetric with
// zero rows at the massless nodes, keeps the total mass, is positive definite on the massive
// nodes (Cholesky of that block), mass_times applies it, a rigid translation keeps m v and
// 1/2 m v^2, and the Newton kernel's matrix is still the derivative of its residual.
TEST(NewtonTet4, MasslessNodesKeepTheMass) {
  Element e = make_element();
  const double rho = 7.0, m = rho * e.Ve;
  for (int mask = 1; mask < 15; ++mask) {
    double M[4][4];
    k::mass_matrix(rho, e.Ve, mask, M);
    double total = 0;
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) {
        total += M[a][b];
        EXPECT_EQ(M[a][b], M[b][a]) << "mask " << mask;
        if ((mask >> a) & 1) {
          EXPECT_EQ(M[a][b], 0.0) << "mask " << mask;
        }
      }
    EXPECT_NEAR(total, m, 1e-14 * m) << "mask " << mask;
    int heavy[4], nh = 0;  // Cholesky of the massive block
    for (int a = 0; a < 4; ++a)
      if (!((mask >> a) & 1)) heavy[nh++] = a;
    double L[4][4] = {};
    for (int i = 0; i < nh; ++i)
      for (int j = 0; j <= i; ++j) {
        double s = M[heavy[i]][heavy[j]];
        for (int q = 0; q < j; ++q) s -= L[i][q] * L[j][q];
        if (i == j) {
          ASSERT_GT(s, 1e-3 * m) << "mask " << mask;
          L[i][i] = std::sqrt(s);
        } else {
          L[i][j] = s / L[j][j];
        }
      }
    std::mt19937 rng(mask);
    double v[4][3], p[4][3];
    random_u(rng, 1.0, v);
    k::mass_times(rho, e.Ve, mask, v, p);
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) {
        double q = 0;
        for (int b = 0; b < 4; ++b) q += M[a][b] * v[b][i];
        EXPECT_NEAR(p[a][i], q, 1e-15 * m) << "mask " << mask;
      }
    const double u[4][3] = {}, grav[3] = {0, 0, 0};
    double V[4][3];
    for (int a = 0; a < 4; ++a) V[a][0] = 1.0, V[a][1] = -2.0, V[a][2] = 0.5;
    k::Monitors mon;
    k::monitors_tet4(e.X, e.G, e.Ve, kMat, rho, grav, u, V, mon, mask);
    EXPECT_NEAR(mon.kinetic, 0.5 * m * 5.25, 1e-14 * m);
    EXPECT_NEAR(mon.L[1], -2.0 * m, 1e-14 * m);

    k::ElementState s;
    random_u(rng, 0.2, s.u0);
    random_u(rng, 0.5, s.V0);
    random_u(rng, 0.2, s.u1);
    const double g[3] = {0.1, -0.2, -9.81}, dt = 0.05;
    double r[12], A[12][12] = {};
    k::newton_tet4(e.G, e.Ve, kMat, rho, g, k::Integrator::energy_momentum, dt, s, r, A, nullptr,
                   mask);
    EXPECT_LT(jacobian_error(e, rho, g, dt, s, mask, A), 1e-6) << "mask " << mask;
  }
}
