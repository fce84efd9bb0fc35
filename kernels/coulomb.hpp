#pragma once
// Coulomb friction of one sliding slave node on one 3-node master facet (docs/THEORY.md §11):
// the frictionless constraint of §5 (the slave's reduced unknowns are its slip increments) plus
// the tangential force f_T = -mu |f_N| d on the slave and -N_i(xi) f_T on the master nodes, with
//     s   = (x_{s,n+1} - x_{s,n}) - N(xi) (x_{m,n+1} - x_{m,n})   (the relative motion over the
//           step at the point where the force acts),
//     s_T = s - (s . n) n,   f_N = g_s . n,   n = the facet's normal at n+1/2,
//     d   = w / |w|,   w = -t + c s_T,   t = g_s - f_N n,
// g_s the slave's contactless residual (t: the tangential force the contact carries at the
// iterate, -t the resistance it offers to the slip) and c > 0 a weight of the size of the
// slave's stiffness (docs/THEORY.md §11.1). At a solution of the slip rows t = f_T, so
// w = (mu |f_N| + c |s_T|) e with e = s_T / |s_T|: d = e and the pair does the work
// f_T . s = -mu |f_N| |s_T| over the step (docs/THEORY.md §11.2). Unlike e, d is smooth where
// the slip vanishes (|w| >= mu |f_N| there), so Newton keeps its rate on a node that barely
// slides (docs/THEORY.md §11.3).
//
// With the residual g' = g - f (f the force pair), the reduced residual is P^T g': the master
// rows are unchanged (g_m + N_i f_T + N_i (g_s - f_T)), the slip rows become
// tau_k . (g_s - f_T) = tau_k . g_s + mu |f_N| tau_k . d. Their exact derivative along the
// update map of §5 (docs/THEORY.md §11.3) adds to the frictionless matrix P^T A Pt + X, with
// p_k = tau_k - (tau_k . d) d and b = mu |f_N| / |w|:
//   - the left factor of the slave's rows of A on the slip rows: tau_k -> tau_k + c_k n - b p_k,
//     c_k = mu sgn(f_N) (tau_k . d) (f_N's and t's dependence on g_s);
//   - X on the slip rows: -dtau_k . f_T (X of §5 takes g_s, the slip rows need g_s - f_T),
//     c_k g_s . dn (f_N through n), and b [c p_k . ds + (f_N - c s . n) p_k . dn] (the turn of
//     d through s_T and n), with ds = du_s - N du_m - dtau_j(step) dxi_j, du_s the exact right
//     factor Pt.
#include <Kokkos_Core.hpp>

#include "kernels/facet.hpp"
#include "kernels/frictionless.hpp"
#include "kernels/math.hpp"

namespace emc::kernels {

/// What friction adds for one sliding slave (struct comment above; dof order as
/// FrictionlessBlocks: master column 3 i + c, slave q column k = dxi, deta).
struct CoulombSlip {
  double fT[3];      ///< friction force on the slave (the masters get -N_i fT)
  double fN;         ///< g_s . n at n+1/2
  double slip;       ///< |s_T|
  double dir[3];     ///< e = s_T / |s_T| (0 when |s_T| = 0)
  double work;       ///< -f_T . s = mu |f_N| d . s_T: the step's dissipation at a solution
  double N[3];       ///< N(xi): the force's point on the facet
  double Plq[3][2];  ///< the slip rows' left factor on the slave's rows of A (replaces Pq)
  double Xsq[2][9];  ///< added to X: slip rows on master columns
  double Xqq[2][2];  ///< added to X: slip rows on the slave's q columns
};

/// d(v . n)/du_m for n the facet's unit normal at n+1/2 and a fixed vector v: with
/// dn = (I - n n^T) dc / |c|, dc = dtau_xi x tau_eta + tau_xi x dtau_eta, dtau_xi =
/// (du_m2 - du_m1)/2, dtau_eta = (du_m3 - du_m1)/2 (§5.4).
KOKKOS_INLINE_FUNCTION void coulomb_dn_row(const Facet& f, const double v[3], double wm[9]) {
  const double vn = v[0] * f.n[0] + v[1] * f.n[1] + v[2] * f.n[2];
  double sp[3];
  for (int c = 0; c < 3; ++c) sp[c] = (v[c] - vn * f.n[c]) / f.area2;
  const double w1[3] = {f.t2[1] * sp[2] - f.t2[2] * sp[1], f.t2[2] * sp[0] - f.t2[0] * sp[2],
                        f.t2[0] * sp[1] - f.t2[1] * sp[0]};
  const double w2[3] = {sp[1] * f.t1[2] - sp[2] * f.t1[1], sp[2] * f.t1[0] - sp[0] * f.t1[2],
                        sp[0] * f.t1[1] - sp[1] * f.t1[0]};
  for (int c = 0; c < 3; ++c) {
    wm[c] = -0.5 * (w1[c] + w2[c]);
    wm[3 + c] = 0.5 * w1[c];
    wm[6 + c] = 0.5 * w2[c];
  }
}

/// The state of one Coulomb entry at (xs0, xm0) = t_n, (xs1, xm1) = the iterate, xi its point
/// on the facet, gs the slave's contactless residual (docs/THEORY.md §11.4): f_N = g_s . n, the
/// trial tangential force g_s - f_N n (the stick force's), the tangential relative motion s_T,
/// and the CPP xi0 of x_{s,n} on the facet at t_n (where a returning entry sticks, §4.1).
struct CoulombState {
  double fN = 0, trial[3] = {0, 0, 0}, sT[3] = {0, 0, 0}, slip = 0, xi0[2] = {0, 0};
};

KOKKOS_INLINE_FUNCTION void coulomb_state(const double xs0[3], const double xs1[3],
                                          const double xm0[3][3], const double xm1[3][3],
                                          const double xi[2], const double gs[3],
                                          CoulombState& st) {
  double xmh[3][3], N[3];
  for (int r = 0; r < 3; ++r)
    for (int i = 0; i < 3; ++i) xmh[i][r] = 0.5 * (xm0[i][r] + xm1[i][r]);
  const Facet f = facet(xmh);
  facet_shape(xi, N);
  double s[3], sn = 0, fN = 0;
  for (int r = 0; r < 3; ++r) {
    double dm = 0;
    for (int i = 0; i < 3; ++i) dm += N[i] * (xm1[i][r] - xm0[i][r]);
    s[r] = (xs1[r] - xs0[r]) - dm;
    sn += s[r] * f.n[r];
    fN += gs[r] * f.n[r];
  }
  st.fN = fN;
  double slip2 = 0;
  for (int r = 0; r < 3; ++r) {
    st.trial[r] = gs[r] - fN * f.n[r];
    st.sT[r] = s[r] - sn * f.n[r];
    slip2 += st.sT[r] * st.sT[r];
  }
  st.slip = kernels::sqrt(slip2);
  double gap;
  if (!facet_cpp(xs0, xm0, st.xi0, gap)) st.xi0[0] = xi[0], st.xi0[1] = xi[1];
}

/// The law's data of one sliding entry (docs/THEORY.md §11.1).
struct SlipLaw {
  double mu = 0;               ///< the friction coefficient
  double weight = 0;           ///< c > 0, the slip's weight in the force's direction
  double hint[3] = {0, 0, 0};  ///< the direction of the entry's last slip (or of its trial force)
  double held = 0;             ///< |s_T| <= held (position round-off): d = the hint's
};

/// The force, the dissipation and the derivative terms of one sliding slave at the state
/// (xs0, xm0) at t_n, (xs1, xm1) the iterate, xi the CPP of x_{s,n+1/2} at n+1/2 (as left by
/// frictionless_project), gs the slave's contactless residual and b the slave's frictionless
/// blocks at that state (Pt, for ds). While the slip is within the round-off of positions (the
/// start iterate of a step, u_{n+1} = u_n) and the entry has a hint, the force is held along the
/// hint (its tangential part), with no turn terms: the direction of the last slip, not that of
/// the start iterate's residual (docs/THEORY.md §11.3). w = 0 (no direction) gives no force and
/// no terms. Returns false for a degenerate facet at n+1/2.
KOKKOS_INLINE_FUNCTION bool coulomb_slip(const double xs0[3], const double xs1[3],
                                         const double xm0[3][3], const double xm1[3][3],
                                         const double xi[2], const double gs[3], const SlipLaw& law,
                                         const FrictionlessBlocks& b, CoulombSlip& c) {
  const double mu = law.mu;
  for (int r = 0; r < 3; ++r) {
    c.fT[r] = c.dir[r] = 0;
    for (int k = 0; k < 2; ++k) c.Plq[r][k] = b.Pq[r][k];
  }
  for (int k = 0; k < 2; ++k) {
    for (int j = 0; j < 9; ++j) c.Xsq[k][j] = 0;
    c.Xqq[k][0] = c.Xqq[k][1] = 0;
  }
  c.fN = c.slip = c.work = 0;
  facet_shape(xi, c.N);
  double xmh[3][3], xsh[3];
  midpoint(xs0, xs1, xsh);
  midpoint(xm0, xm1, xmh);
  const FacetMetric m = facet_metric(xmh);  // §2.2: tau_k, n and the metric g_ab
  const Facet& f = m.f;
  const double G11 = m.g11, G12 = m.g12, G22 = m.g22, detG = m.det;
  if (!(f.area2 > 0) || !(detG > 0)) return false;
  const double Gi[2][2] = {{G22 / detG, -G12 / detG}, {-G12 / detG, G11 / detG}};
  const double* n = f.n;
  const double* N = c.N;
  // s, its normal part, s_T, the mid-point gap h and the facet's change over the step dtau_k
  double s[3], h = 0, sn = 0, fN = 0, dtau[2][3];
  for (int r = 0; r < 3; ++r) {
    double dm = 0, xmN = 0;
    for (int i = 0; i < 3; ++i) {
      dm += N[i] * (xm1[i][r] - xm0[i][r]);
      xmN += N[i] * xmh[i][r];
    }
    s[r] = (xs1[r] - xs0[r]) - dm;
    sn += s[r] * n[r];
    h += (xsh[r] - xmN) * n[r];
    fN += gs[r] * n[r];
    for (int k = 0; k < 2; ++k)
      dtau[k][r] = (xm1[k + 1][r] - xm1[0][r]) - (xm0[k + 1][r] - xm0[0][r]);
  }
  double sT[3], w[3], slip2 = 0, w2 = 0;
  for (int r = 0; r < 3; ++r) {
    sT[r] = s[r] - sn * n[r];
    w[r] = -(gs[r] - fN * n[r]) + law.weight * sT[r];
    slip2 += sT[r] * sT[r];
    w2 += w[r] * w[r];
  }
  c.fN = fN;
  const double slip = kernels::sqrt(slip2);
  double wn = kernels::sqrt(w2);
  c.slip = slip;
  if (slip > 0)
    for (int r = 0; r < 3; ++r) c.dir[r] = sT[r] / slip;
  double hT[3], hn = 0, h2 = 0;  // the hint's tangential part
  for (int r = 0; r < 3; ++r) hn += law.hint[r] * n[r];
  for (int r = 0; r < 3; ++r) {
    hT[r] = law.hint[r] - hn * n[r];
    h2 += hT[r] * hT[r];
  }
  const bool held = slip <= law.held && h2 > 0;
  if (held) {
    wn = kernels::sqrt(h2);
    for (int r = 0; r < 3; ++r) w[r] = hT[r];
  }
  if (!(wn > 0)) return true;
  const double afN = kernels::fabs(fN), sg = fN > 0 ? 1.0 : (fN < 0 ? -1.0 : 0.0);
  double d[3];
  for (int r = 0; r < 3; ++r) {
    d[r] = w[r] / wn;
    c.fT[r] = -mu * afN * d[r];
  }
  c.work = mu * afN * (d[0] * sT[0] + d[1] * sT[1] + d[2] * sT[2]);
  // dxi_k = dq_k / 2 + Dxm_k du_m (§5.4)
  double Dxm[2][9];
  for (int k = 0; k < 2; ++k)
    for (int r = 0; r < 3; ++r) {
      Dxm[k][r] = -h * (Gi[k][0] + Gi[k][1]) * 0.5 * n[r];
      Dxm[k][3 + r] = h * Gi[k][0] * 0.5 * n[r];
      Dxm[k][6 + r] = h * Gi[k][1] * 0.5 * n[r];
    }
  double wg[9];  // d(g_s . n)/du_m at fixed g_s
  coulomb_dn_row(f, gs, wg);
  const double* tau[2] = {f.t1, f.t2};
  // held along the hint: no turn of d
  const double bw = held ? 0.0 : mu * afN / wn, a = bw * law.weight,
               an = bw * (fN - law.weight * sn);
  for (int k = 0; k < 2; ++k) {
    const double td = tau[k][0] * d[0] + tau[k][1] * d[1] + tau[k][2] * d[2];
    const double ck = mu * sg * td;
    double p[3];
    for (int r = 0; r < 3; ++r) {
      p[r] = tau[k][r] - td * d[r];
      c.Plq[r][k] = tau[k][r] + ck * n[r] - bw * p[r];
    }
    double wp[9];
    coulomb_dn_row(f, p, wp);
    const double pd[2] = {p[0] * dtau[0][0] + p[1] * dtau[0][1] + p[2] * dtau[0][2],
                          p[0] * dtau[1][0] + p[1] * dtau[1][1] + p[2] * dtau[1][2]};
    for (int j = 0; j < 9; ++j) {
      double ds = 0;  // p . ds / du_m,j
      for (int r = 0; r < 3; ++r) ds += p[r] * (b.Ptm[r][j] - (j % 3 == r ? N[j / 3] : 0.0));
      ds -= pd[0] * Dxm[0][j] + pd[1] * Dxm[1][j];
      c.Xsq[k][j] = ck * wg[j] + a * ds + an * wp[j];
    }
    for (int l = 0; l < 2; ++l) {
      double ds = -0.5 * pd[l];
      for (int r = 0; r < 3; ++r) ds += p[r] * b.Ptq[r][l];
      c.Xqq[k][l] = a * ds;
    }
    // -dtau_k . f_T: dtau_k = (du_{m,k+2} - du_m1) / 2
    for (int r = 0; r < 3; ++r) {
      c.Xsq[k][r] += 0.5 * c.fT[r];
      c.Xsq[k][3 * (k + 1) + r] -= 0.5 * c.fT[r];
    }
  }
  return true;
}

}  // namespace emc::kernels
