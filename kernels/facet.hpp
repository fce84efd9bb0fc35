#pragma once
// Contact geometry of a 3-node master facet (docs/THEORY.md §2.2-§2.3):
// N = (1 - xi - eta, xi, eta), x(xi) = N_i x_mi, tau_xi = x_m2 - x_m1, tau_eta = x_m3 - x_m1,
// n = tau_xi x tau_eta / |.|, closest-point projection (CPP) by the 2x2 normal equations,
// gap g_N = (y - x(xi)) . n.
#include <Kokkos_Core.hpp>

#include "kernels/math.hpp"

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
  double c[3];
  cross(f.t1, f.t2, c);
  f.area2 = kernels::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
  for (int i = 0; i < 3; ++i) f.n[i] = f.area2 > 0 ? c[i] / f.area2 : 0.0;
  return f;
}

/// Shape functions N(xi) of the facet.
KOKKOS_INLINE_FUNCTION void facet_shape(const double xi[2], double N[3]) {
  N[0] = 1 - xi[0] - xi[1];
  N[1] = xi[0];
  N[2] = xi[1];
}

/// docs/THEORY.md §2.2: how far y lies from the facet's point x(xi) = sum_a N_a(xi) xm_a
/// (`distance`), and the facet's longest edge (`longest_edge`), the length its tolerances scale
/// with. A restored active entry must lie at its facet point (the restart's check).
KOKKOS_INLINE_FUNCTION void facet_point_distance(const double y[3], const double xm[3][3],
                                                 const double xi[2], double& distance,
                                                 double& longest_edge) {
  double N[3];
  facet_shape(xi, N);
  double r2 = 0, h2 = 0;
  for (int i = 0; i < 3; ++i) {
    const double p = N[0] * xm[0][i] + N[1] * xm[1][i] + N[2] * xm[2][i];
    r2 += (y[i] - p) * (y[i] - p);
  }
  for (int e = 0; e < 3; ++e) {
    double l2 = 0;
    for (int i = 0; i < 3; ++i)
      l2 += (xm[(e + 1) % 3][i] - xm[e][i]) * (xm[(e + 1) % 3][i] - xm[e][i]);
    h2 = l2 > h2 ? l2 : h2;
  }
  distance = kernels::sqrt(r2);
  longest_edge = kernels::sqrt(h2);
}

/// How far xi lies outside the facet in barycentric terms: -min(N) (<= 0 inside).
KOKKOS_INLINE_FUNCTION double facet_outside(const double xi[2]) {
  const double a = 1 - xi[0] - xi[1];
  double m = a < xi[0] ? a : xi[0];
  m = m < xi[1] ? m : xi[1];
  return -m;
}

/// What the CPP needs of a facet, independent of the point: its frame and the metric
/// g_ab = tau_a . tau_b of the 2x2 normal equations (the contact search keeps one per facet).
struct FacetMetric {
  Facet f;
  double g11, g12, g22, det;
};

KOKKOS_INLINE_FUNCTION FacetMetric facet_metric(const double xm[3][3]) {
  FacetMetric m;
  m.f = facet(xm);
  m.g11 = m.g12 = m.g22 = 0;
  for (int i = 0; i < 3; ++i) {
    m.g11 += m.f.t1[i] * m.f.t1[i];
    m.g12 += m.f.t1[i] * m.f.t2[i];
    m.g22 += m.f.t2[i] * m.f.t2[i];
  }
  m.det = m.g11 * m.g22 - m.g12 * m.g12;
  return m;
}

/// Closest-point projection of y on the facet's plane: xi and the gap g_N (docs/THEORY.md §2.3),
/// with the facet's metric. Returns false for a degenerate facet.
KOKKOS_INLINE_FUNCTION bool facet_cpp(const double y[3], const double xm[3][3],
                                      const FacetMetric& m, double xi[2], double& gap) {
  if (!(m.det > 0)) return false;
  double b1 = 0, b2 = 0;
  for (int i = 0; i < 3; ++i) {
    const double d = y[i] - xm[0][i];
    b1 += m.f.t1[i] * d;
    b2 += m.f.t2[i] * d;
  }
  xi[0] = (m.g22 * b1 - m.g12 * b2) / m.det;
  xi[1] = (m.g11 * b2 - m.g12 * b1) / m.det;
  double N[3];
  facet_shape(xi, N);
  gap = 0;
  for (int i = 0; i < 3; ++i)
    gap += (y[i] - N[0] * xm[0][i] - N[1] * xm[1][i] - N[2] * xm[2][i]) * m.f.n[i];
  return true;
}

/// The same for a facet given by its nodes only.
KOKKOS_INLINE_FUNCTION bool facet_cpp(const double y[3], const double xm[3][3], double xi[2],
                                      double& gap) {
  return facet_cpp(y, xm, facet_metric(xm), xi, gap);
}

/// The point of the facet closest to the plane point x(xi) (docs/THEORY.md §6.3: the xi of an
/// activated node is clamped to its facet) (the metric g_ab of tau_xi, tau_eta):
/// xi itself when inside, else its projection on the nearest edge, clamped to the edge's ends.
KOKKOS_INLINE_FUNCTION void facet_clamp(const FacetMetric& m, double xi[2]) {
  if (facet_outside(xi) <= 0) return;
  // edges as (start, direction) in (xi, eta): m1 -> m2, m1 -> m3, m2 -> m3
  const double a[3][2] = {{0, 0}, {0, 0}, {1, 0}}, d[3][2] = {{1, 0}, {0, 1}, {-1, 1}};
  double best[2] = {xi[0], xi[1]}, best_d2 = -1;
  for (int e = 0; e < 3; ++e) {
    const double r[2] = {xi[0] - a[e][0], xi[1] - a[e][1]};
    // |v|^2 in the facet's metric: v^T G v, G = [g11 g12; g12 g22]
    const double dd =
        m.g11 * d[e][0] * d[e][0] + 2 * m.g12 * d[e][0] * d[e][1] + m.g22 * d[e][1] * d[e][1];
    const double rd =
        m.g11 * r[0] * d[e][0] + m.g12 * (r[0] * d[e][1] + r[1] * d[e][0]) + m.g22 * r[1] * d[e][1];
    double t = dd > 0 ? rd / dd : 0;
    t = t < 0 ? 0 : (t > 1 ? 1 : t);
    const double p[2] = {a[e][0] + t * d[e][0], a[e][1] + t * d[e][1]};
    const double q[2] = {xi[0] - p[0], xi[1] - p[1]};
    const double d2 = m.g11 * q[0] * q[0] + 2 * m.g12 * q[0] * q[1] + m.g22 * q[1] * q[1];
    if (best_d2 < 0 || d2 < best_d2) {
      best_d2 = d2;
      best[0] = p[0];
      best[1] = p[1];
    }
  }
  xi[0] = best[0];
  xi[1] = best[1];
}

}  // namespace emc::kernels
