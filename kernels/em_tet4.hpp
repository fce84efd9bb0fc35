#pragma once
// Energy-momentum internal force of a P1 SVK tetrahedron and its exact (non-symmetric)
// tangent (docs/THEORY.md §1.4, eq. 18-20, Simo-Tarnow); the plain mid-point variant.
//   f_A  = V_e F_{n+1/2} S_alg G_A
//   S_alg = S((E_n + E_{n+1})/2)  (energy-momentum)  or  S(E(F_{n+1/2}))  (mid-point)
//   K_AB = V_e [ 1/2 (G_A . S_alg G_B) I + 1/2 B_A(F_{n+1/2})^T C B_B(F_x) ],
//   F_x = F_{n+1} (energy-momentum) or F_{n+1/2} (mid-point).
#include "kernels/hyperelastic.hpp"
#include "kernels/svk.hpp"
#include "kernels/tet4.hpp"

namespace emc::kernels {

enum class Integrator : int { energy_momentum = 0, midpoint = 1 };

/// H_n, H_{n+1}, H_{n+1/2} = (H_n + H_{n+1}) / 2, F_{n+1} and F_{n+1/2} of the element
/// (docs/THEORY.md §1.4).
KOKKOS_INLINE_FUNCTION void step_kinematics(const double G[4][3], const double u0[4][3],
                                            const double u1[4][3], double H0[3][3], double H1[3][3],
                                            double Hm[3][3], double F1[3][3], double Fm[3][3]) {
  displacement_gradient(G, u0, H0);
  displacement_gradient(G, u1, H1);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) Hm[i][j] = 0.5 * (H0[i][j] + H1[i][j]);
  identity_plus(H1, F1);
  identity_plus(Hm, Fm);
}

/// f_A = V_e P G_A with P = F_{n+1/2} S_alg (node-major: 3A+i, docs/THEORY.md §1.4 eq. 18).
KOKKOS_INLINE_FUNCTION void internal_force(const double G[4][3], double Ve, const double Fm[3][3],
                                           const double S[3][3], double f[12]) {
  double P[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double s = 0;
      for (int k = 0; k < 3; ++k) s += Fm[i][k] * S[k][j];
      P[i][j] = s;
    }
  for (int A = 0; A < 4; ++A)
    for (int i = 0; i < 3; ++i) {
      double s = 0;
      for (int j = 0; j < 3; ++j) s += P[i][j] * G[A][j];
      f[3 * A + i] = Ve * s;
    }
}

/// Internal force f[12] (node-major: 3A+i) and, if K != nullptr, the tangent d f / d u_{n+1}
/// K[12][12], given u0 = u_n and u1 = u_{n+1} at the 4 nodes.
KOKKOS_INLINE_FUNCTION void em_tet4(const double G[4][3], double Ve, const Lame& m,
                                    Integrator integ, const double u0[4][3], const double u1[4][3],
                                    double f[12], double (*K)[12]) {
  double H0[3][3], H1[3][3], Hm[3][3], F1[3][3], Fm[3][3], Ea[3][3], S[3][3];
  step_kinematics(G, u0, u1, H0, H1, Hm, F1, Fm);
  if (integ == Integrator::energy_momentum) {
    double E0[3][3], E1[3][3];
    green_strain(H0, E0);
    green_strain(H1, E1);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) Ea[i][j] = 0.5 * (E0[i][j] + E1[i][j]);
  } else {
    green_strain(Hm, Ea);
  }
  svk_stress(m, Ea, S);
  internal_force(G, Ve, Fm, S, f);
  if (K == nullptr) return;
  const double(*Fx)[3] = (integ == Integrator::energy_momentum) ? F1 : Fm;
  double a[4][3], b[4][3], SG[4][3], FF[3][3];
  for (int A = 0; A < 4; ++A)
    for (int i = 0; i < 3; ++i) {
      double sa = 0, sb = 0, ss = 0;
      for (int k = 0; k < 3; ++k) {
        sa += Fm[i][k] * G[A][k];
        sb += Fx[i][k] * G[A][k];
        ss += S[i][k] * G[A][k];
      }
      a[A][i] = sa;
      b[A][i] = sb;
      SG[A][i] = ss;
    }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double s = 0;
      for (int k = 0; k < 3; ++k) s += Fm[i][k] * Fx[j][k];
      FF[i][j] = s;
    }
  const double h = 0.5 * Ve;
  for (int A = 0; A < 4; ++A)
    for (int B = 0; B < 4; ++B) {
      double GSG = 0, GG = 0;
      for (int k = 0; k < 3; ++k) {
        GSG += G[A][k] * SG[B][k];
        GG += G[A][k] * G[B][k];
      }
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          K[3 * A + i][3 * B + j] = h * ((i == j ? GSG : 0.0) + m.lambda * a[A][i] * b[B][j] +
                                         m.mu * GG * FF[i][j] + m.mu * a[B][i] * b[A][j]);
    }
}

/// The same for a Neo-Hookean or Mooney-Rivlin element (kernels/hyperelastic.hpp, docs/THEORY.md
/// §12): S_alg is Gonzalez's discrete gradient between E_n and E_{n+1} (energy-momentum) or
/// S(E(F_{n+1/2})) (mid-point), f_A = V_e F_{n+1/2} S_alg G_A, and
///   K_AB,ij = V_e [1/2 (G_A . S_alg G_B) d_ij + (F_{n+1/2} D(X_Bj) G_A)_i],
/// D(X) = dS_alg for the change X_Bj = sym(F_x^T (e_j (x) G_B)) of E_x (F_x = F_{n+1}: D of the
/// discrete gradient; F_{n+1/2}: D = CC(E(F_{n+1/2})) / 2).
KOKKOS_INLINE_FUNCTION void em_tet4(const double G[4][3], double Ve, const LogHyperelastic& m,
                                    Integrator integ, const double u0[4][3], const double u1[4][3],
                                    double f[12], double (*K)[12]) {
  double H0[3][3], H1[3][3], Hm[3][3], F1[3][3], Fm[3][3], S[3][3];
  step_kinematics(G, u0, u1, H0, H1, Hm, F1, Fm);
  const bool em = integ == Integrator::energy_momentum;
  DiscreteGradient dg;
  double Ci[3][3], l = 0;
  if (em) {
    double E0[3][3], E1[3][3];
    green_strain(H0, E0);
    green_strain(H1, E1);
    discrete_gradient(m, E0, E1, dg, K != nullptr);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) S[i][j] = dg.S[i][j];
  } else {
    double Ea[3][3];
    green_strain(Hm, Ea);
    hyper_detail::inverse_C(Ea, Ci);
    l = log_J(Ea);
    hyper_stress(m, Ea, Ci, l, S);
  }
  internal_force(G, Ve, Fm, S, f);
  if (K == nullptr) return;
  const double(*Fx)[3] = em ? F1 : Fm;
  double SG[4][3];
  for (int A = 0; A < 4; ++A)
    for (int i = 0; i < 3; ++i) {
      double s = 0;
      for (int k = 0; k < 3; ++k) s += S[i][k] * G[A][k];
      SG[A][i] = s;
    }
  for (int B = 0; B < 4; ++B)
    for (int j = 0; j < 3; ++j) {
      double X[3][3], T[3][3], FT[3][3];
      for (int p = 0; p < 3; ++p)
        for (int q = 0; q < 3; ++q) X[p][q] = 0.5 * (Fx[j][p] * G[B][q] + Fx[j][q] * G[B][p]);
      if (em) {
        discrete_gradient_tangent(m, dg, X, T);
      } else {
        hyper_tangent(m, Ci, l, X, T);
        for (int p = 0; p < 3; ++p)
          for (int q = 0; q < 3; ++q) T[p][q] *= 0.5;
      }
      for (int i = 0; i < 3; ++i)
        for (int q = 0; q < 3; ++q) {
          double s = 0;
          for (int k = 0; k < 3; ++k) s += Fm[i][k] * T[k][q];
          FT[i][q] = s;
        }
      for (int A = 0; A < 4; ++A) {
        double GSG = 0;
        for (int k = 0; k < 3; ++k) GSG += G[A][k] * SG[B][k];
        for (int i = 0; i < 3; ++i) {
          double s = 0;
          for (int q = 0; q < 3; ++q) s += FT[i][q] * G[A][q];
          K[3 * A + i][3 * B + j] = Ve * s + (i == j ? 0.5 * Ve * GSG : 0.0);
        }
      }
    }
}

/// Strain energy density W(E) of each material.
KOKKOS_INLINE_FUNCTION double energy(const Lame& m, const double E[3][3]) {
  return svk_energy(m, E);
}
KOKKOS_INLINE_FUNCTION double energy(const LogHyperelastic& m, const double E[3][3]) {
  return hyper_energy(m, E);
}
/// |lambda| + 2 mu of the small-strain limit of each material (the scale of its stiffness).
KOKKOS_INLINE_FUNCTION double stiffness(const Lame& m) {
  return kernels::fabs(m.lambda) + 2 * m.mu;
}
KOKKOS_INLINE_FUNCTION double stiffness(const LogHyperelastic& m) {
  return kernels::fabs(2 * (m.beta + m.b)) + 2 * (m.alpha + m.gamma);
}
/// Second Piola-Kirchhoff stress S(E) of each material.
KOKKOS_INLINE_FUNCTION void stress(const Lame& m, const double E[3][3], double S[3][3]) {
  svk_stress(m, E, S);
}
KOKKOS_INLINE_FUNCTION void stress(const LogHyperelastic& m, const double E[3][3], double S[3][3]) {
  hyper_stress(m, E, S);
}

/// Strain energy V_e W(E(u)) of the element.
template <class Material>
KOKKOS_INLINE_FUNCTION double tet4_energy(const double G[4][3], double Ve, const Material& m,
                                          const double u[4][3]) {
  double H[3][3], E[3][3];
  displacement_gradient(G, u, H);
  green_strain(H, E);
  return Ve * energy(m, E);
}

/// det F of the element at u (> 0 unless the element is inverted).
KOKKOS_INLINE_FUNCTION double tet4_detF(const double G[4][3], const double u[4][3]) {
  double F[3][3];
  deformation_gradient(G, u, F);
  return det3(F);
}

}  // namespace emc::kernels
