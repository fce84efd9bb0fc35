// Element kernels without MPI or Tpetra (docs/THEORY.md §1.4-§1.5): exact tangent against central
// finite differences, the per-element energy identity (eq. 25), vanishing sum and moment of
// the internal forces, consistent mass.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "kernels/em_tet4.hpp"
#include "kernels/monitors.hpp"
#include "kernels/newton_tet4.hpp"
#include "support/element.hpp"

namespace k = emc::kernels;

namespace {

using emc::kernels::test::Element;
using emc::kernels::test::make_element;
using emc::kernels::test::random_u;

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
                      const k::ElementState& s, bool moved, const double A[12][12]) {
  const double h = 1e-6;
  double diff[12][12];
  for (int c = 0; c < 12; ++c) {
    k::ElementState p = s, m = s;
    p.u1[c / 3][c % 3] += h;
    m.u1[c / 3][c % 3] -= h;
    double rp[12], rm[12];
    k::newton_tet4(e.G, e.Ve, kMat, rho, grav, k::Integrator::energy_momentum, dt, p, rp, nullptr,
                   nullptr, moved);
    k::newton_tet4(e.G, e.Ve, kMat, rho, grav, k::Integrator::energy_momentum, dt, m, rm, nullptr,
                   nullptr, moved);
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
    EXPECT_LT(emc::kernels::test::force_imbalance(e, u0, u1, f), 1e-13) << "trial " << trial;
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
    EXPECT_LT(emc::kernels::test::linear_force_error(K0, u, f), 1e-10) << "trial " << trial;
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
  EXPECT_LT(jacobian_error(e, rho, grav, dt, s, false, A), 1e-6);
  for (int q = 0; q < 12; ++q) EXPECT_GE(scale[q], std::fabs(r[q]));
}

// docs/THEORY.md §1.6: far from the reference configuration (|u| = 10^4 times the step's
// increment) the residual moves by far more than the four terms' round-off when u_{n+1} moves
// by one ulp (the inertia (2/dt^2) M times eps |u|); Newton's floor 100 eps scale must still
// cover that change at every dof, which the inertia rounding term of scale makes it do.
TEST(NewtonTet4, ScaleBoundsTheRoundingOfTheIterate) {
  Element e = make_element();
  std::mt19937 rng(11);
  k::ElementState s;
  random_u(rng, 0.5, s.V0);
  const double dt = 1e-6, rho = 7.0, grav[3] = {0, 0, 0}, eps = 2.220446049250313e-16;
  double du[4][3];
  random_u(rng, dt, du);
  for (int a = 0; a < 4; ++a)
    for (int i = 0; i < 3; ++i) {
      s.u0[a][i] = 1e4 * dt * (1.0 + 0.1 * i) + 1e-3 * a;  // far out, nearly a translation
      s.u1[a][i] = s.u0[a][i] + du[a][i];
    }
  double r[12], scale[12];
  k::newton_tet4(e.G, e.Ve, kMat, rho, grav, k::Integrator::energy_momentum, dt, s, r, nullptr,
                 scale);
  k::ElementState t = s;  // u_{n+1} one ulp away, alternating directions
  for (int a = 0; a < 4; ++a)
    for (int i = 0; i < 3; ++i)
      t.u1[a][i] = std::nextafter(s.u1[a][i], (a + i) % 2 ? 1e300 : -1e300);
  double rt[12], unused[12];
  k::newton_tet4(e.G, e.Ve, kMat, rho, grav, k::Integrator::energy_momentum, dt, t, rt, nullptr,
                 unused);
  for (int q = 0; q < 12; ++q) EXPECT_LE(std::fabs(rt[q] - r[q]), 100 * eps * scale[q]) << q;
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

// docs/THEORY.md §6.8, massless nodes (every pattern of 1 to 4 of the 4, each massless node's
// velocity the barycentric combination of four support points around the element that gives its
// position): M' = T^T M_e T is symmetric positive semi-definite, and its moments up to the second
// (phi^T M' psi for phi, psi in 1, x, y, z at the supports) are the element's own, so that a
// rigid velocity has the element's m v and kinetic energy. An element with massless nodes leaves
// its mass to the moved mass: the Newton kernel's residual and matrix carry no inertia then, and
// its matrix is still the derivative of its residual.
TEST(NewtonTet4, MovedMassKeepsTheMoments) {
  Element e = make_element();
  const double rho = 7.0, m = rho * e.Ve;
  const double P[4][3] = {{-0.5, -0.4, -0.3}, {1.6, -0.2, 0.1}, {0.1, 1.5, -0.2}, {0.3, 0.2, 1.7}};
  double Pg[4][3];
  const double vol = k::tet_gradients(P, Pg);
  ASSERT_GT(vol, 0);
  for (int mask = 1; mask < 16; ++mask) {
    std::vector<std::array<double, 3>> Y;  // the supports: massive element nodes, then P
    for (int a = 0; a < 4; ++a)
      if (!((mask >> a) & 1)) Y.push_back({e.X[a][0], e.X[a][1], e.X[a][2]});
    const int nh = static_cast<int>(Y.size()), K = nh + 4;
    for (const auto& p : P) Y.push_back({p[0], p[1], p[2]});
    std::vector<double> W(4 * K, 0.0), M(K * K);
    for (int a = 0, h = 0; a < 4; ++a) {
      if (!((mask >> a) & 1)) {
        W[a * K + h++] = 1.0;
        continue;
      }
      for (int j = 0; j < 4; ++j) {  // barycentric coordinate j of X_a in P
        double w = 0.25;
        for (int i = 0; i < 3; ++i)
          w += Pg[j][i] * (e.X[a][i] - 0.25 * (P[0][i] + P[1][i] + P[2][i] + P[3][i]));
        W[a * K + nh + j] = w;
      }
    }
    k::moved_mass(rho, e.Ve, W.data(), K, M.data());
    for (int j = 0; j < K; ++j)
      for (int q = 0; q < K; ++q) EXPECT_EQ(M[j * K + q], M[q * K + j]) << "mask " << mask;
    std::mt19937 rng(mask);
    std::uniform_real_distribution<double> d(-1, 1);
    for (int t = 0; t < 20; ++t) {  // v^T M' v >= 0
      std::vector<double> v(K);
      for (auto& x : v) x = d(rng);
      double q = 0;
      for (int j = 0; j < K; ++j)
        for (int l = 0; l < K; ++l) q += v[j] * M[j * K + l] * v[l];
      EXPECT_GE(q, -1e-14 * m) << "mask " << mask;
    }
    for (int p = 0; p < 4; ++p)  // phi_p = 1, x, y, z
      for (int q = 0; q < 4; ++q) {
        const auto phi = [](int p, const double* x) { return p == 0 ? 1.0 : x[p - 1]; };
        double moved = 0, own = 0;
        for (int j = 0; j < K; ++j)
          for (int l = 0; l < K; ++l)
            moved += phi(p, Y[j].data()) * M[j * K + l] * phi(q, Y[l].data());
        for (int a = 0; a < 4; ++a)
          for (int b = 0; b < 4; ++b)
            own += phi(p, e.X[a]) * k::mass_ab(rho, e.Ve, a, b) * phi(q, e.X[b]);
        EXPECT_NEAR(moved, own, 1e-13 * m * 4) << "mask " << mask << " moment " << p << q;
      }
  }
  k::ElementState s;
  std::mt19937 rng(3);
  random_u(rng, 0.2, s.u0);
  random_u(rng, 0.5, s.V0);
  random_u(rng, 0.2, s.u1);
  const double g[3] = {0.1, -0.2, -9.81}, dt = 0.05, zero[3] = {0, 0, 0};
  double r[12], A[12][12] = {}, f[12], K0[12][12] = {};
  k::newton_tet4(e.G, e.Ve, kMat, rho, g, k::Integrator::energy_momentum, dt, s, r, A, nullptr,
                 true);
  k::em_tet4(e.G, e.Ve, kMat, k::Integrator::energy_momentum, s.u0, s.u1, f, K0);
  for (int p = 0; p < 12; ++p) {
    EXPECT_NEAR(r[p], f[p] - rho * e.Ve * g[p % 3] / 4, 1e-12 * (std::fabs(f[p]) + m));
    for (int q = 0; q < 12; ++q) EXPECT_EQ(A[p][q], K0[p][q]);
  }
  EXPECT_LT(jacobian_error(e, rho, zero, dt, s, true, A), 1e-6);
  const double u[4][3] = {};
  double V[4][3];
  for (int a = 0; a < 4; ++a) V[a][0] = 1.0, V[a][1] = -2.0, V[a][2] = 0.5;
  k::Monitors mon;
  k::monitors_tet4(e.X, e.G, e.Ve, kMat, rho, zero, u, V, mon, true);
  EXPECT_EQ(mon.kinetic, 0.0);
  EXPECT_EQ(mon.L[1], 0.0);
  EXPECT_EQ(mon.moment[2], 0.0);
  EXPECT_NEAR(mon.mass, m, 1e-15 * m);
}
