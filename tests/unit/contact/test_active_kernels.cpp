// docs/THEORY.md §8: every per-active-slave loop of contact, run as its Kokkos kernel over many
// random entries, against a plain host loop over the same entries calling the pointwise
// functions of kernels/ directly: the results must agree bit for bit (each entry writes only
// its own block), and the reductions to round-off of their sums.
#include <gtest/gtest.h>

#include <Kokkos_Core.hpp>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "emcontact/contact/active_kernels.hpp"
#include "emcontact/contact/contact.hpp"
#include "emcontact/contact/detection.hpp"
#include "emcontact/contact/nodes.hpp"
#include "emcontact/views.hpp"
#include "kernels/coulomb.hpp"
#include "kernels/facet.hpp"
#include "kernels/frictionless.hpp"

namespace c = emc::contact;
namespace k = emc::kernels;

namespace {

/// n entries, each with its own slave node and facet (4 contact nodes per entry): a facet near
/// the plane z = 0, the slave near it (slightly in front or behind), positions at t_n and
/// t_{n+1} a small random motion apart; g a random residual on 3 dofs per entry.
struct Entries {
  int n;
  c::Refs refs;
  c::Positions x0, x1;
  Kokkos::View<double**, Kokkos::LayoutLeft, emc::ExecSpace> g;
  std::vector<c::ActiveRef> host;

  explicit Entries(int count, unsigned seed = 7) : n(count) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    refs = c::Refs("refs", n);
    x0 = c::Positions("x0", 4 * n);
    x1 = c::Positions("x1", 4 * n);
    g = decltype(g)("g", 3 * n, 1);
    auto r = Kokkos::create_mirror_view(refs);
    auto a = Kokkos::create_mirror_view(x0);
    auto b = Kokkos::create_mirror_view(x1);
    auto gh = Kokkos::create_mirror_view(g);
    for (int e = 0; e < n; ++e) {
      const double base[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.3, 0.3, 0.02}};
      for (int p = 0; p < 4; ++p)
        for (int i = 0; i < 3; ++i) {
          a(4 * e + p, i) = base[p][i] + 0.05 * u(rng) + 10 * e;
          b(4 * e + p, i) = a(4 * e + p, i) + 0.01 * u(rng);
        }
      c::ActiveRef& ref = r(e);
      ref.m[0] = 4 * e;
      ref.m[1] = 4 * e + 1;
      ref.m[2] = 4 * e + 2;
      ref.s = 4 * e + 3;
      for (int i = 0; i < 3; ++i) ref.dof[i] = 3 * e + i;
      ref.xi[0] = 0.3 + 0.1 * u(rng);
      ref.xi[1] = 0.3 + 0.1 * u(rng);
      ref.edge = 1;
      ref.closes = e % 3 == 0;
      ref.frictionless = 1;
      ref.mu = 0.1 * (e % 6);  // Coulomb: mu = 0 to 0.5 (not drawn: the other data stay)
      if (e % 2) ref.dir[0] = 0.6, ref.dir[1] = -0.8;  // a last slip's direction (not drawn)
      for (int i = 0; i < 3; ++i) gh(3 * e + i, 0) = u(rng);
      host.push_back(ref);
    }
    Kokkos::deep_copy(refs, r);
    Kokkos::deep_copy(x0, a);
    Kokkos::deep_copy(x1, b);
    Kokkos::deep_copy(g, gh);
  }

  void facet(const c::Positions& x, const c::ActiveRef& a, double xm[3][3]) const {
    auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), x);
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) xm[j][i] = h(a.m[j], i);
  }
  void slave(const c::Positions& x, const c::ActiveRef& a, double y[3]) const {
    auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), x);
    for (int i = 0; i < 3; ++i) y[i] = h(a.s, i);
  }
  double gval(int dof) const {
    return Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), g)(dof, 0);
  }
  /// The entry's slave and facet at t_n and t_{n+1}, and its slave's residual, as kernels take
  /// them.
  struct Host {
    double xm0[3][3], xm1[3][3], y0[3], y1[3], gs[3];
  };
  Host host_entry(int q) const {
    Host h;
    facet(x0, host[q], h.xm0);
    facet(x1, host[q], h.xm1);
    slave(x0, host[q], h.y0);
    slave(x1, host[q], h.y1);
    for (int i = 0; i < 3; ++i) h.gs[i] = gval(host[q].dof[i]);
    return h;
  }
};

constexpr int kEntries = 200;

/// The facets of an m x m grid of unit squares in z = 0 (nodes j (m + 1) + i), two triangles
/// each, normals +z.
std::vector<std::array<int, 3>> plane_facets(int m) {
  std::vector<std::array<int, 3>> facets;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) {
      const int a = j * (m + 1) + i;
      facets.push_back({a, a + 1, a + m + 2});
      facets.push_back({a, a + m + 2, a + m + 1});
    }
  return facets;
}

}  // namespace

TEST(ActiveKernels, NormalForcesEqualAHostLoop) {
  Entries e(kEntries);
  c::Values fN("fN", e.n);
  c::normal_forces(e.refs, e.x0, e.x1, e.g, fN);
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), fN);
  for (int q = 0; q < e.n; ++q) {
    double xm0[3][3], xm1[3][3], xh[3][3];
    e.facet(e.x0, e.host[q], xm0);
    e.facet(e.x1, e.host[q], xm1);
    k::midpoint(xm0, xm1, xh);
    const k::Facet f = k::facet(xh);
    double s = 0;
    for (int i = 0; i < 3; ++i) s += e.gval(e.host[q].dof[i]) * f.n[i];
    EXPECT_EQ(h(q), s) << "entry " << q;
  }
}

TEST(ActiveKernels, GapRangeAndBehindEqualAHostLoop) {
  Entries e(kEntries);
  double lo, hi;
  c::gap_range(e.refs, e.x1, lo, hi);
  Kokkos::View<int*, emc::ExecSpace> behind("behind", e.n);
  c::behind_facets(e.refs, e.x1, behind);
  auto bh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), behind);
  double l = 1e300, u = -1e300;
  int n_behind = 0;
  for (int q = 0; q < e.n; ++q) {
    double xm[3][3], y[3], xi[2], gap;
    e.facet(e.x1, e.host[q], xm);
    e.slave(e.x1, e.host[q], y);
    ASSERT_TRUE(k::facet_cpp(y, xm, xi, gap));
    l = std::min(l, gap);
    u = std::max(u, gap);
    const int expect = gap < -c::gap_roundoff(1.0, y);
    EXPECT_EQ(bh(q), expect) << "entry " << q;
    n_behind += expect;
  }
  EXPECT_EQ(lo, l);
  EXPECT_EQ(hi, u);
  EXPECT_GT(n_behind, 0);  // the random set has nodes on both sides
  EXPECT_LT(n_behind, e.n);
}

TEST(ActiveKernels, StickCorrectionsEqualAHostLoop) {
  Entries e(kEntries);
  c::Values3 d("d", e.n);
  const double moved = c::stick_corrections(e.refs, e.x0, e.x1, d);
  auto dh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), d);
  double mx = 0;
  for (int q = 0; q < e.n; ++q) {
    double xm0[3][3], xm1[3][3], y0[3], y1[3], N[3];
    e.facet(e.x0, e.host[q], xm0);
    e.facet(e.x1, e.host[q], xm1);
    e.slave(e.x0, e.host[q], y0);
    e.slave(e.x1, e.host[q], y1);
    k::facet_shape(e.host[q].xi, N);
    for (int i = 0; i < 3; ++i) {
      const double t = e.host[q].closes
                           ? N[0] * xm1[0][i] + N[1] * xm1[1][i] + N[2] * xm1[2][i]
                           : y0[i] + N[0] * (xm1[0][i] - xm0[0][i]) +
                                 N[1] * (xm1[1][i] - xm0[1][i]) + N[2] * (xm1[2][i] - xm0[2][i]);
      EXPECT_EQ(dh(q, i), t - y1[i]);
      mx = std::max(mx, std::fabs(t - y1[i]));
    }
  }
  EXPECT_EQ(moved, mx);
}

// docs/THEORY.md §8: positions read where a kernel needs them (NodePositions: owned, imported
// and rigid nodes) are the bits fill() writes, and the start iterate's corrections computed from
// either are the same.
TEST(ActiveKernels, NodePositionsAreTheFilledPositions) {
  Entries e(kEntries);
  const int nodes = 4 * e.n, nd = nodes - 7;  // the last 7 contact nodes rigid
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  Kokkos::View<double* [3], emc::ExecSpace> X("X", nodes);
  Kokkos::View<emc::LO* [3], emc::ExecSpace> src("src", nodes);
  Kokkos::View<double**, Kokkos::LayoutLeft, emc::ExecSpace> v("v", 3 * nodes, 1), r("r", 64, 1);
  auto Xh = Kokkos::create_mirror_view(X);
  auto sh = Kokkos::create_mirror_view(src);
  auto vh = Kokkos::create_mirror_view(v);
  auto rh = Kokkos::create_mirror_view(r);
  const auto x1 = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), e.x1);
  for (int j = 0; j < 64; ++j) rh(j, 0) = 0.01 * u(rng);
  for (int l = 0; l < nodes; ++l)
    for (int c = 0; c < 3; ++c) {
      vh(3 * l + c, 0) = 0.01 * u(rng);
      const bool remote = l % 5 == 1;  // imported from another rank: one of r's values
      sh(l, c) = remote ? -1 - (3 * l + c) % 64 : 3 * nodes - 1 - (3 * l + c);  // out of order
      Xh(l, c) = x1(l, c);
    }
  Kokkos::deep_copy(X, Xh);
  Kokkos::deep_copy(src, sh);
  Kokkos::deep_copy(v, vh);
  Kokkos::deep_copy(r, rh);
  const c::NodePositions p{X, src, nd, v, r};
  c::Positions x("x", nodes);
  c::fill(p, x);
  const auto xh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), x);
  for (int l = 0; l < nodes; ++l)
    for (int c = 0; c < 3; ++c) {
      const int k = sh(l, c);
      const double ul = l >= nd ? 0.0 : k >= 0 ? vh(k, 0) : rh(-1 - k, 0);
      EXPECT_EQ(xh(l, c), Xh(l, c) + ul) << "node " << l;
    }
  c::Values3 d_lazy("d_lazy", e.n), d_filled("d_filled", e.n);
  const double m_lazy = c::stick_corrections(e.refs, e.x0, p, d_lazy);
  const double m_filled = c::stick_corrections(e.refs, e.x0, x, d_filled);
  EXPECT_EQ(m_lazy, m_filled);
  EXPECT_GT(m_lazy, 0);
  const auto a = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), d_lazy);
  const auto b = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), d_filled);
  for (int q = 0; q < e.n; ++q)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(a(q, c), b(q, c)) << "entry " << q;
}

// §4.1: the corrections land on each entry's own three dofs, as a host loop adds them.
TEST(ActiveKernels, AddToSlavesEqualsAHostLoop) {
  Entries e(kEntries);
  c::Values3 d("d", e.n);
  c::stick_corrections(e.refs, e.x0, e.x1, d);
  Kokkos::View<double**, Kokkos::LayoutLeft, emc::ExecSpace> u("u", e.g.extent(0), 1);
  Kokkos::deep_copy(u, e.g);  // a copy: g keeps the values before
  c::add_to_slaves(e.refs, d, u);
  const auto uh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), u);
  const auto dh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), d);
  for (int q = 0; q < e.n; ++q)
    for (int i = 0; i < 3; ++i)
      EXPECT_EQ(uh(e.host[q].dof[i], 0), e.gval(e.host[q].dof[i]) + dh(q, i));
}

// §4.1: where nothing moved over the step (Newton's cold start u_{n+1} = u_n), a keeping entry
// is not touched, not even by round-off; a closing one is moved onto its master point.
TEST(ActiveKernels, StickCorrectionsLeaveTheColdStartAlone) {
  Entries e(kEntries);
  c::Values3 d("d", e.n);
  c::stick_corrections(e.refs, e.x0, e.x0, d);
  auto dh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), d);
  int closing = 0;
  for (int q = 0; q < e.n; ++q)
    for (int i = 0; i < 3; ++i) {
      if (!e.host[q].closes) EXPECT_EQ(dh(q, i), 0.0) << "entry " << q;
      closing += e.host[q].closes && dh(q, i) != 0.0;
    }
  EXPECT_GT(closing, 0);
}

TEST(ActiveKernels, FrictionlessProjectionsAndBlocksEqualAHostLoop) {
  Entries e(kEntries);
  c::Values3 xs1("xs1", e.n);
  Kokkos::View<double* [2], emc::ExecSpace> xi("xi", e.n);
  c::Values out("out", e.n);
  auto xih = Kokkos::create_mirror_view(xi);
  for (int q = 0; q < e.n; ++q)
    for (int i = 0; i < 2; ++i) xih(q, i) = e.host[q].xi[i];
  Kokkos::deep_copy(xi, xih);
  c::frictionless_projections(e.refs, e.x0, e.x1, xs1, xi, out);
  Kokkos::View<k::FrictionlessBlocks*, emc::ExecSpace> blocks("blocks", e.n);
  c::frictionless_blocks(e.refs, e.x0, e.x1, e.g, blocks);
  auto xsh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), xs1);
  Kokkos::deep_copy(xih, xi);
  auto oh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), out);
  auto bh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), blocks);
  for (int q = 0; q < e.n; ++q) {
    const auto& a = e.host[q];
    double xm0[3][3], xm1[3][3], y0[3], y1[3], z[2] = {a.xi[0], a.xi[1]}, gs[3];
    e.facet(e.x0, a, xm0);
    e.facet(e.x1, a, xm1);
    e.slave(e.x0, a, y0);
    e.slave(e.x1, a, y1);
    double yb[3] = {y1[0], y1[1], y1[2]};
    const double o = k::frictionless_project(y0, yb, xm0, xm1, z, a.closes != 0);
    EXPECT_EQ(oh(q), o);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(xsh(q, i), yb[i]);
    EXPECT_EQ(xih(q, 0), z[0]);
    EXPECT_EQ(xih(q, 1), z[1]);
    for (int i = 0; i < 3; ++i) gs[i] = e.gval(a.dof[i]);
    k::FrictionlessBlocks b;
    k::frictionless_blocks(y0, y1, xm0, xm1, a.xi, gs, b, a.closes != 0);
    EXPECT_EQ(0, std::memcmp(&b, &bh(q), sizeof b)) << "entry " << q;
  }
}

TEST(ActiveKernels, ClosureTermsEqualAHostLoop) {
  Entries e(kEntries);
  c::Values3 F("F", e.n), wn("wn", e.n), N1("N1", e.n);
  auto Fh = Kokkos::create_mirror_view(F);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int q = 0; q < e.n; ++q)
    for (int i = 0; i < 3; ++i) Fh(q, i) = u(rng);
  Kokkos::deep_copy(F, Fh);
  Kokkos::View<int*, emc::ExecSpace> unrestorable("unrestorable", e.n);
  const c::ClosureTerms t = c::closure_terms(e.refs, e.x0, e.x1, F, wn, N1, unrestorable);
  auto uh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), unrestorable);
  auto wh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), wn);
  auto Nh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), N1);
  double work = 0, roundoff = 0, scale = 0;
  int pushing = 0, flagged = 0;
  for (int q = 0; q < e.n; ++q) {
    const auto& a = e.host[q];
    double xm0[3][3], xm1[3][3], y0[3], y1[3], N[3], w_e = 0;
    e.facet(e.x0, a, xm0);
    e.facet(e.x1, a, xm1);
    e.slave(e.x0, a, y0);
    e.slave(e.x1, a, y1);
    k::facet_shape(a.xi, N);
    for (int c3 = 0; c3 < 3; ++c3) {
      double rel = y1[c3] - y0[c3];
      for (int i = 0; i < 3; ++i) rel -= N[i] * (xm1[i][c3] - xm0[i][c3]);
      w_e += Fh(q, c3) * rel;
      scale += std::fabs(Fh(q, c3) * rel);
    }
    work += w_e;
    const double r_e = (std::fabs(Fh(q, 0)) + std::fabs(Fh(q, 1)) + std::fabs(Fh(q, 2))) *
                       c::gap_roundoff(a.edge, y1);
    roundoff += r_e;
    double xi1[2], gap, M[3];
    ASSERT_TRUE(k::facet_cpp(y1, xm1, xi1, gap));
    const k::Facet f1 = k::facet(xm1);
    const double w = std::max(0.0, Fh(q, 0) * f1.n[0] + Fh(q, 1) * f1.n[1] + Fh(q, 2) * f1.n[2]);
    pushing += w > 0;
    // §7.2, the closure's fallback: energy the entry gave, or took with no impulse to give back
    const bool expect_flag = w_e > r_e || (w == 0 && -w_e > r_e);
    EXPECT_EQ(uh(q), expect_flag ? 1 : 0) << "entry " << q;
    flagged += expect_flag;
    k::facet_shape(xi1, M);
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(wh(q, i), w * f1.n[i]);
      EXPECT_EQ(Nh(q, i), M[i]);
    }
  }
  // sums: a parallel reduction may add in another order (threads): round-off of the terms
  EXPECT_NEAR(t.work, work, 1e-14 * scale);
  EXPECT_NEAR(t.roundoff, roundoff, 1e-14 * roundoff);
  EXPECT_GT(pushing, 0);
  EXPECT_GT(flagged, 0);
  EXPECT_LT(flagged, e.n);
}

// docs/THEORY.md §6.3 inside a kernel: entered_facet for many slave nodes over a grid of
// facets, run in a parallel_for, against the same calls in a host loop.
TEST(ActiveKernels, EnteredFacetInAKernelEqualsAHostLoop) {
  // a 20 x 20 grid of squares in z = 0 (two triangles each, normals +z); slaves crossing it
  const int m = 20, nn = (m + 1) * (m + 1), ns = 500;
  const auto facets = plane_facets(m);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> x0(3 * (nn + ns)), x1;
  for (int j = 0; j <= m; ++j)
    for (int i = 0; i <= m; ++i) {
      const int a = j * (m + 1) + i;
      x0[3 * a] = i;
      x0[3 * a + 1] = j;
      x0[3 * a + 2] = 0.01 * (u(rng) - 0.5);
    }
  x1 = x0;
  for (int s = 0; s < ns; ++s) {
    const int n = nn + s;
    x0[3 * n] = m * u(rng);
    x0[3 * n + 1] = m * u(rng);
    x0[3 * n + 2] = 0.05 * u(rng);
    x1[3 * n] = x0[3 * n] + 0.01 * (u(rng) - 0.5);
    x1[3 * n + 1] = x0[3 * n + 1] + 0.01 * (u(rng) - 0.5);
    x1[3 * n + 2] = -0.1 * u(rng);
  }
  c::Pair pair;
  pair.facets = facets;
  pair.dmax = 0.5;
  pair.edge = 1;
  const c::EntryRule rule = c::entry_rule(pair);
  const c::FacetGrid grid(facets, x1, pair.dmax);
  using Unmanaged = Kokkos::MemoryTraits<Kokkos::Unmanaged>;
  const Kokkos::View<const int* [3], Kokkos::HostSpace, Unmanaged> fv(
      reinterpret_cast<const int*>(facets.data()), facets.size());
  const Kokkos::View<const double*[3], Kokkos::HostSpace, Unmanaged> v0(x0.data(), nn + ns),
      v1(x1.data(), nn + ns);
  Kokkos::View<c::Hit*, Kokkos::HostSpace> hits("hits", ns);
  const c::FacetGrid* gp = &grid;
  Kokkos::parallel_for("test::entered_facet",
                       Kokkos::RangePolicy<Kokkos::DefaultHostExecutionSpace>(0, ns),
                       [=](const int s) {
                         const double n_s[3] = {0, 0, -1};
                         hits(s) = c::entered_facet(*gp, fv, v0, v1, nn + s, n_s, rule);
                       });
  int entered = 0;
  for (int s = 0; s < ns; ++s) {
    const double n_s[3] = {0, 0, -1};
    const c::Hit h = c::entered_facet(grid, pair, x0, x1, nn + s, n_s, rule);
    EXPECT_EQ(hits(s).facet, h.facet);
    EXPECT_EQ(hits(s).gap, h.gap);
    EXPECT_EQ(hits(s).xi[0], h.xi[0]);
    EXPECT_EQ(hits(s).xi[1], h.xi[1]);
    entered += h.facet >= 0;
  }
  EXPECT_GT(entered, ns / 2);  // most cross the plane within the step
}

// §5 step 2 as a kernel: slaves above a plane of facets whose current facet lies elsewhere move
// to the facet under them (next_facet at n+1/2) and are projected there, as a host loop of the
// same calls does.
TEST(ActiveKernels, FrictionlessSwitchEqualsAHostLoop) {
  const int m = 10, nn = (m + 1) * (m + 1), ns = 60;
  const auto facets = plane_facets(m);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  // nodes: the plane, then per slave the slave and two neighbours (its triangle faces -z)
  const int total = nn + 3 * ns;
  c::Positions x0("x0", total), x1("x1", total), xh("xh", total);
  auto a0 = Kokkos::create_mirror_view(x0);
  auto a1 = Kokkos::create_mirror_view(x1);
  for (int j = 0; j <= m; ++j)
    for (int i = 0; i <= m; ++i) {
      const int a = j * (m + 1) + i;
      const double p[3] = {double(i), double(j), 0.01 * (u(rng) - 0.5)};
      for (int d = 0; d < 3; ++d) a0(a, d) = a1(a, d) = p[d];
    }
  for (int s = 0; s < ns; ++s) {
    const int n = nn + 3 * s;
    const double y[3] = {1 + (m - 2) * u(rng), 1 + (m - 2) * u(rng), 1e-3 * u(rng)};
    const double off[3][3] = {{0, 0, 0}, {0, 0.1, 0}, {0.1, 0, 0}};  // (0,0.1)x(0.1,0): -z
    for (int q = 0; q < 3; ++q)
      for (int d = 0; d < 3; ++d) {
        a0(n + q, d) = y[d] + off[q][d];
        a1(n + q, d) = a0(n + q, d) + (d == 2 ? -2e-3 : 0.02 * (u(rng) - 0.5));
      }
  }
  Kokkos::deep_copy(x0, a0);
  Kokkos::deep_copy(x1, a1);
  c::midpoint(x0, x1, xh);
  Kokkos::View<int* [3], emc::ExecSpace> fv("facets", facets.size());
  auto fh = Kokkos::create_mirror_view(fv);
  for (std::size_t f = 0; f < facets.size(); ++f)
    for (int a = 0; a < 3; ++a) fh(f, a) = facets[f][a];
  Kokkos::deep_copy(fv, fh);
  c::LocalSlaves ls;
  ls.node = Kokkos::View<int*, emc::ExecSpace>("node", ns);
  ls.start = Kokkos::View<int*, emc::ExecSpace>("start", ns + 1);
  ls.tri = Kokkos::View<int* [3], emc::ExecSpace>("tri", ns);
  auto nh = Kokkos::create_mirror_view(ls.node);
  auto sh = Kokkos::create_mirror_view(ls.start);
  auto th = Kokkos::create_mirror_view(ls.tri);
  c::Refs refs("refs", ns);
  auto rh = Kokkos::create_mirror_view(refs);
  std::vector<int> leaving(ns), slave_k(ns), current(ns);
  for (int s = 0; s < ns; ++s) {
    const int n = nn + 3 * s;
    nh(s) = n;
    sh(s) = s;
    th(s, 0) = n;
    th(s, 1) = n + 1;
    th(s, 2) = n + 2;
    current[s] = static_cast<int>(u(rng) * facets.size()) % facets.size();  // far, mostly
    rh(s).s = n;
    for (int a = 0; a < 3; ++a) rh(s).m[a] = facets[current[s]][a];
    rh(s).closes = s % 2;
    leaving[s] = slave_k[s] = s;
  }
  sh(ns) = ns;
  Kokkos::deep_copy(ls.node, nh);
  Kokkos::deep_copy(ls.start, sh);
  Kokkos::deep_copy(ls.tri, th);
  Kokkos::deep_copy(refs, rh);
  auto to_view = [](const std::vector<int>& v) {
    Kokkos::View<int*, emc::ExecSpace> d("v", v.size());
    auto h = Kokkos::create_mirror_view(d);
    for (std::size_t k = 0; k < v.size(); ++k) h(k) = v[k];
    Kokkos::deep_copy(d, h);
    return d;
  };
  c::Pair pair;
  pair.dmax = 0.5;
  const c::EntryRule rule = c::entry_rule(pair);
  const c::FacetGrid grid(fv, xh, pair.dmax);
  c::Values3 xs1("xs1", ns);
  Kokkos::View<double* [2], emc::ExecSpace> xi("xi", ns);
  c::Values out("out", ns);
  Kokkos::View<int*, emc::ExecSpace> next("next", ns);
  c::frictionless_switch(grid, ls, fv, refs, to_view(leaving), to_view(slave_k), to_view(current),
                         x0, x1, xh, rule, xs1, xi, out, next);
  auto xsh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), xs1);
  auto xih = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), xi);
  auto oh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), out);
  auto nxh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), next);
  auto hh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), xh);
  int switched = 0;
  for (int s = 0; s < ns; ++s) {
    double n_s[3];
    c::slave_normal(ls, s, hh, n_s);
    EXPECT_NEAR(n_s[2], -1, 1e-12);
    const double y[3] = {hh(nn + 3 * s, 0), hh(nn + 3 * s, 1), hh(nn + 3 * s, 2)};
    const c::Hit h = c::next_facet(grid, y, n_s, rule);
    const int expect = h.facet < 0 || h.facet == current[s] ? -1 : h.facet;
    ASSERT_EQ(nxh(s), expect) << "slave " << s;
    if (expect < 0) continue;
    ++switched;
    double xm0[3][3], xm1[3][3], y0[3], y1[3], z[2] = {h.xi[0], h.xi[1]};
    for (int a = 0; a < 3; ++a)
      for (int d = 0; d < 3; ++d) {
        xm0[a][d] = a0(facets[expect][a], d);
        xm1[a][d] = a1(facets[expect][a], d);
      }
    for (int d = 0; d < 3; ++d) {
      y0[d] = a0(nn + 3 * s, d);
      y1[d] = a1(nn + 3 * s, d);
    }
    const double o = k::frictionless_project(y0, y1, xm0, xm1, z, s % 2 != 0);
    EXPECT_EQ(oh(s), o);
    EXPECT_EQ(xih(s, 0), z[0]);
    EXPECT_EQ(xih(s, 1), z[1]);
    for (int d = 0; d < 3; ++d) EXPECT_EQ(xsh(s, d), y1[d]);
  }
  EXPECT_GT(switched, ns / 2);
}

// docs/THEORY.md §11.1, §11.3: the friction force, dissipation and derivative terms of every
// sliding entry (coulomb_slips, on the frictionless blocks of the same state) against
// kernels::coulomb_slip in a host loop: bit for bit (each entry writes its own record).
TEST(ActiveKernels, CoulombSlipsEqualAHostLoop) {
  Entries e(kEntries);
  Kokkos::View<k::FrictionlessBlocks*, emc::ExecSpace> blocks("blocks", e.n);
  c::frictionless_blocks(e.refs, e.x0, e.x1, e.g, blocks);
  Kokkos::View<k::CoulombSlip*, emc::ExecSpace> slips("slips", e.n);
  c::Values weight("weight", e.n);  // a different slip weight per entry
  auto wh = Kokkos::create_mirror_view(weight);
  for (int q = 0; q < e.n; ++q) wh(q) = 0.5 + q;
  Kokkos::deep_copy(weight, wh);
  c::coulomb_slips(e.refs, e.x0, e.x1, e.g, weight, blocks, slips);
  auto sh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), slips);
  int forced = 0;
  for (int q = 0; q < e.n; ++q) {
    const auto& a = e.host[q];
    const auto h = e.host_entry(q);
    k::FrictionlessBlocks b;
    k::frictionless_blocks(h.y0, h.y1, h.xm0, h.xm1, a.xi, h.gs, b, a.closes != 0);
    k::CoulombSlip expect;
    k::SlipLaw law;
    law.mu = a.mu;
    law.weight = wh(q);
    law.held = 64 * k::epsilon() * a.edge;
    for (int c = 0; c < 3; ++c) law.hint[c] = a.dir[c];
    ASSERT_TRUE(k::coulomb_slip(h.y0, h.y1, h.xm0, h.xm1, a.xi, h.gs, law, b, expect));
    EXPECT_EQ(0, std::memcmp(&expect, &sh(q), sizeof expect)) << "entry " << q;
    forced += expect.fT[0] != 0 || expect.fT[1] != 0 || expect.fT[2] != 0;
  }
  // the records are not trivial: friction works on every entry with mu > 0 (5 in 6)
  EXPECT_GT(forced, e.n / 2);
}

// docs/THEORY.md §11.4: the return map's state of every entry (f_N, trial force, s_T, |s_T|,
// the CPP at t_n) against kernels::coulomb_state in a host loop: bit for bit.
TEST(ActiveKernels, CoulombStatesEqualAHostLoop) {
  Entries e(kEntries);
  Kokkos::View<k::CoulombState*, emc::ExecSpace> states("states", e.n);
  c::coulomb_states(e.refs, e.x0, e.x1, e.g, states);
  auto sh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), states);
  int pressing = 0;
  for (int q = 0; q < e.n; ++q) {
    const auto h = e.host_entry(q);
    k::CoulombState expect;
    k::coulomb_state(h.y0, h.y1, h.xm0, h.xm1, e.host[q].xi, h.gs, expect);
    EXPECT_EQ(0, std::memcmp(&expect, &sh(q), sizeof expect)) << "entry " << q;
    EXPECT_GT(expect.slip, 0) << "entry " << q;  // random motions: every entry slips
    pressing += expect.fN > 0;
  }
  EXPECT_GT(pressing, 0);  // f_N of both signs
  EXPECT_LT(pressing, e.n);
}

// docs/THEORY.md §11.4, §4.1: where a returning entry sticks (the CPP of x_{s,n} on its facet at
// t_n; its xi kept on a degenerate facet) against facet_cpp in a host loop: bit for bit. Every
// 7th entry's facet at t_n is collapsed to a point (no CPP).
TEST(ActiveKernels, StartPointsEqualAHostLoop) {
  Entries e(kEntries);
  auto a0 = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), e.x0);
  for (int q = 0; q < e.n; q += 7)
    for (int j = 1; j < 3; ++j)
      for (int i = 0; i < 3; ++i) a0(e.host[q].m[j], i) = a0(e.host[q].m[0], i);
  Kokkos::deep_copy(e.x0, a0);
  Kokkos::View<double* [2], emc::ExecSpace> xi("xi", e.n);
  c::start_points(e.refs, e.x0, xi);
  auto xih = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), xi);
  int kept = 0;
  for (int q = 0; q < e.n; ++q) {
    const auto& a = e.host[q];
    double xm[3][3], y[3], z[2], gap;
    e.facet(e.x0, a, xm);
    e.slave(e.x0, a, y);
    const bool ok = k::facet_cpp(y, xm, z, gap);
    EXPECT_EQ(ok, q % 7 != 0) << "entry " << q;
    EXPECT_EQ(xih(q, 0), ok ? z[0] : a.xi[0]) << "entry " << q;
    EXPECT_EQ(xih(q, 1), ok ? z[1] : a.xi[1]) << "entry " << q;
    kept += !ok;
  }
  EXPECT_EQ(kept, (e.n + 6) / 7);
}

// docs/THEORY.md §1.6: the round-off of each slave's position at t_{n+1} (eps times the sum of
// its coordinates' magnitudes: Newton's floor for the projected slaves' rows) against a host
// loop: bit for bit.
TEST(ActiveKernels, PositionRoundoffEqualsAHostLoop) {
  Entries e(kEntries);
  c::Values r("r", e.n);
  c::position_roundoff(e.refs, e.x1, r);
  auto rh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), r);
  for (int q = 0; q < e.n; ++q) {
    double y[3];
    e.slave(e.x1, e.host[q], y);
    const double expect = std::numeric_limits<double>::epsilon() *
                          (std::fabs(y[0]) + std::fabs(y[1]) + std::fabs(y[2]));
    EXPECT_EQ(rh(q), expect) << "entry " << q;
    EXPECT_GT(rh(q), 0) << "entry " << q;
  }
}

// beta = tr(A_ss) / 3 (docs/THEORY.md §3.2) by the kernel over the dummies equals the host loop
// over each dof's diagonal entry, bit for bit, on a matrix with off-diagonal entries, a row
// without a diagonal entry and a column map that holds the other rank's dofs.
TEST(ActiveKernels, DummyBetasEqualAHostLoop) {
  using emc::GO;
  using emc::Map;
  using emc::Matrix;
  auto comm = Tpetra::getDefaultComm();
  const int nodes = 5, n = 3 * nodes * comm->getSize();
  auto map = Teuchos::rcp(new Map(n, 3 * nodes, 0, comm));
  Matrix A(map, 4);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> val(-2.0, 5.0);
  for (std::size_t l = 0; l < map->getNodeNumElements(); ++l) {
    const GO i = map->getGlobalElement(l);
    std::vector<GO> cols = {(i + 1) % n, (i + n - 4) % n, (i + 7) % n};
    if (i % 7 != 1) cols.push_back(i);  // some rows have no diagonal entry
    std::vector<double> v;
    for (std::size_t k = 0; k < cols.size(); ++k) v.push_back(val(rng));
    A.insertGlobalValues(i, Teuchos::ArrayView<const GO>(cols),
                         Teuchos::ArrayView<const double>(v));
  }
  A.fillComplete();
  std::vector<GO> dummies;
  for (int s = 0; s < nodes; s += 2)  // every other owned node is a slave
    for (int c = 0; c < 3; ++c) dummies.push_back(map->getGlobalElement(3 * s + c));
  const int ns = static_cast<int>(dummies.size() / 3);
  Kokkos::View<GO*, emc::ExecSpace> dof("dof", dummies.size());
  Kokkos::deep_copy(dof,
                    Kokkos::View<const GO*, Kokkos::HostSpace>(dummies.data(), dummies.size()));
  c::Values beta("beta", ns);
  c::dummy_betas(A, dof, beta);
  auto bh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), beta);
  int zero_rows = 0;
  for (int k = 0; k < ns; ++k) {
    double tr = 0;
    for (int c = 0; c < 3; ++c) {
      tr += c::diagonal_entry(A, dummies[3 * k + c]);
      zero_rows += dummies[3 * k + c] % 7 == 1;
    }
    EXPECT_EQ(bh(k), tr / 3) << "slave " << k;
    EXPECT_NE(bh(k), 0.0);
  }
  EXPECT_GT(zero_rows, 0);  // the case of a row without its diagonal entry is met
  // the offsets found once stay right for new values on the same graph (a Newton iterate)
  const auto at = c::diagonal_offsets(A, dof);
  A.resumeFill();
  A.scale(-3.0);
  A.fillComplete();
  c::dummy_betas_at(A, at, beta);
  Kokkos::deep_copy(bh, beta);
  for (int k = 0; k < ns; ++k) {
    double tr = 0;
    for (int c = 0; c < 3; ++c) tr += c::diagonal_entry(A, dummies[3 * k + c]);
    EXPECT_EQ(bh(k), tr / 3) << "slave " << k << " after new values";
  }
  // eq. 59: the frictionless beta, each diagonal entry / 3 summed in dof order (the host loop
  // the laws used), by the kernel over the slaves' rows of the local matrix
  std::vector<int> slaves;
  for (int k = 0; k < ns; ++k) slaves.push_back(static_cast<int>(dummies[3 * k] / 3));
  c::Values mean("mean", ns);
  c::mean_diagonals(A, emc::to_view("slaves", slaves), mean);
  auto mh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), mean);
  for (int k = 0; k < ns; ++k) {
    double b = 0;
    for (int c = 0; c < 3; ++c) b += c::diagonal_entry(A, dummies[3 * k + c]) / 3;
    EXPECT_EQ(mh(k), b) << "slave " << k;
  }
}
