#pragma once
// The compressible Neo-Hookean and Mooney-Rivlin materials (docs/THEORY.md §12) as one policy
// type, functions of the Green strain E = (C - I) / 2 with C = I + 2E, l = ln J = ln det C / 2:
//   W(E) = alpha (tr E - l) + beta (tr E)^2 + gamma E:E + b l^2,
//   S = dW/dE = 2 alpha C^-1 E + 2 beta tr E I + 2 gamma E + 2 b l C^-1,
//   CC : X = dS/dE : X = 2 (alpha - 2 b l) C^-1 X C^-1 + 2 beta tr X I + 2 gamma X
//            + 2 b (C^-1 : X) C^-1.
// Neo-Hookean mu/2 (I1 - 3) - mu l + lambda/2 l^2: alpha = mu, beta = gamma = 0, b = lambda/2.
// Mooney-Rivlin c1 (I1 - 3) + c2 (I2 - 3) - 2 (c1 + 2 c2) l + lambda/2 l^2: alpha = 2 c1 + 4 c2,
// beta = 2 c2, gamma = -2 c2, b = lambda/2 (I2 - 3 = 4 tr E + 2 (tr E)^2 - 2 E:E). At E = 0 both
// are linear elasticity with mu = alpha + gamma, lambda = 2 (beta + b) (§12.1). Every term is
// evaluated without the cancellation of C - I or J - 1 against 1 (C^-1 E in place of (I - C^-1) /
// 2, det C - 1 from the invariants of E, log1p), so that a body near rest carries no force noise of
// eps (lambda + 2 mu) (as kernels/svk.hpp's green_strain).
//
// The energy-momentum stress is Gonzalez's discrete gradient (§12.2): with dE = E_{n+1} - E_n,
//   S_algo = S(E_m) + delta dE / (dE : dE),  delta = W(E_{n+1}) - W(E_n) - S(E_m) : dE,
// E_m = (E_n + E_{n+1}) / 2, so that S_algo : dE = W(E_{n+1}) - W(E_n). The polynomial part of W
// is quadratic, for which delta = 0 exactly: delta comes from l and l^2 alone, directly where
// dE is large and by its series in M = C_m^-1 dE (C_m = I + 2 E_m) where |M| <= kSeriesBound,
// accurate to round-off there, whereas the difference W_{n+1} - W_n would cancel.
#include <Kokkos_Core.hpp>

#include "kernels/math.hpp"

namespace emc::kernels {

/// The coefficients of W (above).
struct LogHyperelastic {
  double alpha = 0, beta = 0, gamma = 0, b = 0;
};

/// Neo-Hookean from its Lame constants (the small-strain lambda and mu).
KOKKOS_INLINE_FUNCTION LogHyperelastic neo_hookean(double lambda, double mu) {
  return {mu, 0, 0, 0.5 * lambda};
}
/// Mooney-Rivlin from c1, c2 and the coefficient lambda of its l^2 term (the small-strain
/// constants are mu = 2 (c1 + c2) and lambda + 4 c2).
KOKKOS_INLINE_FUNCTION LogHyperelastic mooney_rivlin(double c1, double c2, double lambda) {
  return {2 * c1 + 4 * c2, 2 * c2, -2 * c2, 0.5 * lambda};
}

namespace hyper_detail {

using M3 = double[3][3];

KOKKOS_INLINE_FUNCTION double trace(const M3 a) {
  return a[0][0] + a[1][1] + a[2][2];
}
KOKKOS_INLINE_FUNCTION double dot(const M3 a, const M3 b) {
  double s = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) s += a[i][j] * b[i][j];
  return s;
}
KOKKOS_INLINE_FUNCTION void mul(const M3 a, const M3 b, M3 c) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double s = 0;
      for (int k = 0; k < 3; ++k) s += a[i][k] * b[k][j];
      c[i][j] = s;
    }
}
/// c = (a + a^T) / 2.
KOKKOS_INLINE_FUNCTION void sym(const M3 a, M3 c) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) c[i][j] = 0.5 * (a[i][j] + a[j][i]);
}
KOKKOS_INLINE_FUNCTION double det(const M3 a) {
  return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
         a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
         a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
}

/// det(I + 2E) - 1 = 2 tr E + 4 I2(E) + 8 det E (E symmetric): no cancellation against 1.
KOKKOS_INLINE_FUNCTION double det_C_minus_one(const M3 E) {
  const double t = trace(E);
  return 2 * t + 2 * (t * t - dot(E, E)) + 8 * det(E);
}

/// C^-1 = (I + 2E)^-1 (symmetric) by cofactors.
KOKKOS_INLINE_FUNCTION void inverse_C(const M3 E, M3 Ci) {
  M3 C;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) C[i][j] = (i == j ? 1.0 : 0.0) + 2 * E[i][j];
  const double d = 1 + det_C_minus_one(E);
  Ci[0][0] = (C[1][1] * C[2][2] - C[1][2] * C[2][1]) / d;
  Ci[0][1] = (C[0][2] * C[2][1] - C[0][1] * C[2][2]) / d;
  Ci[0][2] = (C[0][1] * C[1][2] - C[0][2] * C[1][1]) / d;
  Ci[1][1] = (C[0][0] * C[2][2] - C[0][2] * C[2][0]) / d;
  Ci[1][2] = (C[0][2] * C[1][0] - C[0][0] * C[1][2]) / d;
  Ci[2][2] = (C[0][0] * C[1][1] - C[0][1] * C[1][0]) / d;
  Ci[1][0] = Ci[0][1];
  Ci[2][0] = Ci[0][2];
  Ci[2][1] = Ci[1][2];
}

}  // namespace hyper_detail

/// l = ln J = ln det C / 2 (NaN where det C <= 0: an inverted element).
KOKKOS_INLINE_FUNCTION double log_J(const double E[3][3]) {
  return 0.5 * kernels::log1p(hyper_detail::det_C_minus_one(E));
}

/// tr E - l, without their cancellation near E = 0: with y = (det C - 1) / 2,
/// tr E - l = (tr E - y) + (y - ln(1 + 2y) / 2), the first exact in the invariants of E, the
/// second by its series for |2y| < 1e-2 (terms to (2y)^10: relative 1e-20).
KOKKOS_INLINE_FUNCTION double trace_minus_log_J(const double E[3][3]) {
  using namespace hyper_detail;
  const double t = trace(E);
  const double x = det_C_minus_one(E);                    // 2y
  const double head = -(t * t - dot(E, E)) - 4 * det(E);  // tr E - y
  if (!(kernels::fabs(x) < 1e-2)) return t - 0.5 * kernels::log1p(x);
  double tail = 0, p = x;  // y - log1p(x)/2 = -sum_{k>=2} (-1)^{k+1} x^k / (2k)
  for (int k = 2; k <= 10; ++k) {
    p *= x;  // x^k
    tail -= ((k % 2) ? 1.0 : -1.0) * p / (2 * k);
  }
  return head + tail;
}

/// W(E) per unit reference volume.
KOKKOS_INLINE_FUNCTION double hyper_energy(const LogHyperelastic& m, const double E[3][3]) {
  using namespace hyper_detail;
  const double t = trace(E), l = log_J(E);
  return m.alpha * trace_minus_log_J(E) + m.beta * t * t + m.gamma * dot(E, E) + m.b * l * l;
}

/// S(E) = dW/dE, given C^-1 and l of E.
KOKKOS_INLINE_FUNCTION void hyper_stress(const LogHyperelastic& m, const double E[3][3],
                                         const double Ci[3][3], double l, double S[3][3]) {
  using namespace hyper_detail;
  M3 CE, sCE;
  mul(Ci, E, CE);
  sym(CE, sCE);
  const double t = trace(E);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      S[i][j] = 2 * m.alpha * sCE[i][j] + (i == j ? 2 * m.beta * t : 0.0) + 2 * m.gamma * E[i][j] +
                2 * m.b * l * Ci[i][j];
}
/// S(E) alone.
KOKKOS_INLINE_FUNCTION void hyper_stress(const LogHyperelastic& m, const double E[3][3],
                                         double S[3][3]) {
  double Ci[3][3];
  hyper_detail::inverse_C(E, Ci);
  hyper_stress(m, E, Ci, log_J(E), S);
}

/// out = CC(E) : X (X symmetric), given C^-1 and l of E.
KOKKOS_INLINE_FUNCTION void hyper_tangent(const LogHyperelastic& m, const double Ci[3][3], double l,
                                          const double X[3][3], double out[3][3]) {
  using namespace hyper_detail;
  M3 CX, CXC;
  mul(Ci, X, CX);
  mul(CX, Ci, CXC);
  const double tX = trace(X), cx = dot(Ci, X), a = 2 * (m.alpha - 2 * m.b * l);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      out[i][j] = a * 0.5 * (CXC[i][j] + CXC[j][i]) + (i == j ? 2 * m.beta * tX : 0.0) +
                  2 * m.gamma * X[i][j] + 2 * m.b * cx * Ci[i][j];
}

/// |M| (Frobenius) up to which delta is summed as a series: terms to M^9 leave |M|^11, below
/// the round-off of W_{n+1} - W_n (relative |M|) for |M| <= 1e-2 (docs/THEORY.md §12.3).
constexpr double kSeriesBound = 1e-2;

/// Gonzalez's discrete gradient of W between E0 = E_n and E1 = E_{n+1}, and what its derivative
/// with respect to E1 needs: dS_algo = CC(E_m) : dE1 / 2 + r dE1 + dE (Q : dE1).
struct DiscreteGradient {
  double S[3][3];       ///< S_algo
  double Ci[3][3];      ///< C_m^-1
  double l = 0;         ///< l(E_m)
  double r = 0;         ///< delta / (dE : dE) (0 where dE = 0)
  double Q[3][3];       ///< (d delta / dE1) / (dE : dE) - 2 delta dE / (dE : dE)^2
  double dE[3][3];      ///< E1 - E0
  double delta = 0;     ///< W(E1) - W(E0) - S(E_m) : dE
  bool series = false;  ///< delta from its series
};

namespace hyper_detail {

/// The log terms' delta_1 = l1 - l0 - C_m^-1 : dE and delta_2 = l1^2 - l0^2 - 2 l_m C_m^-1 : dE
/// and their gradients with respect to E1, by the series in M = C_m^-1 dE: with
/// l(s) = l_m + sum_k c_k s^k along E_m + s dE / 2 (c_k = (-1)^(k+1) tr(M^k) / (2k)),
/// delta_1 = 2 sum_{k odd >= 3} c_k and delta_2 = 2 sum_{k odd >= 3} e_k, e_k = sum_i c_i c_{k-i};
/// d tr(M^k) / dE1 = k sym((I - M) M^(k-1) C_m^-1). g1 = g2 = nullptr: the values alone.
KOKKOS_INLINE_FUNCTION void log_deltas_series(const M3 Ci, double lm, const M3 M, double d[2],
                                              M3 g1, M3 g2) {
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
    if (g1) {
      mul(IM, P, A);
      mul(A, Ci, B);
      sym(B, gc[k]);
    }
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        if (g1) gc[k][i][j] *= sign;
        P[i][j] = Pk[i][j];
      }
  }
  d[0] = d[1] = 0;
  for (int k = 3; k <= K; k += 2) {
    d[0] += 2 * c[k];
    for (int n = 0; n <= k; ++n) d[1] += 2 * c[n] * c[k - n];
  }
  if (!g1) return;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) g1[i][j] = g2[i][j] = 0;
  for (int k = 3; k <= K; k += 2) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        g1[i][j] += 2 * gc[k][i][j];
        double s = 0;
        for (int n = 0; n <= k; ++n) s += c[k - n] * gc[n][i][j];
        g2[i][j] += 4 * s;
      }
  }
}

/// The same directly: l1, l0 and C_1^-1 from E1, E0 (g1 = g2 = nullptr: the values alone).
KOKKOS_INLINE_FUNCTION void log_deltas_direct(const M3 E0, const M3 E1, const M3 Cim, double lm,
                                              const M3 dE, double d[2], M3 g1, M3 g2) {
  const double l0 = log_J(E0), l1 = log_J(E1), cd = dot(Cim, dE);
  d[0] = l1 - l0 - cd;
  d[1] = (l1 - l0) * (l1 + l0) - 2 * lm * cd;
  if (!g1) return;
  M3 Ci1, T, CdC;
  inverse_C(E1, Ci1);
  mul(Cim, dE, T);
  mul(T, Cim, CdC);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double s = 0.5 * (CdC[i][j] + CdC[j][i]);
      g1[i][j] = Ci1[i][j] - Cim[i][j] + s;
      g2[i][j] = 2 * l1 * Ci1[i][j] - cd * Cim[i][j] - 2 * lm * (Cim[i][j] - s);
    }
}

}  // namespace hyper_detail

/// The discrete gradient between E0 and E1 (above, docs/THEORY.md §12.2-§12.4); r and Q (what
/// the tangent needs beyond S_algo) only if `tangent` (a residual alone skips their cost).
KOKKOS_INLINE_FUNCTION void discrete_gradient(const LogHyperelastic& m, const double E0[3][3],
                                              const double E1[3][3], DiscreteGradient& out,
                                              bool tangent = true) {
  using namespace hyper_detail;
  M3 Em, M;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      Em[i][j] = 0.5 * (E0[i][j] + E1[i][j]);
      out.dE[i][j] = E1[i][j] - E0[i][j];
    }
  inverse_C(Em, out.Ci);
  out.l = log_J(Em);
  hyper_stress(m, Em, out.Ci, out.l, out.S);
  mul(out.Ci, out.dE, M);
  const double n = dot(out.dE, out.dE);
  double d[2];
  M3 g1, g2;
  out.series = dot(M, M) <= kSeriesBound * kSeriesBound;
  if (out.series)
    log_deltas_series(out.Ci, out.l, M, d, tangent ? g1 : nullptr, tangent ? g2 : nullptr);
  else
    log_deltas_direct(E0, E1, out.Ci, out.l, out.dE, d, tangent ? g1 : nullptr,
                      tangent ? g2 : nullptr);
  out.delta = -m.alpha * d[0] + m.b * d[1];
  const bool moved = n > 1e-280;  // dE = 0 (or denormal): S_algo = S(E_m), r = Q = 0
  out.r = moved ? out.delta / n : 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double g = tangent ? -m.alpha * g1[i][j] + m.b * g2[i][j] : 0.0;
      out.Q[i][j] = moved && tangent ? g / n - 2 * out.delta * out.dE[i][j] / (n * n) : 0.0;
      out.S[i][j] += out.r * out.dE[i][j];
    }
}

/// dS_algo for a change X of E1 (symmetric): CC(E_m) : X / 2 + r X + dE (Q : X).
KOKKOS_INLINE_FUNCTION void discrete_gradient_tangent(const LogHyperelastic& m,
                                                      const DiscreteGradient& dg,
                                                      const double X[3][3], double out[3][3]) {
  hyper_tangent(m, dg.Ci, dg.l, X, out);
  const double q = hyper_detail::dot(dg.Q, X);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out[i][j] = 0.5 * out[i][j] + dg.r * X[i][j] + q * dg.dE[i][j];
}

}  // namespace emc::kernels
