#pragma once
// Frictionless contact of one active slave node on one 3-node master facet, by direct
// elimination (docs/THEORY.md §2, §3, §5; the paper's eq. 47-64 with the exact linearisation).
//
// The slave s lies on master facet (m1, m2, m3) (the facet's node order); its reduced unknowns
// are q_s = (dxi, deta, dummy). All geometry is taken at the mid-point configuration
// x_{n+1/2} = (x_n + x_{n+1})/2 (§5, eq. 47-49). With the global P and Pt equal to the identity
// except in the slave rows, the reduced Newton system is (§3, §5)
//     (P^T A Pt + X + D) dq = - P^T g,     du = P dq, then update steps 2-3 (frictionless_project)
// with A the contactless Newton matrix, D = beta on the dummy (beta = tr(A_ss)/3; the caller's),
// and the reduced residual P^T g: slave rows T^T g_s (dxi, deta; the dummy row gets 0), master
// rows g_m + N^T g_s (eq. 56). The kernels return the per-slave blocks of P, Pt and X; a node
// index list (s; m1, m2, m3) places them. Dof order inside the blocks: master column/row 3 i + c
// is component c of facet node m_{i+1}; slave q column/row k is dxi (k = 0) or deta (k = 1).
#include <Kokkos_Core.hpp>

#include "kernels/facet.hpp"
#include "kernels/math.hpp"

namespace emc::kernels {

/// Per-slave blocks of P (rows of the Newton increment), Pt (its exact right factor) and X (the
/// variation of P^T itself times g) for one active frictionless slave (docs/THEORY.md §3, §5.4).
/// In the global matrices: P, Pt are the identity on every row but the slave's three; the
/// slave's dummy column (q_s2) of P and Pt is zero; X is zero outside the blocks below.
struct FrictionlessBlocks {
  double n[3];       ///< unit normal of the facet at n+1/2
  double Pm[3][9];   ///< P, slave rows, master columns: N_i I  (du_s = N du_m + T dq)
  double Pq[3][2];   ///< P, slave rows, the slave's own q columns: tau_xi, tau_eta at n+1/2
  double Ptm[3][9];  ///< Pt (the exact right factor, §5): slave rows, master columns
  double Ptq[3][2];  ///< Pt, slave rows, slave q columns
  double Xsq[2][9];  ///< X: slave rows k (dxi, deta) on master columns
  double Xmq[9][2];  ///< X: master rows on the slave's q columns
  double Xmm[9][9];  ///< X: master rows on master columns
};

/// dN_i/dxi_k for N = (1 - xi - eta, xi, eta) (§2).
KOKKOS_INLINE_FUNCTION double frictionless_dN(int i, int k) {
  return i == 0 ? -1.0 : (i == k + 1 ? 1.0 : 0.0);
}

/// Pt's slave rows when step 3 closes the gap at t_{n+1} (docs/THEORY.md §7.3): step 3 moves
/// x_{s,n+1} along n_{n+1/2} until phi = (x_{s,n+1} - x_{m1,n+1}) . n_{n+1} = 0, so at a
/// projected state (phi = 0) du_s = N du_m + tau_k dq_k - n_{n+1/2} dphi / (n_{n+1/2} . n_{n+1}),
/// dphi = (tau_{k,n+1/2} . n_{n+1}) dq_k + b . dn_{n+1}, b = x_{s,n+1} - N x_{m,n+1} (in the
/// facet's plane at n+1), dn_{n+1} = (I - n n^T) dc / |c| at n+1 with dtau_xi = du_m2 - du_m1,
/// dtau_eta = du_m3 - du_m1 (xi drops out: phi does not depend on it). f: the facet at n+1/2.
KOKKOS_INLINE_FUNCTION bool frictionless_closed_right_factor(const double xs1[3],
                                                             const double xm0[3][3],
                                                             const double xm1[3][3],
                                                             const double N[3], const Facet& f,
                                                             FrictionlessBlocks& b) {
  const Facet f1 = facet(xm1);
  double d = 0, bv[3], bn = 0;
  for (int c = 0; c < 3; ++c) {
    d += f.n[c] * f1.n[c];
    bv[c] = xs1[c] - N[0] * xm1[0][c] - N[1] * xm1[1][c] - N[2] * xm1[2][c];
    bn += bv[c] * f1.n[c];
  }
  if (!(f1.area2 > 0) || !(d > 0)) return false;
  double sp[3];
  for (int c = 0; c < 3; ++c) sp[c] = (bv[c] - bn * f1.n[c]) / f1.area2;
  double w1[3], w2[3];
  cross(f1.t2, sp, w1);
  cross(sp, f1.t1, w2);
  double wm[9], tq[2] = {0, 0};
  for (int c = 0; c < 3; ++c) {
    wm[c] = -(w1[c] + w2[c]);
    wm[3 + c] = w1[c];
    wm[6 + c] = w2[c];
    for (int k = 0; k < 2; ++k) tq[k] += 0.5 * (xm0[k + 1][c] - xm0[0][c]) * f1.n[c];
  }
  for (int r = 0; r < 3; ++r) {
    for (int j = 0; j < 9; ++j) b.Ptm[r][j] = b.Pm[r][j] - f.n[r] * wm[j] / d;
    for (int k = 0; k < 2; ++k) b.Ptq[r][k] = b.Pq[r][k] - f.n[r] * tq[k] / d;
  }
  return true;
}

/// The blocks of P, Pt and X (struct above) of one active frictionless slave, at the state
/// (xs0, xm0) = positions at t_n, (xs1, xm1) = the current iterate of t_{n+1}; xi = the slave's
/// facet coordinates, which must be the CPP of x_{s,n+1/2} on the facet at n+1/2 (as left by
/// frictionless_project: the exact terms are the derivative of update steps 1-3 at such a
/// state); gs = the slave's contactless residual g_s; close: the gap is closed at t_{n+1}
/// (docs/THEORY.md §7, step 3 of frictionless_project with close = true). Returns false
/// (blocks zeroed) for a degenerate facet at n+1/2 (or, closing, at n+1).
KOKKOS_INLINE_FUNCTION bool frictionless_blocks(const double xs0[3], const double xs1[3],
                                                const double xm0[3][3], const double xm1[3][3],
                                                const double xi[2], const double gs[3],
                                                FrictionlessBlocks& b, bool close = false) {
  for (int r = 0; r < 3; ++r) {
    b.n[r] = 0;
    for (int j = 0; j < 9; ++j) b.Pm[r][j] = b.Ptm[r][j] = 0;
    for (int k = 0; k < 2; ++k) b.Pq[r][k] = b.Ptq[r][k] = 0;
  }
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 9; ++j) b.Xsq[k][j] = b.Xmq[j][k] = 0;
  for (int i = 0; i < 9; ++i)
    for (int j = 0; j < 9; ++j) b.Xmm[i][j] = 0;

  // Mid-point geometry (§5, eq. 47-49): tau_xi, tau_eta, n, |c| = |tau_xi x tau_eta| (§2).
  double xmh[3][3], xsh[3];
  midpoint(xs0, xs1, xsh);
  midpoint(xm0, xm1, xmh);
  const FacetMetric m = facet_metric(xmh);  // §2.2: tau_k, n and the metric g_ab
  const Facet& f = m.f;
  const double G11 = m.g11, G12 = m.g12, G22 = m.g22, detG = m.det;
  if (!(f.area2 > 0) || !(detG > 0)) return false;
  const double Gi[2][2] = {{G22 / detG, -G12 / detG}, {-G12 / detG, G11 / detG}};  // G^-1
  const double* n = f.n;
  double N[3];
  facet_shape(xi, N);
  for (int r = 0; r < 3; ++r) b.n[r] = n[r];

  // P, slave rows (§3): du_s = N_i du_mi + tau_xi dxi + tau_eta deta (dummy column zero).
  for (int r = 0; r < 3; ++r) {
    for (int i = 0; i < 3; ++i) b.Pm[r][3 * i + r] = N[i];
    b.Pq[r][0] = f.t1[r];
    b.Pq[r][1] = f.t2[r];
  }

  // Ingredients of the exact terms (§5), all at n+1/2 unless marked:
  //   h   = (x_{s,n+1/2} - N x_{m,n+1/2}) . n                (mid-point gap)
  //   s   = (x_{s,n+1} - x_{s,n}) - N (x_{m,n+1} - x_{m,n})  (relative motion over the step)
  //   r_k = (tau_{k,n+1} - tau_{k,n}) . n                    (rotation of the facet)
  double h = 0, sv[3], rk[2] = {0, 0};
  for (int c = 0; c < 3; ++c) {
    double xmN = 0, dmN = 0;
    for (int i = 0; i < 3; ++i) {
      xmN += N[i] * xmh[i][c];
      dmN += N[i] * (xm1[i][c] - xm0[i][c]);
    }
    h += (xsh[c] - xmN) * n[c];
    sv[c] = (xs1[c] - xs0[c]) - dmN;
    for (int k = 0; k < 2; ++k)
      rk[k] += ((xm1[k + 1][c] - xm1[0][c]) - (xm0[k + 1][c] - xm0[0][c])) * n[c];
  }

  // d xi_k / d u_m from the gap term of the CPP (§5: dxi_k = dq_k/2 + h [G^-1 b]_k,
  // b = (n . (du_m2 - du_m1), n . (du_m3 - du_m1)) / 2):  Dxm[k][3i+c] = h [G^-1 B]_k,
  // B[l] = n/2 on m_{l+2} (l = 0: m2, l = 1: m3), -n/2 on m1.
  double Dxm[2][9];
  for (int k = 0; k < 2; ++k)
    for (int c = 0; c < 3; ++c) {
      const double a = h * (Gi[k][0] + Gi[k][1]) * 0.5 * n[c];
      Dxm[k][c] = -a;                             // m1
      Dxm[k][3 + c] = h * Gi[k][0] * 0.5 * n[c];  // m2
      Dxm[k][6 + c] = h * Gi[k][1] * 0.5 * n[c];  // m3
    }

  // s . dn with dn = (I - n n^T) dc / |c|, c = tau_xi x tau_eta, dc = dtau_xi x tau_eta +
  // tau_xi x dtau_eta, dtau_xi = (du_m2 - du_m1)/2, dtau_eta = (du_m3 - du_m1)/2 (§5).
  // sp = (I - n n^T) s / |c|;  sp . (a x v) = (v x sp) . a  gives the row s . dn / du_m.
  double sn = sv[0] * n[0] + sv[1] * n[1] + sv[2] * n[2];
  double sp[3];
  for (int c = 0; c < 3; ++c) sp[c] = (sv[c] - sn * n[c]) / f.area2;
  // d/d(dtau_xi) of sp . (dtau_xi x tau_eta) = tau_eta x sp;  of sp . (tau_xi x dtau_eta) = sp x
  // tau_xi
  double w1[3], w2[3];
  cross(f.t2, sp, w1);
  cross(sp, f.t1, w2);
  double wm[9];
  for (int c = 0; c < 3; ++c) {
    wm[c] = -0.5 * (w1[c] + w2[c]);  // m1: dtau_xi = dtau_eta = -du_m1/2
    wm[3 + c] = 0.5 * w1[c];         // m2: dtau_xi = du_m2/2
    wm[6 + c] = 0.5 * w2[c];         // m3: dtau_eta = du_m3/2
  }
  // Step 3 linearised (§5): du_s = N du_m + tau_k dq_k - n [ s . dn - sum_k r_k dxi_k ],
  // dxi_k = dq_k/2 + Dxm_k du_m; so wm -= r_k Dxm_k and the q columns get + n r_k / 2.
  for (int j = 0; j < 9; ++j) wm[j] -= rk[0] * Dxm[0][j] + rk[1] * Dxm[1][j];
  for (int r = 0; r < 3; ++r) {
    for (int j = 0; j < 9; ++j) b.Ptm[r][j] = b.Pm[r][j] - n[r] * wm[j];
    for (int k = 0; k < 2; ++k) b.Ptq[r][k] = b.Pq[r][k] + 0.5 * n[r] * rk[k];
  }
  if (close && !frictionless_closed_right_factor(xs1, xm0, xm1, N, f, b)) return false;

  // X: the variation of P^T at fixed g (§5).
  // Slave row k: d(tau_k . g_s) = dtau_k . g_s: +g_s/2 on m_{k+2}, -g_s/2 on m1 (eq. 57-58).
  for (int k = 0; k < 2; ++k)
    for (int c = 0; c < 3; ++c) {
      b.Xsq[k][c] -= 0.5 * gs[c];
      b.Xsq[k][3 * (k + 1) + c] += 0.5 * gs[c];
    }
  // Master row i: d(N_i g_s) = g_s (dN_i/dxi_k) dxi_k, dxi_k = dq_k/2 + Dxm_k du_m.
  for (int i = 0; i < 3; ++i)
    for (int c = 0; c < 3; ++c) {
      for (int k = 0; k < 2; ++k) b.Xmq[3 * i + c][k] = 0.5 * frictionless_dN(i, k) * gs[c];
      for (int j = 0; j < 9; ++j)
        b.Xmm[3 * i + c][j] =
            gs[c] * (frictionless_dN(i, 0) * Dxm[0][j] + frictionless_dN(i, 1) * Dxm[1][j]);
    }
  return true;
}

/// The slave's part of the reduced residual P^T g (§3, eq. 56): rq = T^T g_s (the dxi and deta
/// rows; the dummy row is 0) and madd = N^T g_s, to be added to the master rows g_m.
KOKKOS_INLINE_FUNCTION void frictionless_residual(const FrictionlessBlocks& b, const double gs[3],
                                                  double rq[2], double madd[9]) {
  for (int k = 0; k < 2; ++k) {
    rq[k] = 0;
    for (int r = 0; r < 3; ++r) rq[k] += b.Pq[r][k] * gs[r];
  }
  for (int j = 0; j < 9; ++j) {
    madd[j] = 0;
    for (int r = 0; r < 3; ++r) madd[j] += b.Pm[r][j] * gs[r];
  }
}

/// Update steps 2-3 of docs/THEORY.md §5.3 (eq. 60-64) on the given facet:
/// xi := CPP of x_{s,n+1/2} on the facet at n+1/2 (its plane extended; §2); then
/// dgN = (xs1 - xs0 - N (xm1 - xm0)) . n_{n+1/2};  xs1 -= dgN n_{n+1/2}  (condition (a), eq. 48).
/// Step 3 moves x_{s,n+1/2} along n, which keeps its CPP on the flat facet (§2), so xi stays the
/// CPP (condition (b)). Returns how far xi is outside the facet (-min N, <= 0 inside); facet
/// switching and hysteresis are the caller's. A degenerate facet leaves xi and xs1 unchanged
/// and returns +infinity. close (docs/THEORY.md §7.3): step 3 instead moves x_{s,n+1} along
/// n_{n+1/2} onto the facet's plane at n+1 (g_N = 0 at t_{n+1}); moving along n_{n+1/2} keeps
/// condition (b), and (a) is then replaced by the closure.
KOKKOS_INLINE_FUNCTION double frictionless_project(const double xs0[3], double xs1[3],
                                                   const double xm0[3][3], const double xm1[3][3],
                                                   double xi[2], bool close = false) {
  double xmh[3][3], xsh[3];
  midpoint(xs0, xs1, xsh);
  midpoint(xm0, xm1, xmh);
  double xi_new[2], gap;
  if (!facet_cpp(xsh, xmh, xi_new, gap)) return kernels::infinity();
  const Facet f = facet(xmh);
  double dgN = 0;
  if (close) {  // phi / (n_{n+1/2} . n_{n+1}), phi = g_N at n+1 (independent of xi)
    const Facet f1 = facet(xm1);
    double phi = 0, d = 0;
    for (int c = 0; c < 3; ++c) {
      phi += (xs1[c] - xm1[0][c]) * f1.n[c];
      d += f.n[c] * f1.n[c];
    }
    if (!(f1.area2 > 0) || !(d > 0)) return kernels::infinity();
    dgN = phi / d;
  }
  xi[0] = xi_new[0];
  xi[1] = xi_new[1];
  double N[3];
  facet_shape(xi, N);
  if (!close)
    for (int c = 0; c < 3; ++c) {
      double dmN = 0;
      for (int i = 0; i < 3; ++i) dmN += N[i] * (xm1[i][c] - xm0[i][c]);
      dgN += (xs1[c] - xs0[c] - dmN) * f.n[c];
    }
  for (int c = 0; c < 3; ++c) xs1[c] -= dgN * f.n[c];
  return facet_outside(xi);
}

}  // namespace emc::kernels
