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

namespace em_detail {

/// What the closed-form tangent of a hyperelastic element (docs/THEORY.md §12.4) needs of nodes
/// 1-3 (A, B = 1 + n, 1 + m), the weights of the terms folded in: pa = V_e beta a, pd = V_e b d,
/// pg = V_e g, qa = V_e (gamma + r)/2 a, qd = V_e a'/2 d; per pair sd = V_e/2 G_A . S_alg G_B,
/// sX = V_e (gamma + r)/2 G_A . G_B, sC = V_e a'/2 G_A . C^-1 G_B.
struct HyperTangentTerms {
  double b[3][3], c[3][3], e[3][3], pa[3][3], pd[3][3], pg[3][3], qa[3][3], qd[3][3];
  double sd[3][3], sX[3][3], sC[3][3], FF[3][3], FCF[3][3];
};

/// K of the terms: the blocks of nodes 1-3, then row and column 0 as their negated sums (K_AB
/// is bilinear in (G_A, G_B) and G_0 = -(G_1 + G_2 + G_3), tet_gradients). kBeta: the beta term
/// (Mooney-Rivlin; beta = 0 for Neo-Hookean).
template <bool kBeta>
KOKKOS_INLINE_FUNCTION void hyper_tangent_blocks(const HyperTangentTerms& t, double (*K)[12]) {
  for (int n = 0; n < 3; ++n)
    for (int m = 0; m < 3; ++m)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          K[3 + 3 * n + i][3 + 3 * m + j] =
              (i == j ? t.sd[n][m] : 0.0) + (kBeta ? t.pa[n][i] * t.b[m][j] : 0.0) +
              t.pd[n][i] * t.c[m][j] + t.pg[n][i] * t.e[m][j] + t.qa[m][i] * t.b[n][j] +
              t.qd[m][i] * t.c[n][j] + t.sX[n][m] * t.FF[i][j] + t.sC[n][m] * t.FCF[i][j];
  for (int p = 3; p < 12; ++p)
    for (int j = 0; j < 3; ++j) K[p][j] = -(K[p][3 + j] + K[p][6 + j] + K[p][9 + j]);
  for (int q = 0; q < 12; ++q)
    for (int i = 0; i < 3; ++i) K[i][q] = -(K[3 + i][q] + K[6 + i][q] + K[9 + i][q]);
}

/// The closed-form tangent (em_tet4 below, docs/THEORY.md §12.4) given the discrete gradient
/// (kEm) or the mid-point stress (dg.S, dg.Ci, dg.l; dE = Q = 0), F_{n+1/2} and F_x.
template <bool kEm>
KOKKOS_INLINE_FUNCTION void hyper_element_tangent(const double G[4][3], double Ve,
                                                  const LogHyperelastic& m,
                                                  const DiscreteGradient& dg, const double Fm[3][3],
                                                  const double Fx[3][3], double (*K)[12]) {
  const double(*Ci)[3] = dg.Ci;
  em_detail::HyperTangentTerms t;
  const double wX = 0.5 * Ve * (m.gamma + dg.r), wC = 0.5 * Ve * (m.alpha - 2 * m.b * dg.l);
  const double wI = Ve * m.beta, wb = Ve * m.b;
  // Rows n: G_n (Gt), C^-1 G_n, S_alg G_n, dE G_n, Q G_n, and their products with F_{n+1/2}^T,
  // F_x^T (3 x 3 products on local copies).
  using hyper_detail::mul;
  double Gt[3][3], FmT[3][3], FxT[3][3], CG[3][3], SG[3][3], a[3][3], d[3][3], g[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      Gt[i][j] = G[i + 1][j];
      FmT[i][j] = Fm[j][i];
      FxT[i][j] = Fx[j][i];
    }
  mul(Gt, dg.Ci, CG);  // C^-1, S_alg, dE, Q symmetric
  mul(Gt, dg.S, SG);
  mul(Gt, FmT, a);
  mul(Gt, FxT, t.b);
  mul(CG, FmT, d);
  mul(CG, FxT, t.c);
  if (kEm) {
    double dEG[3][3], QG[3][3];
    mul(Gt, dg.dE, dEG);
    mul(Gt, dg.Q, QG);
    mul(dEG, FmT, g);
    mul(QG, FxT, t.e);
  }
  for (int n = 0; n < 3; ++n)
    for (int i = 0; i < 3; ++i) {
      t.pa[n][i] = wI * a[n][i];
      t.pd[n][i] = wb * d[n][i];
      t.pg[n][i] = kEm ? Ve * g[n][i] : 0.0;
      if (!kEm) t.e[n][i] = 0;
      t.qa[n][i] = wX * a[n][i];
      t.qd[n][i] = wC * d[n][i];
    }
  for (int q = 0; q < 6; ++q) {  // symmetric in the pair (S_alg, C^-1 symmetric)
    const int n = hyper_detail::up_i(q), p = hyper_detail::up_j(q);
    double GSG = 0, GG = 0, GCG = 0;
    for (int k = 0; k < 3; ++k) {
      GSG += Gt[n][k] * SG[p][k];
      GG += Gt[n][k] * Gt[p][k];
      GCG += Gt[n][k] * CG[p][k];
    }
    t.sd[n][p] = t.sd[p][n] = 0.5 * Ve * GSG;
    t.sX[n][p] = t.sX[p][n] = wX * GG;
    t.sC[n][p] = t.sC[p][n] = wC * GCG;
  }
  double FmCi[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      FmCi[i][j] = Fm[i][0] * Ci[0][j] + Fm[i][1] * Ci[1][j] + Fm[i][2] * Ci[2][j];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      t.FF[i][j] = Fm[i][0] * Fx[j][0] + Fm[i][1] * Fx[j][1] + Fm[i][2] * Fx[j][2];
      t.FCF[i][j] = FmCi[i][0] * Fx[j][0] + FmCi[i][1] * Fx[j][1] + FmCi[i][2] * Fx[j][2];
    }
  if (m.beta != 0)
    em_detail::hyper_tangent_blocks<true>(t, K);
  else
    em_detail::hyper_tangent_blocks<false>(t, K);
}

}  // namespace em_detail

/// The same for a Neo-Hookean or Mooney-Rivlin element (kernels/hyperelastic.hpp, docs/THEORY.md
/// §12): S_alg is Gonzalez's discrete gradient between E_n and E_{n+1} (energy-momentum) or
/// S(E(F_{n+1/2})) (mid-point), f_A = V_e F_{n+1/2} S_alg G_A, and the tangent
///   K_AB,ij = V_e [1/2 (G_A . S_alg G_B) d_ij + (F_{n+1/2} D(X_Bj) G_A)_i],
/// D(X) = dS_alg for the change X_Bj = sym(F_x^T (e_j (x) G_B)) of E_x (F_x = F_{n+1}: D of the
/// discrete gradient; F_{n+1/2}: D = CC(E(F_{n+1/2})) / 2, r = Q = 0), in closed form
/// (docs/THEORY.md §12.4): with C^-1 and l of E_m (of E(F_{n+1/2})), a' = alpha - 2 b l,
/// a_A = F_{n+1/2} G_A, b_A = F_x G_A, d_A = F_{n+1/2} C^-1 G_A, c_A = F_x C^-1 G_A,
/// g_A = F_{n+1/2} dE G_A, e_A = F_x Q G_A, FF = F_{n+1/2} F_x^T, FCF = F_{n+1/2} C^-1 F_x^T,
///   K_AB,ij / V_e = 1/2 (G_A . S_alg G_B) d_ij + beta a_Ai b_Bj + b d_Ai c_Bj + g_Ai e_Bj
///                   + (gamma + r)/2 [(G_A . G_B) FF_ij + a_Bi b_Aj]
///                   + a'/2 [(G_A . C^-1 G_B) FCF_ij + d_Bi c_Aj].
KOKKOS_INLINE_FUNCTION void em_tet4(const double G[4][3], double Ve, const LogHyperelastic& m,
                                    Integrator integ, const double u0[4][3], const double u1[4][3],
                                    double f[12], double (*K)[12]) {
  double H0[3][3], H1[3][3], Hm[3][3], F1[3][3], Fm[3][3];
  step_kinematics(G, u0, u1, H0, H1, Hm, F1, Fm);
  const bool em = integ == Integrator::energy_momentum;
  DiscreteGradient dg;  // the mid-point rule: S, C^-1 and l of E(F_{n+1/2}) in it, r = 0
  if (em) {
    double E0[3][3], E1[3][3];
    green_strain(H0, E0);
    green_strain(H1, E1);
    discrete_gradient(m, E0, E1, dg, K != nullptr);
  } else {
    double Ea[3][3];
    green_strain(Hm, Ea);
    dg.l = hyper_detail::inverse_C_log_J(Ea, dg.Ci);
    hyper_stress(m, Ea, dg.Ci, dg.l, dg.S);
  }
  internal_force(G, Ve, Fm, dg.S, f);
  if (K == nullptr) return;
  if (em)
    em_detail::hyper_element_tangent<true>(G, Ve, m, dg, Fm, F1, K);
  else
    em_detail::hyper_element_tangent<false>(G, Ve, m, dg, Fm, Fm, K);
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
