#pragma once
// Saint-Venant-Kirchhoff material (docs/THEORY.md §1.2): E = (F^T F - I)/2 = (H + H^T + H^T H)/2,
// S(E) = lambda tr(E) I + 2 mu E, W = lambda/2 tr(E)^2 + mu E:E (per unit reference volume).
#include <Kokkos_Core.hpp>

#include "kernels/math.hpp"

namespace emc::kernels {

struct Lame {
  double lambda, mu;
};

/// Lame parameters from Young's modulus and Poisson's ratio.
KOKKOS_INLINE_FUNCTION Lame lame(double young, double poisson) {
  return {young * poisson / ((1 + poisson) * (1 - 2 * poisson)), young / (2 * (1 + poisson))};
}

/// E = (H + H^T + H^T H) / 2 from the displacement gradient H = F - I: the same E as
/// (F^T F - I) / 2 without the cancellation against I, whose round-off (eps, not eps |H|) would
/// put a force noise of about eps V_e (lambda + 2 mu) |G| on every node of a body near rest,
/// above the round-off floor of Newton's tolerance (docs/THEORY.md §1.6).
KOKKOS_INLINE_FUNCTION void green_strain(const double H[3][3], double E[3][3]) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double s = 0;
      for (int k = 0; k < 3; ++k) s += H[k][i] * H[k][j];
      E[i][j] = 0.5 * (H[i][j] + H[j][i] + s);
    }
}

KOKKOS_INLINE_FUNCTION void svk_stress(const Lame& m, const double E[3][3], double S[3][3]) {
  const double tr = E[0][0] + E[1][1] + E[2][2];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) S[i][j] = 2 * m.mu * E[i][j] + (i == j ? m.lambda * tr : 0.0);
}

/// Strain energy density W(E).
KOKKOS_INLINE_FUNCTION double svk_energy(const Lame& m, const double E[3][3]) {
  const double tr = E[0][0] + E[1][1] + E[2][2];
  double ee = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) ee += E[i][j] * E[i][j];
  return 0.5 * m.lambda * tr * tr + m.mu * ee;
}

/// Von Mises equivalent of the Cauchy stress sigma = F S F^T / det F.
KOKKOS_INLINE_FUNCTION double von_mises(const double F[3][3], const double S[3][3], double detF) {
  double FS[3][3], s[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      FS[i][j] = 0;
      for (int k = 0; k < 3; ++k) FS[i][j] += F[i][k] * S[k][j];
    }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      s[i][j] = 0;
      for (int k = 0; k < 3; ++k) s[i][j] += FS[i][k] * F[j][k];
      s[i][j] /= detF;
    }
  const double a = s[0][0] - s[1][1], b = s[1][1] - s[2][2], c = s[2][2] - s[0][0];
  const double sh = s[0][1] * s[0][1] + s[1][2] * s[1][2] + s[2][0] * s[2][0];
  return kernels::sqrt(0.5 * (a * a + b * b + c * c) + 3 * sh);
}

}  // namespace emc::kernels
