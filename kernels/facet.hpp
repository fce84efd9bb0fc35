#pragma once
// Contact geometry of a 3-node master facet (ALGORITHM.md §2): N = (1 - xi - eta, xi, eta),
// x(xi) = N_i x_mi, tau_xi = x_m2 - x_m1, tau_eta = x_m3 - x_m1, n = tau_xi x tau_eta / |.|,
// closest-point projection (CPP) by the 2x2 normal equations, gap g_N = (y - x(xi)) . n.
#include <Kokkos_Core.hpp>

namespace emc::kernels {

struct Facet {
  double t1[3], t2[3];  ///< tau_xi, tau_eta
  double n[3];          ///< unit normal (outward from the master body)
  double area2;         ///< |tau_xi x tau_eta| (twice the area)
};

KOKKOS_INLINE_FUNCTION Facet facet(const double xm[3][3]) {
  Facet f;
  for (int i = 0; i < 3; ++i) {
    f.t1[i] = xm[1][i] - xm[0][i];
    f.t2[i] = xm[2][i] - xm[0][i];
  }
  const double c[3] = {f.t1[1] * f.t2[2] - f.t1[2] * f.t2[1], f.t1[2] * f.t2[0] - f.t1[0] * f.t2[2],
                       f.t1[0] * f.t2[1] - f.t1[1] * f.t2[0]};
  f.area2 = Kokkos::Experimental::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
  for (int i = 0; i < 3; ++i) f.n[i] = f.area2 > 0 ? c[i] / f.area2 : 0.0;
  return f;
}

/// Shape functions N(xi) of the facet.
KOKKOS_INLINE_FUNCTION void facet_shape(const double xi[2], double N[3]) {
  N[0] = 1 - xi[0] - xi[1];
  N[1] = xi[0];
  N[2] = xi[1];
}

/// How far xi lies outside the facet in barycentric terms: -min(N) (<= 0 inside).
KOKKOS_INLINE_FUNCTION double facet_outside(const double xi[2]) {
  const double a = 1 - xi[0] - xi[1];
  double m = a < xi[0] ? a : xi[0];
  m = m < xi[1] ? m : xi[1];
  return -m;
}

/// Closest-point projection of y on the facet's plane: xi and the gap g_N (ALGORITHM.md §2).
/// Returns false for a degenerate facet.
KOKKOS_INLINE_FUNCTION bool facet_cpp(const double y[3], const double xm[3][3], double xi[2],
                                      double& gap) {
  const Facet f = facet(xm);
  double d[3];
  for (int i = 0; i < 3; ++i) d[i] = y[i] - xm[0][i];
  double g11 = 0, g12 = 0, g22 = 0, b1 = 0, b2 = 0;
  for (int i = 0; i < 3; ++i) {
    g11 += f.t1[i] * f.t1[i];
    g12 += f.t1[i] * f.t2[i];
    g22 += f.t2[i] * f.t2[i];
    b1 += f.t1[i] * d[i];
    b2 += f.t2[i] * d[i];
  }
  const double det = g11 * g22 - g12 * g12;
  if (!(det > 0)) return false;
  xi[0] = (g22 * b1 - g12 * b2) / det;
  xi[1] = (g11 * b2 - g12 * b1) / det;
  double N[3];
  facet_shape(xi, N);
  gap = 0;
  for (int i = 0; i < 3; ++i)
    gap += (y[i] - N[0] * xm[0][i] - N[1] * xm[1][i] - N[2] * xm[2][i]) * f.n[i];
  return true;
}

}  // namespace emc::kernels
