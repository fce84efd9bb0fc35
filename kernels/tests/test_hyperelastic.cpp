// The Neo-Hookean and Mooney-Rivlin policy (kernels/hyperelastic.hpp, docs/THEORY.md §12) and its
// energy-momentum element (kernels/em_tet4.hpp): the stress is the energy's gradient and the
// tangent the stress's (central differences); the small-strain limit is linear elasticity with
// the stated lambda and mu; Gonzalez's discrete gradient does the work W_{n+1} - W_n to
// round-off, its series agrees with the direct quotient where both apply and with a long double
// reference, its order follows |M| and its gradients agree with the term-by-term products of
// M^k; the element's closed-form tangent equals the strain-variation-by-variation one and is
// the derivative of its force at large strain and next to dE = 0 (at every order of the series);
// a body starting from rest does the work of its energy; a tiny strain's force is the linear
// one; the forces have no resultant or moment.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "kernels/em_tet4.hpp"
#include "support/element.hpp"

namespace k = emc::kernels;

namespace {

using M3 = double[3][3];

/// The materials: Neo-Hookean (lambda, mu of E = 1e6, nu = 0.45) and Mooney-Rivlin (c1, c2,
/// lambda).
const k::Lame kLame = k::lame(1e6, 0.45);
const k::LogHyperelastic kNeo = k::neo_hookean(kLame.lambda, kLame.mu);
const k::LogHyperelastic kMooney = k::mooney_rivlin(1.2e5, 0.5e5, 2.0e6);

class Materials : public ::testing::TestWithParam<k::LogHyperelastic> {};

/// A random symmetric matrix of entries in [-amp, amp].
void random_sym(std::mt19937& rng, double amp, M3 E) {
  std::uniform_real_distribution<double> d(-amp, amp);
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) E[i][j] = E[j][i] = d(rng);
}
double dot(const M3 a, const M3 b) {
  double s = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) s += a[i][j] * b[i][j];
  return s;
}
double norm(const M3 a) {
  return std::sqrt(dot(a, a));
}

// S : X = dW/dE . X and CC : X = dS/dE . X by central differences (step 1e-6 on strains of 0.2:
// truncation 1e-12, round-off 1e-10 relative), at 20 random large strains.
TEST_P(Materials, StressAndTangentAreTheDerivatives) {
  const auto m = GetParam();
  std::mt19937 rng(1);
  const double h = 1e-6;
  for (int trial = 0; trial < 20; ++trial) {
    M3 E, X, S, Ci, CX;
    random_sym(rng, 0.2, E);
    random_sym(rng, 1.0, X);
    k::hyper_stress(m, E, S);
    M3 Ep, Em, Sp, Sm;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        Ep[i][j] = E[i][j] + h * X[i][j], Em[i][j] = E[i][j] - h * X[i][j];
    const double dW = (k::hyper_energy(m, Ep) - k::hyper_energy(m, Em)) / (2 * h);
    EXPECT_NEAR(dot(S, X), dW, 1e-7 * norm(S) * norm(X)) << "trial " << trial;
    k::hyper_stress(m, Ep, Sp);
    k::hyper_stress(m, Em, Sm);
    k::hyper_detail::inverse_C(E, Ci);
    k::hyper_tangent(m, Ci, k::log_J(E), X, CX);
    M3 diff;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) diff[i][j] = CX[i][j] - (Sp[i][j] - Sm[i][j]) / (2 * h);
    EXPECT_LT(norm(diff), 1e-7 * norm(CX)) << "trial " << trial;
  }
}

// At E = 0: W = 0, S = 0 and CC : X = lambda tr X I + 2 mu X with mu = alpha + gamma and
// lambda = 2 (beta + b): the Lame constants for Neo-Hookean, mu = 2 (c1 + c2) and lambda + 4 c2
// for Mooney-Rivlin.
TEST(Hyperelastic, SmallStrainLimitIsLinearElasticity) {
  const double c1 = 1.2e5, c2 = 0.5e5, lambda = 2.0e6;
  struct Case {
    k::LogHyperelastic m;
    double lambda, mu;
  };
  for (const Case& c :
       {Case{kNeo, kLame.lambda, kLame.mu}, Case{kMooney, lambda + 4 * c2, 2 * (c1 + c2)}}) {
    M3 zero = {}, S, Ci, X, CX;
    EXPECT_EQ(k::hyper_energy(c.m, zero), 0.0);
    k::hyper_stress(c.m, zero, S);
    EXPECT_EQ(norm(S), 0.0);
    std::mt19937 rng(2);
    random_sym(rng, 1.0, X);
    k::hyper_detail::inverse_C(zero, Ci);
    k::hyper_tangent(c.m, Ci, 0.0, X, CX);
    const double tr = X[0][0] + X[1][1] + X[2][2];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        EXPECT_NEAR(CX[i][j], c.lambda * tr * (i == j) + 2 * c.mu * X[i][j], 1e-12 * c.lambda);
  }
}

/// delta_1, delta_2 of the log terms (l1 - l0 - C_m^-1 : dE, l1^2 - l0^2 - 2 l_m C_m^-1 : dE) in
/// long double, directly, and the sizes of their terms (what their round-off in double is of).
void long_double_deltas(const M3 E0, const M3 E1, long double d[2], double size[2]) {
  auto logJ = [](const long double E[3][3]) {
    long double C[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) C[i][j] = (i == j) + 2 * E[i][j];
    const long double det = C[0][0] * (C[1][1] * C[2][2] - C[1][2] * C[2][1]) -
                            C[0][1] * (C[1][0] * C[2][2] - C[1][2] * C[2][0]) +
                            C[0][2] * (C[1][0] * C[2][1] - C[1][1] * C[2][0]);
    return 0.5L * std::log(det);
  };
  long double e0[3][3], e1[3][3], em[3][3], dE[3][3], C[3][3], Ci[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      e0[i][j] = E0[i][j], e1[i][j] = E1[i][j];
      em[i][j] = 0.5L * (e0[i][j] + e1[i][j]);
      dE[i][j] = e1[i][j] - e0[i][j];
      C[i][j] = (i == j) + 2 * em[i][j];
    }
  const long double det = C[0][0] * (C[1][1] * C[2][2] - C[1][2] * C[2][1]) -
                          C[0][1] * (C[1][0] * C[2][2] - C[1][2] * C[2][0]) +
                          C[0][2] * (C[1][0] * C[2][1] - C[1][1] * C[2][0]);
  Ci[0][0] = (C[1][1] * C[2][2] - C[1][2] * C[2][1]) / det;
  Ci[0][1] = Ci[1][0] = (C[0][2] * C[2][1] - C[0][1] * C[2][2]) / det;
  Ci[0][2] = Ci[2][0] = (C[0][1] * C[1][2] - C[0][2] * C[1][1]) / det;
  Ci[1][1] = (C[0][0] * C[2][2] - C[0][2] * C[2][0]) / det;
  Ci[1][2] = Ci[2][1] = (C[0][2] * C[1][0] - C[0][0] * C[1][2]) / det;
  Ci[2][2] = (C[0][0] * C[1][1] - C[0][1] * C[1][0]) / det;
  long double cd = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) cd += Ci[i][j] * dE[i][j];
  const long double l0 = logJ(e0), l1 = logJ(e1), lm = logJ(em);
  d[0] = l1 - l0 - cd;
  d[1] = l1 * l1 - l0 * l0 - 2 * lm * cd;
  size[0] = static_cast<double>(std::fabs(l1) + std::fabs(l0) + std::fabs(cd));
  size[1] = static_cast<double>(l1 * l1 + l0 * l0 + 2 * std::fabs(lm * cd));
}

/// A random E_n (entries within +-0.2) and E_{n+1} = E_n + step D / 2 (D within +-1), with E_m,
/// dE, C_m^-1 and M = C_m^-1 dE; false where |M| is beyond the series' bound.
bool random_series_step(std::mt19937& rng, double step, M3 E0, M3 E1, M3 Em, M3 dE, M3 Ci, M3 M) {
  M3 D;
  random_sym(rng, 0.2, E0);
  random_sym(rng, 1.0, D);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      E1[i][j] = E0[i][j] + 0.5 * step * D[i][j];
      Em[i][j] = 0.5 * (E0[i][j] + E1[i][j]);
      dE[i][j] = E1[i][j] - E0[i][j];
    }
  k::hyper_detail::inverse_C(Em, Ci);
  k::hyper_detail::mul(Ci, dE, M);
  return norm(M) <= k::kSeriesBound;
}

// The series of delta (|M| <= 1e-2) against the long double direct quotient: to the round-off of
// its terms (4 eps of their sizes, |l0| + |l1| + |C_m^-1 : dE| and their squares: what the
// energy identity needs), and to 1e-9 relative where delta stands above that (|M| = 1e-2,
// delta ~ |M|^3); the double direct quotient equals the series at the switch to the same
// round-off.
TEST(Hyperelastic, SeriesOfDeltaIsAccurate) {
  std::mt19937 rng(3);
  const double eps = std::numeric_limits<double>::epsilon();
  int checked = 0;
  for (const double step : {1e-2, 1e-3, 1e-4, 1e-6}) {
    for (int trial = 0; trial < 10; ++trial) {
      M3 E0, E1, Em, Ci, M, g1, g2, dE;
      if (!random_series_step(rng, step, E0, E1, Em, dE, Ci, M)) continue;
      double d[2], dd[2], size[2];
      k::hyper_detail::log_deltas_series(Ci, k::log_J(Em), M, dE, d, g1, g2);
      long double ref[2];
      long_double_deltas(E0, E1, ref, size);
      for (int c = 0; c < 2; ++c) {
        const double r = static_cast<double>(ref[c]);
        EXPECT_NEAR(d[c], r, 4 * eps * size[c]) << "|M| " << norm(M) << " term " << c;
        if (step == 1e-2) {
          EXPECT_NEAR(d[c], r, 1e-9 * std::fabs(r)) << "|M| " << norm(M);
        }
      }
      if (step == 1e-2) {
        k::hyper_detail::log_deltas_direct(E0, E1, Ci, k::log_J(Em), dE, M, dd, g1, g2);
        for (int c = 0; c < 2; ++c) EXPECT_NEAR(dd[c], d[c], 4 * eps * size[c]);
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 30);
}

/// The reference series of delta_1, delta_2 and their gradients: every term to M^9, three
/// products a term, dc_k / dE1 = s_k sym((I - M) M^(k-1) C_m^-1) (docs/THEORY.md §12.3-§12.4).
void reference_series(const M3 Ci, double lm, const M3 M, double d[2], M3 g1, M3 g2) {
  using namespace k::hyper_detail;
  constexpr int K = 9;
  double c[K + 1];
  M3 gc[K + 1];
  M3 P, IM;  // P = M^(k-1); IM = I - M
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      P[i][j] = i == j ? 1.0 : 0.0;
      IM[i][j] = (i == j ? 1.0 : 0.0) - M[i][j];
      gc[0][i][j] = 0.5 * Ci[i][j];
    }
  c[0] = lm;
  for (int k = 1; k <= K; ++k) {
    M3 A, B, Pk;
    mul(P, M, Pk);  // M^k
    const double sign = (k % 2) ? 0.5 : -0.5;
    c[k] = sign * trace(Pk) / k;
    mul(IM, P, A);
    mul(A, Ci, B);
    sym(B, gc[k]);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        gc[k][i][j] *= sign;
        P[i][j] = Pk[i][j];
      }
  }
  d[0] = d[1] = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) g1[i][j] = g2[i][j] = 0;
  for (int k = 3; k <= K; k += 2) {
    d[0] += 2 * c[k];
    for (int n = 0; n <= k; ++n) d[1] += 2 * c[n] * c[k - n];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        g1[i][j] += 2 * gc[k][i][j];
        double s = 0;
        for (int n = 0; n <= k; ++n) s += c[k - n] * gc[n][i][j];
        g2[i][j] += 4 * s;
      }
  }
}

// The series' order: the first odd K with |M|^K <= 1e-17, 9 at the bound 1e-2.
TEST(Hyperelastic, SeriesOrderFollowsTheSizeOfM) {
  using k::hyper_detail::series_order;
  const double tail = k::kSeriesTail;
  for (int K = 3; K <= 9; K += 2) {
    const double m = std::pow(tail, 1.0 / K);  // |M|^K = tail: still order K
    EXPECT_EQ(series_order(0.99 * m * m), K) << "K " << K;
    if (K < 9) {
      EXPECT_EQ(series_order(1.01 * m * m), K + 2) << "K " << K;
    }
  }
  EXPECT_EQ(series_order(0.0), 3);
  EXPECT_EQ(series_order(k::kSeriesBound * k::kSeriesBound), 9);
  EXPECT_LE(std::pow(k::kSeriesBound, k::kSeriesMaxOrder), tail);
}

// The series (two products and Cayley-Hamilton, to its order) against the reference (every term
// to M^9, three products a term): delta_1, delta_2 to 4 eps of their terms' sizes (as
// SeriesOfDeltaIsAccurate), and their gradients g, O(|M|^2), to 1e-15 of |C_m^-1| |M| (1 + |l_m|):
// g / (dE : dE) enters the tangent times dE (the dE (x) Q term), so that this bounds the
// tangent's change by 1e-15 relative; the truncation leaves |M|^(K+1) <= 1e-17 |M| (§12.3).
// Symmetric to the bit; the values alone (no gradients) are the same bits. |M| from 1e-2 to
// 1e-9: every order.
TEST(Hyperelastic, SeriesGradientsMatchTheReference) {
  std::mt19937 rng(7);
  const double eps = std::numeric_limits<double>::epsilon();
  int orders[10] = {};
  for (const double step : {1e-2, 3e-3, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-9}) {
    for (int trial = 0; trial < 10; ++trial) {
      M3 E0, E1, Em, Ci, M, dE, g1, g2, r1, r2;
      if (!random_series_step(rng, step, E0, E1, Em, dE, Ci, M)) continue;
      const double lm = k::log_J(Em);
      double d[2], dr[2], size[2];
      long double ld[2];
      long_double_deltas(E0, E1, ld, size);
      k::hyper_detail::log_deltas_series(Ci, lm, M, dE, d, g1, g2);
      reference_series(Ci, lm, M, dr, r1, r2);
      ++orders[k::hyper_detail::series_order(dot(M, M))];
      for (int c = 0; c < 2; ++c)
        EXPECT_NEAR(d[c], dr[c], 4 * eps * size[c]) << "|M| " << norm(M) << " term " << c;
      const double scale = 1e-15 * norm(Ci) * norm(M) * (1 + std::fabs(lm));
      M3 e1, e2;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          e1[i][j] = g1[i][j] - r1[i][j];
          e2[i][j] = g2[i][j] - r2[i][j];
          EXPECT_EQ(g1[i][j], g1[j][i]);
          EXPECT_EQ(g2[i][j], g2[j][i]);
        }
      EXPECT_LT(norm(e1), scale) << "|M| " << norm(M);
      EXPECT_LT(norm(e2), scale) << "|M| " << norm(M);
      double dv[2];
      k::hyper_detail::log_deltas_series(Ci, lm, M, dE, dv, nullptr, nullptr);
      EXPECT_EQ(dv[0], d[0]);
      EXPECT_EQ(dv[1], d[1]);
    }
  }
  for (int K = 3; K <= 9; K += 2) EXPECT_GT(orders[K], 0) << "order " << K;
}

using emc::kernels::test::Element;
using emc::kernels::test::make_element;
using emc::kernels::test::random_u;

/// f . (u1 - u0) and V_e (W(u1) - W(u0)).
void work_and_energy(const Element& e, const k::LogHyperelastic& m, const double u0[4][3],
                     const double u1[4][3], double& work, double& dW, double& scale) {
  double f[12];
  k::em_tet4(e.G, e.Ve, m, k::Integrator::energy_momentum, u0, u1, f, nullptr);
  work = 0;
  for (int a = 0; a < 4; ++a)
    for (int i = 0; i < 3; ++i) work += f[3 * a + i] * (u1[a][i] - u0[a][i]);
  const double W0 = k::tet4_energy(e.G, e.Ve, m, u0), W1 = k::tet4_energy(e.G, e.Ve, m, u1);
  dW = W1 - W0;
  scale = std::fabs(W0) + std::fabs(W1);
}

// f . (u1 - u0) = V_e (W1 - W0) to round-off (1e-13 of W0 + W1) over random large deformations
// and over increments of 1e-1 down to 1e-9 about a large strain, on both sides of the series'
// switch; the plain mid-point rule misses it by far more.
TEST_P(Materials, DiscreteGradientDoesTheWorkOfTheEnergy) {
  const auto m = GetParam();
  const Element e = make_element();
  std::mt19937 rng(4);
  double worst = 0;
  int series = 0, direct = 0;
  for (int trial = 0; trial < 50; ++trial) {
    double u0[4][3], u1[4][3], du[4][3], work, dW, scale;
    random_u(rng, 0.3, u0);
    random_u(rng, 0.3, u1);
    work_and_energy(e, m, u0, u1, work, dW, scale);
    worst = std::max(worst, std::fabs(work - dW) / scale);
    random_u(rng, 1.0, du);
    for (double size = 1e-1; size >= 1e-9; size /= 10) {
      for (int a = 0; a < 4; ++a)
        for (int i = 0; i < 3; ++i) u1[a][i] = u0[a][i] + size * du[a][i];
      work_and_energy(e, m, u0, u1, work, dW, scale);
      worst = std::max(worst, std::fabs(work - dW) / scale);
      double H0[3][3], H1[3][3], E0[3][3], E1[3][3];
      k::displacement_gradient(e.G, u0, H0);
      k::displacement_gradient(e.G, u1, H1);
      k::green_strain(H0, E0);
      k::green_strain(H1, E1);
      k::DiscreteGradient dg;
      k::discrete_gradient(m, E0, E1, dg);
      (dg.series ? series : direct)++;
    }
  }
  std::printf("worst |f . du - dW| / (|W0| + |W1|) = %.2e (%d series, %d direct)\n", worst, series,
              direct);
  EXPECT_LT(worst, 1e-13);
  EXPECT_GT(series, 100);
  EXPECT_GT(direct, 50);
}

/// |K - the central finite-difference Jacobian of the force in u1| / |K|.
double tangent_error(const Element& e, const k::LogHyperelastic& m, k::Integrator integ,
                     const double u0[4][3], const double u1[4][3], double h) {
  double f[12], K[12][12];
  k::em_tet4(e.G, e.Ve, m, integ, u0, u1, f, K);
  double err = 0, size = 0;
  for (int c = 0; c < 12; ++c) {
    double up[4][3], um[4][3], fp[12], fm[12];
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) up[a][i] = um[a][i] = u1[a][i];
    up[c / 3][c % 3] += h;
    um[c / 3][c % 3] -= h;
    k::em_tet4(e.G, e.Ve, m, integ, u0, up, fp, nullptr);
    k::em_tet4(e.G, e.Ve, m, integ, u0, um, fm, nullptr);
    for (int r = 0; r < 12; ++r) {
      const double d = K[r][c] - (fp[r] - fm[r]) / (2 * h);
      err += d * d;
      size += K[r][c] * K[r][c];
    }
  }
  return std::sqrt(err / size);
}

// The element tangent against central differences (step 1e-6), energy-momentum and mid-point,
// at large strain (u ~ 0.3) and with u1 next to u0 (|u1 - u0| = 1e-4 and 1e-8: the series; a
// step of 1e-6 then dominates dE and crosses the switch, one of 1e-8 stays below |u1 - u0|).
TEST_P(Materials, ElementTangentMatchesFiniteDifferences) {
  const auto m = GetParam();
  const Element e = make_element();
  std::mt19937 rng(5);
  for (int trial = 0; trial < 10; ++trial) {
    double u0[4][3], u1[4][3], du[4][3];
    random_u(rng, 0.3, u0);
    random_u(rng, 0.3, u1);
    for (auto integ : {k::Integrator::energy_momentum, k::Integrator::midpoint})
      EXPECT_LT(tangent_error(e, m, integ, u0, u1, 1e-6), 1e-6) << "trial " << trial;
    random_u(rng, 1.0, du);
    for (double size : {1e-4, 1e-8}) {
      for (int a = 0; a < 4; ++a)
        for (int i = 0; i < 3; ++i) u1[a][i] = u0[a][i] + size * du[a][i];
      EXPECT_LT(tangent_error(e, m, k::Integrator::energy_momentum, u0, u1, 1e-6), 1e-6)
          << "trial " << trial << " |du| " << size;
      if (size == 1e-4) {  // a step below |u1 - u0| (round-off eps |f| / 1e-8: 1e-7 of K)
        EXPECT_LT(tangent_error(e, m, k::Integrator::energy_momentum, u0, u1, 1e-8), 1e-5)
            << "trial " << trial << " |du| " << size << ", step below it";
      }
    }
  }
}

/// The reference element tangent: D applied to each of the 12 strain variations
/// X_Bj = sym(F_x^T (e_j (x) G_B)) (discrete_gradient_tangent; the mid-point rule CC / 2), then
/// K_AB,ij = V_e [1/2 (G_A . S_alg G_B) d_ij + (F_{n+1/2} D(X_Bj) G_A)_i] (docs/THEORY.md §12.4).
void reference_tangent(const Element& e, const k::LogHyperelastic& m, k::Integrator integ,
                       const double u0[4][3], const double u1[4][3], double K[12][12]) {
  double H0[3][3], H1[3][3], Hm[3][3], F1[3][3], Fm[3][3], S[3][3], Ci[3][3], l = 0;
  k::step_kinematics(e.G, u0, u1, H0, H1, Hm, F1, Fm);
  const bool em = integ == k::Integrator::energy_momentum;
  k::DiscreteGradient dg{};
  if (em) {
    double E0[3][3], E1[3][3];
    k::green_strain(H0, E0);
    k::green_strain(H1, E1);
    k::discrete_gradient(m, E0, E1, dg);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) S[i][j] = dg.S[i][j];
  } else {
    double Ea[3][3];
    k::green_strain(Hm, Ea);
    k::hyper_detail::inverse_C(Ea, Ci);
    l = k::log_J(Ea);
    k::hyper_stress(m, Ea, Ci, l, S);
  }
  const double(*Fx)[3] = em ? F1 : Fm;
  for (int B = 0; B < 4; ++B)
    for (int j = 0; j < 3; ++j) {
      double X[3][3], T[3][3];
      for (int p = 0; p < 3; ++p)
        for (int q = 0; q < 3; ++q) X[p][q] = 0.5 * (Fx[j][p] * e.G[B][q] + Fx[j][q] * e.G[B][p]);
      if (em) {
        k::discrete_gradient_tangent(m, dg, X, T);
      } else {
        k::hyper_tangent(m, Ci, l, X, T);
        for (int p = 0; p < 3; ++p)
          for (int q = 0; q < 3; ++q) T[p][q] *= 0.5;
      }
      for (int A = 0; A < 4; ++A)
        for (int i = 0; i < 3; ++i) {
          double s = 0, GSG = 0;
          for (int p = 0; p < 3; ++p)
            for (int q = 0; q < 3; ++q) {
              s += Fm[i][p] * T[p][q] * e.G[A][q];
              GSG += e.G[A][p] * S[p][q] * e.G[B][q];
            }
          K[3 * A + i][3 * B + j] = e.Ve * s + (i == j ? 0.5 * e.Ve * GSG : 0.0);
        }
    }
}

// The closed-form tangent of em_tet4 equals the reference strain variation by variation to
// 1e-14 of |K|, energy-momentum and mid-point, at large strain (the direct branch), with u1
// within 1e-3 to 1e-9 of u0 (the series, every order) and at u1 = u0 (dE = 0).
TEST_P(Materials, ClosedFormTangentEqualsThePerVariationOne) {
  const auto m = GetParam();
  const Element e = make_element();
  std::mt19937 rng(8);
  double worst = 0;
  for (int trial = 0; trial < 10; ++trial) {
    double u0[4][3], u1[4][3], du[4][3];
    random_u(rng, 0.3, u0);
    random_u(rng, 0.3, u1);
    random_u(rng, 1.0, du);
    for (const double size : {-1.0, 1e-3, 1e-5, 1e-7, 1e-9, 0.0}) {
      if (size >= 0)
        for (int a = 0; a < 4; ++a)
          for (int i = 0; i < 3; ++i) u1[a][i] = u0[a][i] + size * du[a][i];
      for (auto integ : {k::Integrator::energy_momentum, k::Integrator::midpoint}) {
        double f[12], K[12][12], R[12][12], err = 0, big = 0;
        k::em_tet4(e.G, e.Ve, m, integ, u0, u1, f, K);
        reference_tangent(e, m, integ, u0, u1, R);
        for (int r = 0; r < 12; ++r)
          for (int c = 0; c < 12; ++c) {
            err += (K[r][c] - R[r][c]) * (K[r][c] - R[r][c]);
            big += R[r][c] * R[r][c];
          }
        worst = std::max(worst, std::sqrt(err / big));
        EXPECT_LT(std::sqrt(err / big), 1e-14) << "trial " << trial << " |du| " << size;
      }
    }
  }
  std::printf("worst |K - K_ref| / |K_ref| = %.2e\n", worst);
}

// Near dE = 0 on the series path at each of its orders (|u1 - u0| from 1e-3 down to 1e-7:
// |M| from about 1e-3, order 7, to 1e-7, order 3), the tangent against central differences with
// a step of 1e-2 of |u1 - u0| (the series throughout; round-off eps |f| / step: 1e-7 of |K| at
// the smallest step).
TEST_P(Materials, ElementTangentOnTheSeriesMatchesFiniteDifferences) {
  const auto m = GetParam();
  const Element e = make_element();
  std::mt19937 rng(9);
  int orders[10] = {};
  for (int trial = 0; trial < 5; ++trial) {
    double u0[4][3], u1[4][3], du[4][3];
    random_u(rng, 0.3, u0);
    random_u(rng, 1.0, du);
    for (const double size : {1e-3, 3e-4, 1e-4, 1e-5, 1e-6, 1e-7}) {
      for (int a = 0; a < 4; ++a)
        for (int i = 0; i < 3; ++i) u1[a][i] = u0[a][i] + size * du[a][i];
      double H0[3][3], H1[3][3], E0[3][3], E1[3][3], Em[3][3], dE[3][3], Ci[3][3], M[3][3];
      k::displacement_gradient(e.G, u0, H0);
      k::displacement_gradient(e.G, u1, H1);
      k::green_strain(H0, E0);
      k::green_strain(H1, E1);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          Em[i][j] = 0.5 * (E0[i][j] + E1[i][j]);
          dE[i][j] = E1[i][j] - E0[i][j];
        }
      k::hyper_detail::inverse_C(Em, Ci);
      k::hyper_detail::mul(Ci, dE, M);
      ASSERT_LE(norm(M), k::kSeriesBound);
      ++orders[k::hyper_detail::series_order(dot(M, M))];
      EXPECT_LT(tangent_error(e, m, k::Integrator::energy_momentum, u0, u1, 1e-2 * size), 1e-6)
          << "trial " << trial << " |du| " << size;
    }
  }
  for (int K = 3; K <= 7; K += 2) EXPECT_GT(orders[K], 0) << "order " << K;
}

// A body starting from rest (u0 = 0, E_n = 0): W_{n+1} - W_n = W_{n+1} is O(|dE|^2), the
// smallest scale against which the series' remainder must stand below round-off (§12.3):
// f . u1 = V_e W(u1) to 1e-14 of it on the series (every order: |u1| from 1e-2 to 1e-8), to
// 1e-13 on the direct branch (its differences' round-off eps |l| against W = O(|M|^2): eps / |M|,
// 2e-14 just above the switch).
TEST_P(Materials, WorkFromRestIsTheEnergy) {
  const auto m = GetParam();
  const Element e = make_element();
  std::mt19937 rng(10);
  double worst = 0, worst_series = 0;
  for (int trial = 0; trial < 20; ++trial) {
    double zero[4][3] = {}, du[4][3], u1[4][3], work, dW, scale;
    random_u(rng, 1.0, du);
    for (double size = 1e-1; size >= 1e-8; size /= 10) {
      for (int a = 0; a < 4; ++a)
        for (int i = 0; i < 3; ++i) u1[a][i] = size * du[a][i];
      work_and_energy(e, m, zero, u1, work, dW, scale);
      double H1[3][3], E1[3][3], Z[3][3] = {};
      k::displacement_gradient(e.G, u1, H1);
      k::green_strain(H1, E1);
      k::DiscreteGradient dg;
      k::discrete_gradient(m, Z, E1, dg, false);
      const double err = std::fabs(work - dW) / scale;
      (dg.series ? worst_series : worst) = std::max(dg.series ? worst_series : worst, err);
      EXPECT_LT(err, dg.series ? 1e-14 : 1e-13) << "trial " << trial << " |u1| " << size;
    }
  }
  std::printf("worst |f . u1 - W1| / W1 = %.2e series, %.2e direct\n", worst_series, worst);
}

// A body near rest: the force of |H| ~ 1e-12 is the linear one 2 K(0) u to 1e-10 (no noise of
// eps (lambda + 2 mu) from C - I or J - 1); the forces sum to zero and have no moment about
// the mid-point configuration (1e-13 of the largest).
TEST_P(Materials, TinyStrainIsLinearAndForcesBalance) {
  const auto m = GetParam();
  const Element e = make_element();
  std::mt19937 rng(6);
  double zero[4][3] = {}, f0[12], K0[12][12];
  k::em_tet4(e.G, e.Ve, m, k::Integrator::energy_momentum, zero, zero, f0, K0);
  for (int trial = 0; trial < 10; ++trial) {
    double u[4][3], f[12];
    random_u(rng, 1e-12, u);
    k::em_tet4(e.G, e.Ve, m, k::Integrator::energy_momentum, u, u, f, nullptr);
    EXPECT_LT(emc::kernels::test::linear_force_error(K0, u, f), 1e-10) << "trial " << trial;
  }
  for (int trial = 0; trial < 20; ++trial) {
    double u0[4][3], u1[4][3], f[12];
    random_u(rng, 0.4, u0);
    random_u(rng, 0.4, u1);
    k::em_tet4(e.G, e.Ve, m, k::Integrator::energy_momentum, u0, u1, f, nullptr);
    EXPECT_LT(emc::kernels::test::force_imbalance(e, u0, u1, f), 1e-13) << "trial " << trial;
  }
}

INSTANTIATE_TEST_SUITE_P(NeoHookeanAndMooneyRivlin, Materials, ::testing::Values(kNeo, kMooney),
                         [](const auto& info) {
                           return info.index == 0 ? std::string("NeoHookean")
                                                  : std::string("MooneyRivlin");
                         });

}  // namespace
