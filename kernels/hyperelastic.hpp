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
// accurate to round-off there, whereas the difference W_{n+1} - W_n would cancel; the series'
// terms follow from three of them by Cayley-Hamilton (docs/THEORY.md §12.3).
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

/// Entry p = 0..5 of the upper half of a symmetric 3 x 3 matrix: (0,0) (1,1) (2,2) (0,1) (0,2)
/// (1,2) (a loop over p unrolls to straight code where one over j >= i would not).
KOKKOS_INLINE_FUNCTION constexpr int up_i(int p) {
  return p < 3 ? p : (p < 5 ? 0 : 1);
}
KOKKOS_INLINE_FUNCTION constexpr int up_j(int p) {
  return p < 3 ? p : (p == 3 ? 1 : 2);
}

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

/// C^-1 = (I + 2E)^-1 (symmetric) by cofactors, given x = det C - 1 (det_C_minus_one).
KOKKOS_INLINE_FUNCTION void inverse_C(const M3 E, double x, M3 Ci) {
  M3 C;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) C[i][j] = (i == j ? 1.0 : 0.0) + 2 * E[i][j];
  const double d = 1 / (1 + x);  // 1 / det C
  Ci[0][0] = (C[1][1] * C[2][2] - C[1][2] * C[2][1]) * d;
  Ci[0][1] = (C[0][2] * C[2][1] - C[0][1] * C[2][2]) * d;
  Ci[0][2] = (C[0][1] * C[1][2] - C[0][2] * C[1][1]) * d;
  Ci[1][1] = (C[0][0] * C[2][2] - C[0][2] * C[2][0]) * d;
  Ci[1][2] = (C[0][2] * C[1][0] - C[0][0] * C[1][2]) * d;
  Ci[2][2] = (C[0][0] * C[1][1] - C[0][1] * C[1][0]) * d;
  Ci[1][0] = Ci[0][1];
  Ci[2][0] = Ci[0][2];
  Ci[2][1] = Ci[1][2];
}
/// C^-1 of E.
KOKKOS_INLINE_FUNCTION void inverse_C(const M3 E, M3 Ci) {
  inverse_C(E, det_C_minus_one(E), Ci);
}
/// C^-1 of E, and l = ln J (log_J below) from the same det C - 1.
KOKKOS_INLINE_FUNCTION double inverse_C_log_J(const M3 E, M3 Ci) {
  const double x = det_C_minus_one(E);
  inverse_C(E, x, Ci);
  return 0.5 * kernels::log1p(x);
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
  const double t = trace(E), c = 2 * m.b * l;
  for (int p = 0; p < 6; ++p) {  // 2 alpha sym(C^-1 E) = alpha (C^-1 E + E C^-1)
    const int i = up_i(p), j = up_j(p);
    double ce = 0;
    for (int k = 0; k < 3; ++k) ce += Ci[i][k] * E[k][j] + E[i][k] * Ci[k][j];
    S[i][j] = S[j][i] =
        m.alpha * ce + (i == j ? 2 * m.beta * t : 0.0) + 2 * m.gamma * E[i][j] + c * Ci[i][j];
  }
}
/// S(E) alone.
KOKKOS_INLINE_FUNCTION void hyper_stress(const LogHyperelastic& m, const double E[3][3],
                                         double S[3][3]) {
  double Ci[3][3];
  const double l = hyper_detail::inverse_C_log_J(E, Ci);
  hyper_stress(m, E, Ci, l, S);
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

/// |M| (Frobenius) up to which delta is summed as a series, to the order of series_order
/// (docs/THEORY.md §12.3).
constexpr double kSeriesBound = 1e-2;
/// The series stops at the first odd order K with |M|^K <= kSeriesTail: its remainder, of order
/// |M|^(K+2), is then below 1e-17 of |M|^2, the smallest scale of W_{n+1} - W_n (a body starting
/// from rest, docs/THEORY.md §12.3).
constexpr double kSeriesTail = 1e-17;
/// The largest order of the series (|M|^9 <= 1e-18 at kSeriesBound).
constexpr int kSeriesMaxOrder = 9;

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

/// The order K of the series of delta for |M|^2 = m2 (docs/THEORY.md §12.3): the first odd
/// K >= 3 with |M|^K <= kSeriesTail, at most kSeriesMaxOrder.
KOKKOS_INLINE_FUNCTION int series_order(double m2) {
  int K = 3;
  double p = m2 * m2 * m2;  // |M|^(2K)
  while (K < kSeriesMaxOrder && p > kSeriesTail * kSeriesTail) {
    p *= m2 * m2;
    K += 2;
  }
  return K;
}

/// The log terms' delta_1 = l1 - l0 - C_m^-1 : dE and delta_2 = l1^2 - l0^2 - 2 l_m C_m^-1 : dE
/// and their gradients g1, g2 with respect to E1, by the series in M = C_m^-1 dE to M^K (K odd,
/// docs/THEORY.md §12.3-§12.4): with l(s) = l_m + sum_k c_k s^k along E_m + s dE / 2,
/// c_k = (-1)^(k+1) p_k / (2k), p_k = tr(M^k), delta_1 = 2 sum_{k odd >= 3} c_k and
/// delta_2 = 2 sum_{k odd >= 3} sum_n c_n c_{k-n}. With R_k = M^k C_m^-1 (symmetric),
///   g1 = sum_{k=2..K} (-1)^k R_k,   g2 = 2 sum_{k=0..K} (-1)^k s_k R_k,
/// s_0 = c_2 + ... + c_K, s_1 = c_1 + ... + c_{K-1}, s_k = c_0 + ... + c_{K-k} (k >= 2). By
/// Cayley-Hamilton, M^k = I1 M^(k-1) - I2 M^(k-2) + I3 M^(k-3) (I1, I2, I3 the invariants of M):
/// p_k and R_k = x_k R_0 + y_k R_1 + z_k R_2 for k >= 3 follow by scalar recurrences from
/// R_1 = M C_m^-1, R_2 = M R_1 and p_1, p_2, p_3 = R_{k-1} : dE, two products in all.
/// g1 = g2 = nullptr: the values alone.
template <int K>
KOKKOS_INLINE_FUNCTION void log_deltas_series_to(const M3 Ci, double lm, const M3 M, const M3 dE,
                                                 double d[2], M3 g1, M3 g2) {
  // (-1)^(k+1) / (2k): c_k = wk[k] p_k
  constexpr double wk[10] = {0,   0.5,       -0.25,    1.0 / 6, -0.125,
                             0.1, -1.0 / 12, 1.0 / 14, -0.0625, 1.0 / 18};
  M3 R1, R2;
  for (int q = 0; q < 6; ++q) {  // the upper half of M C_m^-1, mirrored
    const int i = up_i(q), j = up_j(q);
    R1[i][j] = R1[j][i] = M[i][0] * Ci[0][j] + M[i][1] * Ci[1][j] + M[i][2] * Ci[2][j];
  }
  for (int q = 0; q < 6; ++q) {
    const int i = up_i(q), j = up_j(q);
    R2[i][j] = R2[j][i] = M[i][0] * R1[0][j] + M[i][1] * R1[1][j] + M[i][2] * R1[2][j];
  }
  double p[K + 1], c[K + 1];
  p[0] = 3;
  p[1] = dot(Ci, dE);
  p[2] = dot(R1, dE);
  p[3] = dot(R2, dE);
  const double I1 = p[1], I2 = 0.5 * (I1 * I1 - p[2]),
               I3 = (I1 * I1 * I1 - 3 * I1 * p[2] + 2 * p[3]) / 6;
  for (int k = 4; k <= K; ++k) p[k] = I1 * p[k - 1] - I2 * p[k - 2] + I3 * p[k - 3];
  c[0] = lm;
  for (int k = 1; k <= K; ++k) c[k] = wk[k] * p[k];
  d[0] = d[1] = 0;
  for (int k = K; k >= 3; k -= 2) {  // the small terms first
    double e = 0;
    for (int n = 0; 2 * n < k; ++n) e += c[n] * c[k - n];
    d[0] += 2 * c[k];
    d[1] += 4 * e;
  }
  if (!g1) return;
  double P[K + 1], s0 = 0;  // P_j = c_1 + ... + c_j
  P[0] = 0;
  for (int j = 1; j <= K; ++j) P[j] = P[j - 1] + c[j];
  for (int j = K; j >= 2; --j) s0 += c[j];
  // the weights of R_0, R_1, R_2 in g1 (a) and in g2 (b); r: (x, y, z) of R_k, R_{k-1}, R_{k-2}
  double a[3] = {0, 0, 1}, b[3] = {2 * s0, -2 * P[K - 1], 2 * (c[0] + P[K - 2])};
  double r[3][3] = {{0, 0, 1}, {0, 1, 0}, {1, 0, 0}};
  for (int k = 3; k <= K; ++k) {
    const double sg = (k % 2) ? -1.0 : 1.0, wg = 2 * sg * (c[0] + P[K - k]);
    for (int q = 0; q < 3; ++q) {
      const double v = I1 * r[0][q] - I2 * r[1][q] + I3 * r[2][q];
      r[2][q] = r[1][q];
      r[1][q] = r[0][q];
      r[0][q] = v;
      a[q] += sg * v;
      b[q] += wg * v;
    }
  }
  M3 h1, h2;  // locals, then stored
  for (int q = 0; q < 6; ++q) {
    const int i = up_i(q), j = up_j(q);
    h1[i][j] = h1[j][i] = a[0] * Ci[i][j] + a[1] * R1[i][j] + a[2] * R2[i][j];
    h2[i][j] = h2[j][i] = b[0] * Ci[i][j] + b[1] * R1[i][j] + b[2] * R2[i][j];
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) g1[i][j] = h1[i][j], g2[i][j] = h2[i][j];
}

/// log_deltas_series_to to the order of series_order (|M| <= kSeriesBound).
KOKKOS_INLINE_FUNCTION void log_deltas_series(const M3 Ci, double lm, const M3 M, const M3 dE,
                                              double d[2], M3 g1, M3 g2) {
  switch (series_order(dot(M, M))) {
    case 3:
      log_deltas_series_to<3>(Ci, lm, M, dE, d, g1, g2);
      break;
    case 5:
      log_deltas_series_to<5>(Ci, lm, M, dE, d, g1, g2);
      break;
    case 7:
      log_deltas_series_to<7>(Ci, lm, M, dE, d, g1, g2);
      break;
    default:
      log_deltas_series_to<kSeriesMaxOrder>(Ci, lm, M, dE, d, g1, g2);
  }
}

/// The same directly: l1, l0 and C_1^-1 from E1, E0, given M = C_m^-1 dE (C_m^-1 dE C_m^-1 =
/// M C_m^-1; g1 = g2 = nullptr: the values alone).
KOKKOS_INLINE_FUNCTION void log_deltas_direct(const M3 E0, const M3 E1, const M3 Cim, double lm,
                                              const M3 dE, const M3 M, double d[2], M3 g1, M3 g2) {
  const double l0 = log_J(E0), cd = dot(Cim, dE);
  M3 Ci1;
  const double l1 = g1 ? inverse_C_log_J(E1, Ci1) : log_J(E1);
  d[0] = l1 - l0 - cd;
  d[1] = (l1 - l0) * (l1 + l0) - 2 * lm * cd;
  if (!g1) return;
  M3 h1, h2;  // locals, then stored
  for (int q = 0; q < 6; ++q) {
    const int i = up_i(q), j = up_j(q);
    const double s = M[i][0] * Cim[0][j] + M[i][1] * Cim[1][j] + M[i][2] * Cim[2][j];
    h1[i][j] = h1[j][i] = Ci1[i][j] - Cim[i][j] + s;
    h2[i][j] = h2[j][i] = 2 * l1 * Ci1[i][j] - cd * Cim[i][j] - 2 * lm * (Cim[i][j] - s);
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) g1[i][j] = h1[i][j], g2[i][j] = h2[i][j];
}

}  // namespace hyper_detail

/// The discrete gradient between E0 and E1 (above, docs/THEORY.md §12.2-§12.4); r and Q (what
/// the tangent needs beyond S_algo) only if `tangent` (a residual alone skips their cost).
KOKKOS_INLINE_FUNCTION void discrete_gradient(const LogHyperelastic& m, const double E0[3][3],
                                              const double E1[3][3], DiscreteGradient& out,
                                              bool tangent = true) {
  using namespace hyper_detail;
  M3 Em, dE, Ci, S, M, g1, g2;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      Em[i][j] = 0.5 * (E0[i][j] + E1[i][j]);
      dE[i][j] = E1[i][j] - E0[i][j];
    }
  const double l = inverse_C_log_J(Em, Ci);
  hyper_stress(m, Em, Ci, l, S);
  mul(Ci, dE, M);
  const double n = dot(dE, dE);
  double d[2];
  const bool series = dot(M, M) <= kSeriesBound * kSeriesBound;
  if (series)
    log_deltas_series(Ci, l, M, dE, d, tangent ? g1 : nullptr, tangent ? g2 : nullptr);
  else
    log_deltas_direct(E0, E1, Ci, l, dE, M, d, tangent ? g1 : nullptr, tangent ? g2 : nullptr);
  const double delta = -m.alpha * d[0] + m.b * d[1];
  const bool moved = n > 1e-280;  // dE = 0 (or denormal): S_algo = S(E_m), r = Q = 0
  const double in = moved ? 1 / n : 0.0, r = delta * in;
  for (int p = 0; p < 6; ++p) {  // Q = (d delta / dE1 - 2 r dE) / (dE : dE); all symmetric
    const int i = up_i(p), j = up_j(p);
    const double g = tangent ? -m.alpha * g1[i][j] + m.b * g2[i][j] : 0.0;
    out.Q[i][j] = out.Q[j][i] = tangent ? (g - 2 * r * dE[i][j]) * in : 0.0;
    out.S[i][j] = out.S[j][i] = S[i][j] + r * dE[i][j];
    out.Ci[i][j] = out.Ci[j][i] = Ci[i][j];
    out.dE[i][j] = out.dE[j][i] = dE[i][j];
  }
  out.l = l;
  out.r = r;
  out.delta = delta;
  out.series = series;
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
