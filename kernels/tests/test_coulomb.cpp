// Coulomb friction of one sliding slave on one master facet (docs/THEORY.md §11), without MPI or
// Tpetra, on the dense 4-node system of test_frictionless (slave = node 0, masters = nodes 1..3,
// synthetic residual g(u) = A0 (u - u_n) + b + a cubic term with its exact Jacobian). The
// reduced residual along the update map of §5 is R(q) = P^T (g - f), f the friction pair
// (f_T on the slave, -N_i f_T on the masters, f_T = -mu |g_s . n| d, d the direction of
// -t + c s_T, t = the tangential part of g_s, c = kWeight); the kernel's
// matrix Pl^T A Pt + X + X_f must be its Jacobian (f_N's dependence on the displacements
// included), and where the slip rows are solved the force pair's work over the step is
// -mu |f_N| |s_T|.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "frictionless_system.hpp"
#include "kernels/coulomb.hpp"

namespace k = emc::kernels;
using namespace emc::test::frictionless_system;

namespace {

/// Well-shaped facet, slave 0.06 above it; u_n small and random; A0 = 4 I + U(-1, 1)
/// (non-symmetric, well conditioned), b = U(-0.5, 0.5). The current iterate: the masters rotate
/// by 0.3 rad about their centroid, translate and deform (0.05) between t_n and t_{n+1}; the
/// slave slides by about 0.15 and is projected (steps 2-3). deforming = false: xm1 == xm0.
void make(unsigned seed, bool deforming, System& sys, State& st, bool close = false,
          double slide_scale = 1.0) {
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
  for (int c = 0; c < 3; ++c) st.u[c] += slide_scale * slide[c];
  st.xi[0] = st.xi[1] = 0;
  EXPECT_LT(project(sys, st), 0.0) << "the slave's CPP should be inside the facet";
}

/// the slip's weight c of §11.1: A0's diagonal (about 4)
constexpr double kWeight = 4.0;

struct Friction {
  k::FrictionlessBlocks b;
  k::CoulombSlip c;
};

Friction friction(const System& sys, const State& st, double mu, double cw = kWeight) {
  double xs0[3], xm0[3][3], xs1[3], xm1[3][3];
  sys.positions(sys.u0, xs0, xm0);
  sys.positions(st.u, xs1, xm1);
  const Vec g = sys.g(st.u);
  Friction f;
  EXPECT_TRUE(k::frictionless_blocks(xs0, xs1, xm0, xm1, st.xi, g.data(), f.b, sys.close));
  k::SlipLaw law;
  law.mu = mu;
  law.weight = cw;
  EXPECT_TRUE(k::coulomb_slip(xs0, xs1, xm0, xm1, st.xi, g.data(), law, f.b, f.c));
  return f;
}

/// R = P^T (g - f) at a state.
Vec reduced_residual(const System& sys, const State& st, double mu) {
  const Friction f = friction(sys, st, mu);
  const Dense d = dense(f.b);
  Vec g = sys.g(st.u);
  for (int c = 0; c < 3; ++c) {
    g[c] -= f.c.fT[c];
    for (int i = 0; i < 3; ++i) g[3 * (i + 1) + c] += f.c.N[i] * f.c.fT[c];
  }
  return mulv(transpose(d.P), g);
}

/// The kernel's matrix: Pl^T A Pt + X + X_f (with_friction = false: the frictionless matrix).
Mat reduced_matrix(const System& sys, const State& st, double mu, bool with_friction = true) {
  const Friction f = friction(sys, st, mu);
  Dense d = dense(f.b);
  Mat Pl = d.P;
  if (with_friction)
    for (int r = 0; r < 3; ++r)
      for (int q = 0; q < 2; ++q) Pl[r][q] = f.c.Plq[r][q];
  Mat K = mul(mul(transpose(Pl), sys.A(st.u)), d.Pt);
  for (int i = 0; i < kN; ++i)
    for (int j = 0; j < kN; ++j) K[i][j] += d.X[i][j];
  if (with_friction)
    for (int q = 0; q < 2; ++q) {
      for (int j = 0; j < 9; ++j) K[q][3 + j] += f.c.Xsq[q][j];
      for (int l = 0; l < 2; ++l) K[q][l] += f.c.Xqq[q][l];
    }
  return K;
}

State update(const System& sys, const State& st, const Vec& dq) {
  const Dense d = dense(blocks(sys, st));
  State s2 = st;
  const Vec du = mulv(d.P, dq);
  for (int i = 0; i < kN; ++i) s2.u[i] += du[i];
  project(sys, s2);
  return s2;
}

Mat fd_jacobian(const System& sys, const State& st, double mu, double h) {
  Mat JR = zeros();
  for (int j : kRed) {
    Vec e{};
    e[j] = h;
    const Vec Rp = reduced_residual(sys, update(sys, st, e), mu);
    e[j] = -h;
    const Vec Rm = reduced_residual(sys, update(sys, st, e), mu);
    for (int i = 0; i < kN; ++i) JR[i][j] = (Rp[i] - Rm[i]) / (2 * h);
  }
  return JR;
}

}  // namespace

// docs/THEORY.md §11.3: the kernel's matrix is the Jacobian of the reduced residual with the
// friction pair along update steps 1-3, on a deforming, rotating master, keeping and closing
// the gap, for f_N of either sign. Tolerance as test_frictionless (central differences, h =
// 1e-7: truncation ~1e-14, round-off ~1e-9 relative): 1e-6; leaving out f_N's dependence on
// the displacements (the left factor and the g_s . dn term) misses by > 1e-3.
TEST(Coulomb, ExactMatrixIsTheJacobianOfTheReducedResidual) {
  for (bool close : {false, true})
    for (unsigned seed : {1u, 2u, 3u}) {
      System sys;
      State st;
      make(seed, true, sys, st, close);
      const double mu = 0.4;
      const Mat JR = fd_jacobian(sys, st, mu, 1e-7);
      const Friction f = friction(sys, st, mu);
      const Mat K = reduced_matrix(sys, st, mu);
      // f_N's dependence on g_s left out: the frictionless left factor P instead of Pl
      Mat Kn = K;
      Mat Pl = dense(f.b).P;
      for (int r = 0; r < 3; ++r)
        for (int q = 0; q < 2; ++q) Pl[r][q] = f.c.Plq[r][q];
      const Mat Kp = mul(mul(transpose(dense(f.b).P), sys.A(st.u)), dense(f.b).Pt);
      const Mat Kl = mul(mul(transpose(Pl), sys.A(st.u)), dense(f.b).Pt);
      for (int i = 0; i < kN; ++i)
        for (int j = 0; j < kN; ++j) Kn[i][j] += Kp[i][j] - Kl[i][j];
      const double e = rel_diff(K, JR, kRed, kRed), en = rel_diff(Kn, JR, kRed, kRed);
      const double ef = rel_diff(reduced_matrix(sys, st, mu, false), JR, kRed, kRed);
      std::printf(
          "%s seed %u f_N %+.3f |s_T| %.3f: |K - J_fd|/|J_fd| %.2e; without Pl %.2e; "
          "frictionless matrix %.2e\n",
          close ? "closing" : "keeping", seed, f.c.fN, f.c.slip, e, en, ef);
      EXPECT_GT(f.c.slip, 1e-3);
      EXPECT_LT(e, 1e-6);
      EXPECT_GT(en, 1e-3);
      EXPECT_GT(ef, 1e-3);
    }
}

// docs/THEORY.md §11.3: where the slip vanishes (the slave slides by 1e-9 to 1e-13 of the
// facet's size over the step, on a fixed master) the matrix is still the Jacobian: the force's
// direction d = (-t + c s_T) / |-t + c s_T| is smooth there, where s_T / |s_T| turns by O(1)
// over a change of q of the size of the slip (its derivative, mu |f_N| / |s_T|, is 1e8 to 1e12
// times the system's). Tolerance as above.
TEST(Coulomb, ExactMatrixWhereTheSlipVanishes) {
  for (double scale : {1e-9, 1e-13})
    for (unsigned seed : {1u, 2u, 3u}) {
      System sys;
      State st;
      make(seed, false, sys, st, false, scale);
      const double mu = 0.4;
      const Mat JR = fd_jacobian(sys, st, mu, 1e-7);
      const Friction f = friction(sys, st, mu);
      const double e = rel_diff(reduced_matrix(sys, st, mu), JR, kRed, kRed);
      std::printf("seed %u |s_T| %.2e |f_T| %.3f: |K - J_fd|/|J_fd| %.2e\n", seed, f.c.slip,
                  std::sqrt(f.c.fT[0] * f.c.fT[0] + f.c.fT[1] * f.c.fT[1] + f.c.fT[2] * f.c.fT[2]),
                  e);
      EXPECT_LT(f.c.slip, 1e-7);
      EXPECT_NEAR(std::sqrt(f.c.fT[0] * f.c.fT[0] + f.c.fT[1] * f.c.fT[1] + f.c.fT[2] * f.c.fT[2]),
                  mu * std::fabs(f.c.fN), 1e-14);
      EXPECT_LT(e, 1e-6);
    }
}

// docs/THEORY.md §11.2: f_T is tangential (f_T . n = 0) with |f_T| = mu |f_N|, the pair sums to
// zero (L), and its work over the step, f_T . (dx_s - N dx_m), is -work to round-off at any
// iterate. Where the slip rows are solved (the contact's tangential force t equals f_T: here
// g_s is replaced by f_N n - mu |f_N| e, e = s_T / |s_T|) the force opposes the slip, d = e, and
// the work is the dissipation mu |f_N| |s_T| > 0. mu = 0: no force, no terms.
TEST(Coulomb, WorkOfTheForcePairIsTheDissipation) {
  for (bool close : {false, true})
    for (unsigned seed : {4u, 5u}) {
      System sys;
      State st;
      make(seed, true, sys, st, close);
      double xs0[3], xm0[3][3], xs1[3], xm1[3][3];
      sys.positions(sys.u0, xs0, xm0);
      sys.positions(st.u, xs1, xm1);
      const Friction f = friction(sys, st, 0.3);
      auto work = [&](const k::CoulombSlip& c) {
        double w = 0;
        for (int r = 0; r < 3; ++r) {
          double rel = xs1[r] - xs0[r];
          for (int i = 0; i < 3; ++i) rel -= c.N[i] * (xm1[i][r] - xm0[i][r]);
          w += c.fT[r] * rel;
        }
        return w;
      };
      double fn = 0, ft = 0, sum = 0;
      for (int c = 0; c < 3; ++c) {
        fn += f.c.fT[c] * f.b.n[c];
        ft += f.c.fT[c] * f.c.fT[c];
        sum += f.c.fT[c] * (1 - f.c.N[0] - f.c.N[1] - f.c.N[2]);
      }
      const double w = work(f.c);
      EXPECT_NEAR(w, -f.c.work, 1e-14 * std::sqrt(ft));
      EXPECT_NEAR(fn, 0, 1e-15 * std::sqrt(ft));
      EXPECT_NEAR(std::sqrt(ft), 0.3 * std::fabs(f.c.fN), 1e-15 * std::fabs(f.c.fN));
      EXPECT_NEAR(sum, 0, 1e-15 * std::sqrt(ft));
      // the same state with the slip rows solved: t = f_T = -mu |f_N| e
      Vec g = sys.g(st.u);
      for (int c = 0; c < 3; ++c) g[c] = f.c.fN * f.b.n[c] - 0.3 * std::fabs(f.c.fN) * f.c.dir[c];
      k::CoulombSlip solved;
      k::SlipLaw law;
      law.mu = 0.3;
      law.weight = kWeight;
      ASSERT_TRUE(k::coulomb_slip(xs0, xs1, xm0, xm1, st.xi, g.data(), law, f.b, solved));
      const double ws = work(solved);
      std::printf("%s seed %u: work %.6e (rows solved %.6e), mu |f_N| |s_T| %.6e\n",
                  close ? "closing" : "keeping", seed, w, ws, 0.3 * std::fabs(f.c.fN) * f.c.slip);
      EXPECT_GT(solved.work, 0);
      EXPECT_NEAR(ws, -0.3 * std::fabs(f.c.fN) * f.c.slip, 1e-14 * solved.work);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(solved.fT[c], -0.3 * std::fabs(f.c.fN) * f.c.dir[c], 1e-15 * std::sqrt(ft));
      const Friction f0 = friction(sys, st, 0.0);
      const Mat K0 = reduced_matrix(sys, st, 0.0), Kf = reduced_matrix(sys, st, 0.0, false);
      EXPECT_EQ(f0.c.work, 0.0);
      EXPECT_LT(rel_diff(K0, Kf, kRed, kRed), 1e-15);
    }
}

// docs/THEORY.md §11.3: at the start iterate (no slip over the step, u_{n+1} = u_n on the
// contact) an entry with a hint (its last slip's direction) carries the force along the hint's
// tangential part, |f_T| = mu |f_N|, without turn terms; without a hint the direction is -t's.
TEST(Coulomb, HeldAlongTheHintWhereNothingSlipsYet) {
  System sys;
  State st;
  make(1, false, sys, st, false, 0.0);
  double xs0[3], xm0[3][3], xs1[3], xm1[3][3];
  sys.positions(sys.u0, xs0, xm0);
  sys.positions(st.u, xs1, xm1);
  const Vec g = sys.g(st.u);
  k::FrictionlessBlocks b;
  ASSERT_TRUE(k::frictionless_blocks(xs0, xs1, xm0, xm1, st.xi, g.data(), b, false));
  k::SlipLaw law;
  law.mu = 0.3;
  law.weight = kWeight;
  law.held = 1e-12;
  const double hint[3] = {0.6, -0.8, 0.0};
  for (int c = 0; c < 3; ++c) law.hint[c] = hint[c];
  k::CoulombSlip held, free;
  ASSERT_TRUE(k::coulomb_slip(xs0, xs1, xm0, xm1, st.xi, g.data(), law, b, held));
  law.hint[0] = law.hint[1] = 0;
  ASSERT_TRUE(k::coulomb_slip(xs0, xs1, xm0, xm1, st.xi, g.data(), law, b, free));
  ASSERT_LE(held.slip, 1e-12);
  double hn = 0, hT[3], h2 = 0, t[3], t2 = 0;
  for (int c = 0; c < 3; ++c) hn += hint[c] * b.n[c];
  for (int c = 0; c < 3; ++c) {
    hT[c] = hint[c] - hn * b.n[c];
    h2 += hT[c] * hT[c];
    t[c] = g[c] - held.fN * b.n[c];
    t2 += t[c] * t[c];
  }
  const double F = 0.3 * std::fabs(held.fN);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(held.fT[c], -F * hT[c] / std::sqrt(h2), 1e-15);
    EXPECT_NEAR(free.fT[c], F * t[c] / std::sqrt(t2), 1e-12 * F);
  }
  for (int q = 0; q < 2; ++q)
    for (int l = 0; l < 2; ++l) EXPECT_EQ(held.Xqq[q][l], 0.0);  // no turn of d
}
