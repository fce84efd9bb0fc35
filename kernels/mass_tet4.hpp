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

}  // namespace emc::kernels
