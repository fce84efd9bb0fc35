#pragma once
// One element's contribution to the residual of eq. 20 and to the Newton matrix
// (2/dt^2) M + K (docs/THEORY.md §1.4):
//   g_A = (2/dt^2) M_AB (u_{B,n+1} - u_{B,n}) - (2/dt) M_AB V_{B,n} + f_int_A - f_ext_A.
#include "kernels/em_tet4.hpp"
#include "kernels/mass_tet4.hpp"
#include "kernels/math.hpp"

namespace emc::kernels {

struct ElementState {
  double u0[4][3];  ///< u_n
  double V0[4][3];  ///< V_n
  double u1[4][3];  ///< u_{n+1} (current Newton iterate)
};

/// r[12]: element residual; A (optional): element Newton matrix; scale[12] (optional): sum of
/// the absolute values of the four terms of g plus bounds of the force that the round-off of
/// the displacements u_{n+1} themselves causes (docs/THEORY.md §1.6): through the stiffness, in
/// a stiff element in large rigid motion (V_e (lambda + 2 mu) |G_A| sum_B |u_B| |G_B|, weighted
/// 1e-3: the floor 100 eps |scale| of the §1 Newton tolerance then sits above the noise at which
/// the stiff thin disks of three_disks.xml stagnate; the figures are in perf/README.md
/// "Constants of the code, measured"), and through the inertia, (2/dt^2) sum_B M_AB |u_B|
/// weighted 1e-2 (ten times the noise of rounding u_{n+1}; it outgrows the inertia term's own
/// size after about 100 steps from the start, as |u| / |u_{n+1} - u_n| grows with the steps).
/// moved: the element has massless nodes (docs/THEORY.md §6.8), its mass term is assembled with
/// the moved mass (fem::Discretization) and left out here.
template <class Material>
KOKKOS_INLINE_FUNCTION void newton_tet4(const double G[4][3], double Ve, const Material& m,
                                        double rho, const double grav[3], Integrator integ,
                                        double dt, const ElementState& s, double r[12],
                                        double (*A)[12], double* scale, bool moved = false) {
  em_tet4(G, Ve, m, integ, s.u0, s.u1, r, A);  // r = f_int for now
  double du[4][3], Mdu[4][3] = {}, MV[4][3] = {};
  for (int a = 0; a < 4; ++a)
    for (int i = 0; i < 3; ++i) du[a][i] = s.u1[a][i] - s.u0[a][i];
  if (!moved) {
    mass_times(rho, Ve, du, Mdu);
    mass_times(rho, Ve, s.V0, MV);
  }
  const double c2 = 2.0 / (dt * dt), c1 = 2.0 / dt;
  double gnorm[4], ug = 0;
  for (int a = 0; a < 4; ++a) {
    gnorm[a] = kernels::sqrt(G[a][0] * G[a][0] + G[a][1] * G[a][1] + G[a][2] * G[a][2]);
    const double un =
        kernels::sqrt(s.u1[a][0] * s.u1[a][0] + s.u1[a][1] * s.u1[a][1] + s.u1[a][2] * s.u1[a][2]);
    ug += un * gnorm[a];
  }
  const double stiff = 1e-3 * Ve * stiffness(m) * ug;
  double ua[4][3], Mua[4][3] = {};  // M |u_{n+1}|: M's entries are >= 0 (moved: M' adds it)
  for (int a = 0; a < 4; ++a)
    for (int i = 0; i < 3; ++i) ua[a][i] = kernels::fabs(s.u1[a][i]);
  if (scale && !moved) mass_times(rho, Ve, ua, Mua);
  for (int a = 0; a < 4; ++a)
    for (int i = 0; i < 3; ++i) {
      const double fext = rho * Ve * grav[i] / 4.0;
      const double fint = r[3 * a + i];
      r[3 * a + i] = c2 * Mdu[a][i] - c1 * MV[a][i] + fint - fext;
      if (scale)
        scale[3 * a + i] = kernels::fabs(c2 * Mdu[a][i]) + kernels::fabs(c1 * MV[a][i]) +
                           kernels::fabs(fint) + kernels::fabs(fext) + stiff * gnorm[a] +
                           1e-2 * c2 * Mua[a][i];
    }
  if (A == nullptr || moved) return;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) {
      const double mab = c2 * mass_ab(rho, Ve, a, b);
      for (int i = 0; i < 3; ++i) A[3 * a + i][3 * b + i] += mab;
    }
}

}  // namespace emc::kernels
