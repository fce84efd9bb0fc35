// Frictionless contact by direct elimination, one slave on one master facet (docs/THEORY.md §3,
// §5), without MPI or Tpetra: a dense 4-node system (slave = node 0, masters = nodes 1..3,
// 12 dofs, node-major 3A+i) with a synthetic residual g(u) = A0 (u - u_n) + b (+ a cubic term),
// so the exact Jacobian of g is known. Reduced unknowns q: q_0, q_1 = dxi, deta of the slave,
// q_2 = its dummy, q_{3..11} = the master increments du_m. The reduced residual along the
// update map is R(q) = P(state)^T g(state), state = update steps 1-3 of §5 applied to the
// current iterate with increment q; the kernel's matrix P^T A Pt + X must be its Jacobian.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "frictionless_system.hpp"
#include "kernels/frictionless.hpp"

namespace k = emc::kernels;
using namespace emc::test::frictionless_system;

namespace {

enum class Terms { exact, half, paper };

/// The reduced matrix without D: exact = P^T A Pt + X (§5); half = P^T A P + X without the
/// step 2-3 terms (proto.py mode 'half'); paper = the same with (dN_i/dxi_k) g_s dq_k on the
/// master rows, i.e. dxi = dq instead of dq/2 (the paper's eq. 57-58, proto.py mode 'paper').
Mat reduced_matrix(const System& sys, const State& st, Terms t) {
  const k::FrictionlessBlocks b = blocks(sys, st);
  Dense d = dense(b);
  if (t != Terms::exact) {
    d.Pt = d.P;
    for (int i = 3; i < kN; ++i)
      for (int j = 3; j < kN; ++j) d.X[i][j] = 0;
    if (t == Terms::paper)
      for (int i = 3; i < kN; ++i)
        for (int q = 0; q < 2; ++q) d.X[i][q] *= 2;
  }
  Mat K = mul(mul(transpose(d.P), sys.A(st.u)), d.Pt);
  for (int i = 0; i < kN; ++i)
    for (int j = 0; j < kN; ++j) K[i][j] += d.X[i][j];
  return K;
}

/// The reduced residual P^T g at a state.
Vec reduced_residual(const System& sys, const State& st) {
  const Dense d = dense(blocks(sys, st));
  return mulv(transpose(d.P), sys.g(st.u));
}

/// Update steps 1-3 of §5 with increment dq: u += P dq (P of the current state), then project.
State update(const System& sys, const State& st, const Vec& dq) {
  const Dense d = dense(blocks(sys, st));
  State s2 = st;
  const Vec du = mulv(d.P, dq);
  for (int i = 0; i < kN; ++i) s2.u[i] += du[i];
  project(sys, s2);
  return s2;
}

/// Central finite-difference Jacobian of q -> R(q) (columns cols) and of q -> u(q).
void fd_jacobians(const System& sys, const State& st, const std::vector<int>& cols, double h,
                  Mat& JR, Mat& Ju) {
  JR = zeros();
  Ju = zeros();
  for (int j : cols) {
    Vec e{};
    e[j] = h;
    const State sp = update(sys, st, e);
    e[j] = -h;
    const State sm = update(sys, st, e);
    const Vec Rp = reduced_residual(sys, sp), Rm = reduced_residual(sys, sm);
    for (int i = 0; i < kN; ++i) {
      JR[i][j] = (Rp[i] - Rm[i]) / (2 * h);
      Ju[i][j] = (sp.u[i] - sm.u[i]) / (2 * h);
    }
  }
}

/// Well-shaped facet, slave 0.06 above it; u_n small and random; A0 = 4 I + U(-1, 1)
/// (non-symmetric, well conditioned), b = U(-0.5, 0.5). The current iterate: the masters rotate
/// by 0.3 rad about their centroid, translate and deform (0.05) between t_n and t_{n+1}; the
/// slave slides by about 0.15 and is projected (steps 2-3). deforming = false: xm1 == xm0.
void make(unsigned seed, bool deforming, System& sys, State& st, bool close = false) {
  sys.close = close;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  const double X[4][3] = {
      {0.35, 0.3, 0.06}, {0.0, 0.0, 0.0}, {1.1, 0.05, -0.03}, {0.1, 0.95, 0.05}};
  for (int a = 0; a < 4; ++a)
    for (int c = 0; c < 3; ++c) sys.X[a][c] = X[a][c];
  for (int i = 0; i < kN; ++i) {
    sys.u0[i] = 0.03 * U(rng);
    sys.b[i] = 0.5 * U(rng);
    for (int j = 0; j < kN; ++j) sys.A0[i][j] = (i == j ? 4.0 : 0.0) + U(rng);
  }
  st.u = sys.u0;
  if (deforming) {
    double ax[3] = {1.0 + 0.2 * U(rng), 2.0, 0.5};
    const double na = std::sqrt(dot(ax, ax));
    for (double& v : ax) v /= na;
    const double th = 0.3, cs = std::cos(th), sn = std::sin(th);
    double xm0[3][3], xs0[3], cen[3] = {0, 0, 0};
    sys.positions(sys.u0, xs0, xm0);
    for (int i = 0; i < 3; ++i)
      for (int c = 0; c < 3; ++c) cen[c] += xm0[i][c] / 3;
    const double tr[3] = {0.05, -0.03, 0.04};
    for (int i = 0; i < 3; ++i) {
      double r[3], axr[3];
      for (int c = 0; c < 3; ++c) r[c] = xm0[i][c] - cen[c];
      cross(ax, r, axr);
      const double ad = dot(ax, r);
      for (int c = 0; c < 3; ++c) {  // Rodrigues
        const double rot = r[c] * cs + axr[c] * sn + ax[c] * ad * (1 - cs);
        st.u[3 * (i + 1) + c] = cen[c] + rot + tr[c] + 0.05 * U(rng) - sys.X[i + 1][c];
      }
    }
  }
  const double slide[3] = {0.12, -0.08, 0.03};
  for (int c = 0; c < 3; ++c) st.u[c] += slide[c];
  st.xi[0] = st.xi[1] = 0;
  EXPECT_LT(project(sys, st), 0.0) << "the slave's CPP should be inside the facet";
}

}  // namespace

// §5: the exact matrix P^T A Pt + X is the Jacobian of the reduced residual along update steps
// 1-3. Tolerance: central differences with h = 1e-7 have a truncation error ~h^2 |R'''| ~ 1e-14
// and a round-off error ~eps |R| / h ~ 1e-9 relative (|R| ~ |K| ~ 1-10 here), so 1e-6 leaves
// three orders of margin while the paper's terms miss by > 1e-3 (next test).
TEST(Frictionless, ExactMatrixIsTheJacobianOfTheReducedResidual) {
  for (bool close : {false, true})
    for (unsigned seed : {1u, 2u, 3u}) {
      System sys;
      State st;
      make(seed, true, sys, st, close);
      Mat JR, Ju;
      fd_jacobians(sys, st, kRed, 1e-7, JR, Ju);
      const double e_exact = rel_diff(reduced_matrix(sys, st, Terms::exact), JR, kRed, kRed);
      const double e_half = rel_diff(reduced_matrix(sys, st, Terms::half), JR, kRed, kRed);
      const double e_paper = rel_diff(reduced_matrix(sys, st, Terms::paper), JR, kRed, kRed);
      std::printf("%s seed %u  |K - J_fd|/|J_fd|: exact %.2e  half %.2e  paper %.2e\n",
                  close ? "closing" : "keeping", seed, e_exact, e_half, e_paper);
      EXPECT_LT(e_exact, 1e-6);
      // the extra terms matter for a master that moves and rotates over the step
      EXPECT_GT(e_half, 1e-3);
      EXPECT_GT(e_paper, 1e-3);
    }
}

// §5: Pt's slave rows are the first-order update map du_s(dq) of steps 1-3 (the master rows
// are the identity: u_m += du_m), independent of g.
TEST(Frictionless, RightFactorIsTheLinearisedUpdateMap) {
  for (bool close : {false, true}) {
    System sys;
    State st;
    make(4, true, sys, st, close);
    Mat JR, Ju;
    fd_jacobians(sys, st, kRed, 1e-7, JR, Ju);
    const Dense d = dense(blocks(sys, st));
    const std::vector<int> slave = {0, 1, 2}, all = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11};
    const double e_t = rel_diff(d.Pt, Ju, all, kRed), e_p = rel_diff(d.P, Ju, slave, kRed);
    std::printf("%s: |Pt - du/dq_fd|/|.| %.2e, slave rows of P instead: %.2e\n",
                close ? "closing" : "keeping", e_t, e_p);
    EXPECT_LT(e_t, 1e-7);
    EXPECT_GT(e_p, 1e-3);
  }
}

// §5 last paragraph: a fixed master (xm1 == xm0; its dofs get no columns) has dxi = dq/2
// exactly and K = P^T A P + X on the q columns: Pt = P there (r_k = 0), the master rows carry
// (dN_i/dxi_k) g_s / 2; the paper's factor 1 (dxi = dq) is wrong on the master rows.
TEST(Frictionless, FixedMasterReducesToPtAPPlusX) {
  System sys;
  State st;
  make(5, false, sys, st);
  const k::FrictionlessBlocks b = blocks(sys, st);
  for (int r = 0; r < 3; ++r)
    for (int q = 0; q < 2; ++q) EXPECT_NEAR(b.Ptq[r][q], b.Pq[r][q], 1e-15);
  // dxi = dq/2 exactly (the step is linear on a fixed flat facet)
  for (int q = 0; q < 2; ++q) {
    Vec dq{};
    dq[q] = 0.01;
    const State s2 = update(sys, st, dq);
    EXPECT_NEAR(s2.xi[q] - st.xi[q], 0.005, 1e-14);
    EXPECT_NEAR(s2.xi[1 - q] - st.xi[1 - q], 0.0, 1e-14);
  }
  const std::vector<int> qcols = {0, 1};
  Mat JR, Ju;
  fd_jacobians(sys, st, qcols, 1e-7, JR, Ju);
  const Mat K = reduced_matrix(sys, st, Terms::exact);
  const Mat Kh = reduced_matrix(sys, st, Terms::half);  // P^T A P + X
  const Mat Kp = reduced_matrix(sys, st, Terms::paper);
  const double e = rel_diff(K, JR, kRed, qcols), eh = rel_diff(Kh, K, kRed, qcols),
               ep = rel_diff(Kp, JR, kRed, qcols);
  std::printf(
      "fixed master, q columns: exact vs FD %.2e, P^T A P + X vs exact %.2e, paper vs FD %.2e\n", e,
      eh, ep);
  EXPECT_LT(e, 1e-6);
  EXPECT_LT(eh, 1e-14);
  EXPECT_GT(ep, 1e-3);
}

// §5 conditions (a) and (b) after update steps 2-3, checked with independent geometry, to
// round-off (coordinates are O(1): a few eps).
TEST(Frictionless, ProjectionSatisfiesConditionsAandB) {
  for (unsigned seed : {6u, 7u}) {
    System sys;
    State st;
    make(seed, true, sys, st);
    // perturb the iterate (slave off the constraint, masters moved) and project again
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> U(-0.02, 0.02);
    for (double& v : st.u) v += U(rng);
    const double xi_in[2] = {st.xi[0], st.xi[1]};
    double xs_before[3], dummy[3][3];
    sys.positions(st.u, xs_before, dummy);
    project(sys, st);
    EXPECT_TRUE(xi_in[0] != st.xi[0] || xi_in[1] != st.xi[1]);
    double xs0[3], xm0[3][3], xs1[3], xm1[3][3], xsh[3], xmh[3][3];
    sys.positions(sys.u0, xs0, xm0);
    sys.positions(st.u, xs1, xm1);
    k::midpoint(xs0, xs1, xsh);
    k::midpoint(xm0, xm1, xmh);
    double t1[3], t2[3], n[3];
    for (int c = 0; c < 3; ++c) {
      t1[c] = xmh[1][c] - xmh[0][c];
      t2[c] = xmh[2][c] - xmh[0][c];
    }
    cross(t1, t2, n);
    const double nn = std::sqrt(dot(n, n));
    for (double& v : n) v /= nn;
    const double N[3] = {1 - st.xi[0] - st.xi[1], st.xi[0], st.xi[1]};
    // (a) (x_{s,n+1} - x_{s,n}) . n = (N (x_{m,n+1} - x_{m,n})) . n at n+1/2
    double ds[3], dm[3], d[3], moved[3];
    for (int c = 0; c < 3; ++c) {
      ds[c] = xs1[c] - xs0[c];
      dm[c] = 0;
      d[c] = xsh[c];
      for (int i = 0; i < 3; ++i) {
        dm[c] += N[i] * (xm1[i][c] - xm0[i][c]);
        d[c] -= N[i] * xmh[i][c];
      }
      moved[c] = xs1[c] - xs_before[c];
    }
    EXPECT_NEAR(dot(ds, n), dot(dm, n), 4e-15);
    // (b) xi is the CPP of x_{s,n+1/2}: x_{s,n+1/2} - x_{n+1/2}(xi) has no tangential part
    EXPECT_NEAR(dot(d, t1), 0.0, 4e-15);
    EXPECT_NEAR(dot(d, t2), 0.0, 4e-15);
    // step 3 moved x_{s,n+1} along n only
    EXPECT_NEAR(dot(moved, t1), 0.0, 4e-15);
    EXPECT_NEAR(dot(moved, t2), 0.0, 4e-15);
    // projecting again changes nothing
    State again = st;
    project(sys, again);
    for (int i = 0; i < kN; ++i) EXPECT_NEAR(again.u[i], st.u[i], 4e-15);
    for (int q = 0; q < 2; ++q) EXPECT_NEAR(again.xi[q], st.xi[q], 1e-14);
  }
}

// §3, eq. 56: P^T g has slave rows T^T g_s (dummy row 0) and master rows g_m + N^T g_s;
// frictionless_residual gives the same pieces.
TEST(Frictionless, ReducedResidualShapes) {
  System sys;
  State st;
  make(8, true, sys, st);
  const Vec g = sys.g(st.u);
  const Vec R = reduced_residual(sys, st);
  double xs0[3], xm0[3][3], xs1[3], xm1[3][3], xmh[3][3];
  sys.positions(sys.u0, xs0, xm0);
  sys.positions(st.u, xs1, xm1);
  k::midpoint(xm0, xm1, xmh);
  double tau[2][3];
  for (int c = 0; c < 3; ++c) {
    tau[0][c] = xmh[1][c] - xmh[0][c];
    tau[1][c] = xmh[2][c] - xmh[0][c];
  }
  const double N[3] = {1 - st.xi[0] - st.xi[1], st.xi[0], st.xi[1]};
  for (int q = 0; q < 2; ++q) EXPECT_NEAR(R[q], dot(tau[q], g.data()), 1e-14);
  EXPECT_EQ(R[2], 0.0);
  for (int i = 0; i < 3; ++i)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(R[3 * (i + 1) + c], g[3 * (i + 1) + c] + N[i] * g[c], 1e-14);
  const k::FrictionlessBlocks b = blocks(sys, st);
  double rq[2], madd[9];
  k::frictionless_residual(b, g.data(), rq, madd);
  for (int q = 0; q < 2; ++q) EXPECT_NEAR(rq[q], R[q], 1e-14);
  for (int j = 0; j < 9; ++j) EXPECT_NEAR(g[3 + j] + madd[j], R[3 + j], 1e-14);
  // the normal is the unit normal at n+1/2
  double nc[3];
  cross(tau[0], tau[1], nc);
  const double nn = std::sqrt(dot(nc, nc));
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(b.n[c], nc[c] / nn, 1e-15);
}

// Newton on the tiny nonlinear system (cubic term in g): (K + D) dq = -R, D = beta on the
// dummy, update steps 1-3. Exact terms: quadratic; the 'half' terms: linear.
TEST(Frictionless, NewtonConvergesQuadratically) {
  for (bool close : {false, true}) {
    System sys;
    State st0;
    make(9, true, sys, st0, close);
    sys.cubic = 2.0;
    std::vector<double> hist[2];
    for (int t = 0; t < 2; ++t) {
      State st = st0;
      for (int it = 0; it < 10; ++it) {
        const Vec R = reduced_residual(sys, st);
        hist[t].push_back(norm(R));
        if (hist[t].back() < 1e-13) break;
        Mat K = reduced_matrix(sys, st, t == 0 ? Terms::exact : Terms::half);
        const Mat A = sys.A(st.u);
        K[2][2] += (A[0][0] + A[1][1] + A[2][2]) / 3;  // D: beta on the dummy (§3)
        Vec mR{};
        for (int i = 0; i < kN; ++i) mR[i] = -R[i];
        st = update(sys, st, solve(K, mR));
        EXPECT_LT(std::fabs(k::facet_outside(st.xi)), 1.0);
      }
      std::printf("%s |P^T g|:", t == 0 ? "exact" : "half ");
      for (double r : hist[t]) std::printf(" %.1e", r);
      std::printf("\n");
    }
    const auto& h = hist[0];
    ASSERT_GE(h.size(), 4u);
    EXPECT_LT(h.back(), 1e-12 * h[0]);
    EXPECT_LE(h.size(), 7u);
    // quadratic: r_{k+1} <= C r_k^2 while above round-off
    for (size_t i = 1; i + 1 < h.size(); ++i)
      if (h[i + 1] > 1e-12) {
        EXPECT_LT(h[i + 1], 10.0 * h[i] * h[i]) << "iteration " << i;
      }
    // the simplified terms converge linearly (ratio ~1e-2, set by their 2e-2 relative error in
    // the matrix): far behind by the fifth residual
    ASSERT_GE(hist[1].size(), 5u);
    EXPECT_GT(hist[1][4], 1e3 * h[4]);
  }
}

// docs/THEORY.md §7.3: closing, step 3 puts x_{s,n+1} on the facet's plane at t_{n+1} (g_N = 0
// there, checked by an independent CPP at n+1) while xi stays the CPP of x_{s,n+1/2} at n+1/2
// (condition (b)) and x_{s,n+1} moves along n_{n+1/2} only. Coordinates are O(1) and the
// slave starts 0.06 off the facet: a few eps of round-off.
TEST(Frictionless, ClosingProjectionLandsOnTheFacetAtTheEndOfTheStep) {
  for (unsigned seed : {6u, 7u, 10u}) {
    System sys;
    State st;
    make(seed, true, sys, st, true);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> U(-0.02, 0.02);
    for (double& v : st.u) v += U(rng);
    double xs_before[3], dummy[3][3];
    sys.positions(st.u, xs_before, dummy);
    project(sys, st);
    double xs0[3], xm0[3][3], xs1[3], xm1[3][3], xsh[3], xmh[3][3];
    sys.positions(sys.u0, xs0, xm0);
    sys.positions(st.u, xs1, xm1);
    // g_N at n+1 on the facet at n+1 (independent of the kernels' facet_cpp)
    double t1[3], t2[3], n1[3], d1[3];
    for (int c = 0; c < 3; ++c) {
      t1[c] = xm1[1][c] - xm1[0][c];
      t2[c] = xm1[2][c] - xm1[0][c];
      d1[c] = xs1[c] - xm1[0][c];
    }
    cross(t1, t2, n1);
    const double nn1 = std::sqrt(dot(n1, n1));
    EXPECT_NEAR(dot(d1, n1) / nn1, 0.0, 4e-15);
    // (b) at n+1/2, and the move along n_{n+1/2}
    k::midpoint(xs0, xs1, xsh);
    k::midpoint(xm0, xm1, xmh);
    for (int c = 0; c < 3; ++c) {
      t1[c] = xmh[1][c] - xmh[0][c];
      t2[c] = xmh[2][c] - xmh[0][c];
    }
    const double N[3] = {1 - st.xi[0] - st.xi[1], st.xi[0], st.xi[1]};
    double d[3], moved[3];
    for (int c = 0; c < 3; ++c) {
      d[c] = xsh[c] - N[0] * xmh[0][c] - N[1] * xmh[1][c] - N[2] * xmh[2][c];
      moved[c] = xs1[c] - xs_before[c];
    }
    EXPECT_NEAR(dot(d, t1), 0.0, 4e-15);
    EXPECT_NEAR(dot(d, t2), 0.0, 4e-15);
    EXPECT_NEAR(dot(moved, t1), 0.0, 4e-15);
    EXPECT_NEAR(dot(moved, t2), 0.0, 4e-15);
    EXPECT_GT(std::sqrt(dot(moved, moved)), 1e-3) << "the closure should have moved the slave";
  }
}
