#pragma once
// Per-element contributions to the monitored quantities at t_n (docs/THEORY.md §1.9, eq. 23-24):
//   kinetic 1/2 V_A . M_AB V_B, elastic W_e(E_n), potential -f_ext_A . u_A,
//   L = sum_A M_AB V_B, J = sum_A x_A x (M_AB V_B) about the origin;
//   also the mass and its first moment sum_AB M_AB x_B (centre of mass = moment / mass).
#include "kernels/em_tet4.hpp"
#include "kernels/mass_tet4.hpp"

namespace emc::kernels {

struct Monitors {
  double kinetic = 0, elastic = 0, potential = 0;
  double L[3] = {0, 0, 0}, J[3] = {0, 0, 0};
  double mass = 0, moment[3] = {0, 0, 0};

  Monitors() = default;
  KOKKOS_INLINE_FUNCTION Monitors& operator+=(const Monitors& o) {
    add(*this, o);
    return *this;
  }
#if KOKKOS_VERSION < 30700  // Kokkos before 3.7 joins threaded reductions through volatile
  /// The volatile join Kokkos 3.4's threaded (OpenMP) reductions call.
  KOKKOS_INLINE_FUNCTION void operator+=(const volatile Monitors& o) volatile {
    add(*this, o);
  }
  /// Copies from a volatile reduction value (Kokkos 3.4's threaded reductions): 0 + o.
  KOKKOS_INLINE_FUNCTION Monitors(const volatile Monitors& o) {
    add(*this, o);
  }
#endif
  // defaulted: host and device functions alike (CUDA ignores annotations on them)
  Monitors(const Monitors&) = default;
  Monitors& operator=(const Monitors&) = default;

 private:
  template <class A, class B>
  KOKKOS_INLINE_FUNCTION static void add(A& a, const B& o) {
    a.kinetic += o.kinetic;
    a.elastic += o.elastic;
    a.potential += o.potential;
    a.mass += o.mass;
    for (int i = 0; i < 3; ++i) {
      a.L[i] += o.L[i];
      a.J[i] += o.J[i];
      a.moment[i] += o.moment[i];
    }
  }
};

/// Adds the element's contribution; X: reference coordinates, u, V at t_n. moved: the element
/// has massless nodes (docs/THEORY.md §6.8): its kinetic energy, momenta and mass moment come
/// from the moved mass (fem::Discretization::monitors), its mass, elastic and potential energy
/// from here.
template <class Material>
KOKKOS_INLINE_FUNCTION void monitors_tet4(const double X[4][3], const double G[4][3], double Ve,
                                          const Material& m, double rho, const double grav[3],
                                          const double u[4][3], const double V[4][3], Monitors& out,
                                          bool moved = false) {
  double p[4][3] = {};
  if (!moved) mass_times(rho, Ve, V, p);
  const double row = moved ? 0.0 : 0.25 * rho * Ve;  // sum_B M_AB
  out.mass += rho * Ve;
  for (int a = 0; a < 4; ++a) {
    const double x[3] = {X[a][0] + u[a][0], X[a][1] + u[a][1], X[a][2] + u[a][2]};
    for (int i = 0; i < 3; ++i) {
      out.kinetic += 0.5 * V[a][i] * p[a][i];
      out.potential -= rho * Ve * grav[i] / 4.0 * u[a][i];
      out.L[i] += p[a][i];
      out.moment[i] += row * x[i];
    }
    out.J[0] += x[1] * p[a][2] - x[2] * p[a][1];
    out.J[1] += x[2] * p[a][0] - x[0] * p[a][2];
    out.J[2] += x[0] * p[a][1] - x[1] * p[a][0];
  }
  out.elastic += tet4_energy(G, Ve, m, u);
}

}  // namespace emc::kernels
