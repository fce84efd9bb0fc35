#pragma once
// P1 tetrahedron geometry (docs/THEORY.md §1.1): shape gradients G_A = grad_X N_A, reference
// volume V_e, deformation gradient F = I + sum_A u_A (x) G_A. Pure functions of fixed-size
// arrays, callable from Kokkos kernels.
#include <Kokkos_Core.hpp>

namespace emc::kernels {

/// 3x3 determinant.
KOKKOS_INLINE_FUNCTION double det3(const double a[3][3]) {
  return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
         a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
         a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
}

/// Signed volume of the tet with corner coordinates x[4][3].
KOKKOS_INLINE_FUNCTION double tet_volume(const double x[4][3]) {
  double J[3][3];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) J[i][k] = x[k + 1][i] - x[0][i];
  return det3(J) / 6.0;
}

/// Shape-function gradients G[A][j] = dN_A/dX_j and the volume V_e; returns V_e (<= 0 means
/// an inverted or degenerate element, G is then left unset).
KOKKOS_INLINE_FUNCTION double tet_gradients(const double X[4][3], double G[4][3]) {
  double J[3][3];  // J[i][k] = dX_i/dxi_k
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) J[i][k] = X[k + 1][i] - X[0][i];
  const double d = det3(J);
  if (!(d > 0)) return d / 6.0;
  // inverse of J: Ji[k][i] = dxi_k/dX_i
  double Ji[3][3];
  Ji[0][0] = (J[1][1] * J[2][2] - J[1][2] * J[2][1]) / d;
  Ji[0][1] = (J[0][2] * J[2][1] - J[0][1] * J[2][2]) / d;
  Ji[0][2] = (J[0][1] * J[1][2] - J[0][2] * J[1][1]) / d;
  Ji[1][0] = (J[1][2] * J[2][0] - J[1][0] * J[2][2]) / d;
  Ji[1][1] = (J[0][0] * J[2][2] - J[0][2] * J[2][0]) / d;
  Ji[1][2] = (J[0][2] * J[1][0] - J[0][0] * J[1][2]) / d;
  Ji[2][0] = (J[1][0] * J[2][1] - J[1][1] * J[2][0]) / d;
  Ji[2][1] = (J[0][1] * J[2][0] - J[0][0] * J[2][1]) / d;
  Ji[2][2] = (J[0][0] * J[1][1] - J[0][1] * J[1][0]) / d;
  for (int j = 0; j < 3; ++j) {
    G[0][j] = -(Ji[0][j] + Ji[1][j] + Ji[2][j]);
    for (int k = 0; k < 3; ++k) G[k + 1][j] = Ji[k][j];
  }
  return d / 6.0;
}

/// H = sum_A u_A (x) G_A, the displacement gradient (F = I + H, docs/THEORY.md §1.1).
KOKKOS_INLINE_FUNCTION void displacement_gradient(const double G[4][3], const double u[4][3],
                                                  double H[3][3]) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double s = 0;
      for (int A = 0; A < 4; ++A) s += u[A][i] * G[A][j];
      H[i][j] = s;
    }
}

/// F = I + H.
KOKKOS_INLINE_FUNCTION void identity_plus(const double H[3][3], double F[3][3]) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) F[i][j] = H[i][j] + (i == j ? 1.0 : 0.0);
}

/// F = I + sum_A u_A (x) G_A  (docs/THEORY.md §1.1).
KOKKOS_INLINE_FUNCTION void deformation_gradient(const double G[4][3], const double u[4][3],
                                                 double F[3][3]) {
  double H[3][3];
  displacement_gradient(G, u, H);
  identity_plus(H, F);
}

}  // namespace emc::kernels
