#pragma once
// Consistent mass and gravity load of a P1 tetrahedron (docs/THEORY.md §1.3):
//   M_AB = rho V_e (1 + delta_AB) / 20 (times I_3),   f_ext_A = rho V_e g / 4.
#include <Kokkos_Core.hpp>

namespace emc::kernels {

/// M_AB for nodes A, B of the element (scalar; the 3x3 block is this times identity).
KOKKOS_INLINE_FUNCTION double mass_ab(double rho, double Ve, int A, int B) {
  return rho * Ve * (A == B ? 2.0 : 1.0) / 20.0;
}

/// p_A = sum_B M_AB v_B = rho V_e / 20 (v_A + sum_B v_B).
KOKKOS_INLINE_FUNCTION void mass_times(double rho, double Ve, const double v[4][3],
                                       double p[4][3]) {
  const double c = rho * Ve / 20.0;
  for (int i = 0; i < 3; ++i) {
    const double s = v[0][i] + v[1][i] + v[2][i] + v[3][i];
    for (int A = 0; A < 4; ++A) p[A][i] = c * (v[A][i] + s);
  }
}

/// docs/THEORY.md §6.8: the element mass with the mass of its massless nodes (bit a of `massless`
/// set for node a) moved to its other nodes, M' = T^T M T with (T v)_a = v_a for a massive node
/// and the mean of the massive nodes' v for a massless one: symmetric, the same total mass
/// (T keeps constants), zero rows and columns at the massless nodes. An element whose four
/// nodes are all massless (or none) keeps M.
KOKKOS_INLINE_FUNCTION void mass_times(double rho, double Ve, int massless, const double v[4][3],
                                       double p[4][3]) {
  int heavy = 0;
  for (int a = 0; a < 4; ++a) heavy += ((massless >> a) & 1) == 0;
  if (heavy == 4 || heavy == 0) {
    mass_times(rho, Ve, v, p);
    return;
  }
  double w[4][3], q[4][3];
  for (int i = 0; i < 3; ++i) {
    double mean = 0;
    for (int a = 0; a < 4; ++a) mean += ((massless >> a) & 1) ? 0.0 : v[a][i];
    mean /= heavy;
    for (int a = 0; a < 4; ++a) w[a][i] = ((massless >> a) & 1) ? mean : v[a][i];
  }
  mass_times(rho, Ve, w, q);
  for (int i = 0; i < 3; ++i) {
    double light = 0;
    for (int a = 0; a < 4; ++a) light += ((massless >> a) & 1) ? q[a][i] : 0.0;
    for (int a = 0; a < 4; ++a) p[a][i] = ((massless >> a) & 1) ? 0.0 : q[a][i] + light / heavy;
  }
}

/// M'_AB of the mass above (scalar; the 3x3 block is this times identity).
KOKKOS_INLINE_FUNCTION void mass_matrix(double rho, double Ve, int massless, double M[4][4]) {
  if (massless == 0 || massless == 15) {
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) M[a][b] = mass_ab(rho, Ve, a, b);
    return;
  }
  for (int b = 0; b < 4; ++b) {
    double e[4][3] = {}, p[4][3];
    e[b][0] = 1;
    mass_times(rho, Ve, massless, e, p);
    for (int a = 0; a < 4; ++a) M[a][b] = p[a][0];
  }
}

}  // namespace emc::kernels
