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

/// docs/THEORY.md §6.8: the element mass of an element with massless nodes, M'_e = T_e^T M_e T_e,
/// where node a of the element moves as sum_j W[a][j] v_j over the K supports j (W: 4 rows of K,
/// row-major; a massive node is its own support with weight 1, a massless node's row its affine
/// fit over massive nodes): M'_jk = rho V_e / 20 (sum_a W_aj W_ak + s_j s_k), s_j = sum_a W_aj
/// (M_e = rho V_e / 20 (I + 1 1^T)). M' (K x K, row-major) is symmetric positive semi-definite.
KOKKOS_INLINE_FUNCTION void moved_mass(double rho, double Ve, const double* W, int K, double* M) {
  const double c = rho * Ve / 20.0;
  for (int j = 0; j < K; ++j)
    for (int k = 0; k < K; ++k) {
      double ww = 0, sj = 0, sk = 0;
      for (int a = 0; a < 4; ++a) {
        ww += W[a * K + j] * W[a * K + k];
        sj += W[a * K + j];
        sk += W[a * K + k];
      }
      M[j * K + k] = c * (ww + sj * sk);
    }
}

}  // namespace emc::kernels
