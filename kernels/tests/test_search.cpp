// The contact search of kernels/search.hpp (docs/THEORY.md §2.5) on every enabled execution
// space: built and queried there, it answers what a brute-force loop over all facets answers on
// the host, bit for bit (a host backend; a device one to 1e-12, its compiler may fuse products),
// and what the reference backend (Serial) answers. Two builds on one backend give the same cell
// lists bit for bit (filled by atomics, then sorted); against Serial the grid's cell size may
// differ in its last bits only (a parallel sum of the facets' extents: within 3 n_f eps).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <type_traits>
#include <vector>

#include "kernels/search.hpp"
#include "support/backends.hpp"
#include "support/meshes.hpp"

namespace {

namespace k = emc::kernels;
namespace t = emc::kernels::test;
using Facets = std::vector<std::array<int, 3>>;

/// The exact box test and CPP of facet f, as a plain loop over the facets does it.
bool brute_cpp(const double y[3], const Facets& facets, const std::vector<double>& x, double margin,
               int f, k::Hit& h) {
  double xm[3][3], lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i < 3; ++i) {
      xm[a][i] = x[3 * facets[f][a] + i];
      lo[i] = std::min(lo[i], xm[a][i]);
      hi[i] = std::max(hi[i], xm[a][i]);
    }
  bool in_box = true;
  for (int i = 0; i < 3; ++i) in_box = in_box && y[i] >= lo[i] - margin && y[i] <= hi[i] + margin;
  h = k::Hit{};
  h.facet = f;
  return k::facet_cpp(y, xm, h.xi, h.gap) && (in_box || margin < 0);
}

/// docs/THEORY.md §2.5 and §5.5 over all facets (no grid): what FacetGrid::locate answers, with
/// the same tie tolerance.
k::Hit brute_force(const double y[3], const Facets& facets, const std::vector<double>& x,
                   double margin, double tie, int current = -1, double hyst = 0) {
  const double tol = 1e-9;
  k::Hit h, best, least;
  if (current >= 0 && brute_cpp(y, facets, x, -1, current, h) &&
      k::facet_outside(h.xi) <= std::max(hyst, tol)) {
    h.inside = true;
    return h;
  }
  double least_out = 1e300;
  for (int f = 0; f < static_cast<int>(facets.size()); ++f) {
    if (!brute_cpp(y, facets, x, margin, f, h)) continue;
    const double out = k::facet_outside(h.xi);
    if (out <= tol && (best.facet < 0 || std::fabs(h.gap) < std::fabs(best.gap) - tie)) {
      best = h;
      best.inside = true;
    }
    if (out < least_out) {
      least_out = out;
      least = h;
    }
  }
  if (best.facet >= 0 || current < 0) return best;
  if (least.facet < 0) {
    brute_cpp(y, facets, x, -1, current, least);
    least_out = k::facet_outside(least.xi);
  }
  least.inside = least_out <= hyst;
  return least;
}

/// The same hit: bit for bit, or (a device) the same facet and side, xi and gap to 1e-12.
void expect_same(const k::Hit& a, const k::Hit& b, bool bitwise, int q) {
  ASSERT_EQ(a.facet, b.facet) << "query " << q;
  EXPECT_EQ(a.inside, b.inside) << "query " << q;
  if (bitwise) {
    EXPECT_EQ(a.xi[0], b.xi[0]) << "query " << q;
    EXPECT_EQ(a.xi[1], b.xi[1]) << "query " << q;
    EXPECT_EQ(a.gap, b.gap) << "query " << q;
  } else {
    EXPECT_NEAR(a.xi[0], b.xi[0], 1e-12) << "query " << q;
    EXPECT_NEAR(a.xi[1], b.xi[1], 1e-12) << "query " << q;
    EXPECT_NEAR(a.gap, b.gap, 1e-12) << "query " << q;
  }
}

/// A summary of for_each_candidate at a point: the candidates' count and a sum over them in
/// their order (a functor, host and device alike).
template <class Grid>
struct CandidateSum {
  const Grid& g;
  double count = 0, sum = 0;
  KOKKOS_INLINE_FUNCTION void operator()(const k::Hit& h, double out) {
    count += 1;
    sum += h.gap * (h.facet + 1) + out + g.metric(h.facet).f.n[2];
  }
};

/// In a kernel over the points q of y: locate(y_q), locate(y_q, current, 1e-3) and a summary of
/// for_each_candidate (CandidateSum).
template <class E, class Grid, class Y, class Hits, class Cand>
void kernel_queries(const E& space, const Grid& grid, const Y& y, const Hits& hits,
                    const Cand& cand) {
  const Grid g = grid;
  Kokkos::parallel_for(
      "test::grid_queries", Kokkos::RangePolicy<E>(space, 0, y.extent(0)),
      KOKKOS_LAMBDA(const int q) {
        const double p[3] = {y(q, 0), y(q, 1), y(q, 2)};
        hits(q, 0) = g.locate(p);
        hits(q, 1) = g.locate(p, q % 7 == 0 ? -1 : (37 * q) % g.num_facets(), 1e-3);
        CandidateSum<Grid> c{g};
        g.for_each_candidate(p, c);
        cand(q, 0) = c.count;
        cand(q, 1) = c.sum;
      });
}

template <class E>
class Search : public ::testing::Test {
 public:
  using M = typename E::memory_space;
  using Grid = k::FacetGrid<M>;
  /// The grid of facets over x, built on E from Views.
  static Grid grid(const Facets& facets, const std::vector<double>& x, double margin) {
    return Grid(E(), t::rows<int, 3, M>(facets.front().data(), facets.size(), "test::facets"),
                t::rows<double, 3, M>(x.data(), x.size() / 3, "test::x"), margin);
  }
  /// locate_all on E for the points y (3 coordinates each), on the host.
  static std::vector<k::Hit> locate_all(const Grid& g, const std::vector<double>& y) {
    const auto n = y.size() / 3;
    typename Grid::HitsView hits("test::hits", n);
    g.locate_all(E(), t::rows<double, 3, M>(y.data(), n, "test::y"), hits);
    const auto hh = t::on_host(hits);
    return std::vector<k::Hit>(hh.data(), hh.data() + n);
  }
};
TYPED_TEST_SUITE(Search, t::Backends, t::BackendName);

// Points near a bumpy sheet, a quarter exactly on facet edges or vertices (ties to the lowest
// facet id), some outside the grid: the batch query finds the brute-force facet of each.
TYPED_TEST(Search, LocateAllMatchesBruteForce) {
  using E = TypeParam;
  const t::Sheet s(40);
  for (const double margin : {0.05, 0.01}) {
    const auto grid = TestFixture::grid(s.facets, s.x, margin);
    EXPECT_GT(grid.num_cells(), 20u);
    const auto y = s.near_points(4000, 3, -0.1, 1.1, 1.2 * margin, 40);
    const auto hits = TestFixture::locate_all(grid, y);
    int found = 0;
    for (int q = 0; q < 4000; ++q) {
      expect_same(hits[q], brute_force(&y[3 * q], s.facets, s.x, margin, grid.tie()),
                  t::bitwise<E>(), q);
      found += hits[q].facet >= 0;
    }
    EXPECT_GT(found, 1500);  // a third lie off the sheet's square, a sixth beyond the margin
  }
}

// facet_point_distance on the backend against the closed form: a point at height h above the
// facet point of xi (any xi, also outside the facet) lies h from it, whatever the facet's
// orientation; the longest edge is the largest of the three edge lengths.
TYPED_TEST(Search, FacetPointDistanceIsTheHeightAboveThePoint) {
  using E = TypeParam;
  constexpr int n = 64;
  // per case: y (3), xm (9), xi (2), then the heights h; a right triangle of legs 2 and 1,
  // rotated about z by th and tilted about x by th / 2, xi from outside to inside the facet
  Kokkos::View<double* [14], Kokkos::HostSpace> in("in", n);
  std::vector<double> heights(n);
  for (int q = 0; q < n; ++q) {
    const double th = 0.1 * q, c = std::cos(th), s = std::sin(th);
    const double ct = std::cos(0.5 * th), st = std::sin(0.5 * th);
    const double legs[3][2] = {{0, 0}, {2, 0}, {0, 1}};
    double xm[3][3];
    for (int v = 0; v < 3; ++v) {
      const double xr = c * legs[v][0] - s * legs[v][1], yr = s * legs[v][0] + c * legs[v][1];
      xm[v][0] = xr + 0.3;
      xm[v][1] = ct * yr - 0.2;
      xm[v][2] = st * yr + 0.1;
    }
    const double xi[2] = {-0.5 + 0.03 * q, 0.8 - 0.02 * q};
    const k::Facet f = k::facet(xm);
    double N[3];
    k::facet_shape(xi, N);
    heights[q] = 0.01 * (q - 20);
    for (int i = 0; i < 3; ++i)
      in(q, i) = N[0] * xm[0][i] + N[1] * xm[1][i] + N[2] * xm[2][i] + heights[q] * f.n[i];
    for (int v = 0; v < 3; ++v)
      for (int i = 0; i < 3; ++i) in(q, 3 + 3 * v + i) = xm[v][i];
    in(q, 12) = xi[0];
    in(q, 13) = xi[1];
  }
  auto din = Kokkos::create_mirror_view_and_copy(typename E::memory_space(), in);
  Kokkos::View<double* [2], typename E::memory_space> out("out", n);
  Kokkos::parallel_for(
      "emcontact::kernels::test::facet_point_distance", Kokkos::RangePolicy<E>(0, n),
      KOKKOS_LAMBDA(const int q) {
        double y[3], xm[3][3], xi[2] = {din(q, 12), din(q, 13)};
        for (int i = 0; i < 3; ++i) y[i] = din(q, i);
        for (int v = 0; v < 3; ++v)
          for (int i = 0; i < 3; ++i) xm[v][i] = din(q, 3 + 3 * v + i);
        k::facet_point_distance(y, xm, xi, out(q, 0), out(q, 1));
      });
  auto host = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), out);
  for (int q = 0; q < n; ++q) {
    EXPECT_NEAR(host(q, 0), std::fabs(heights[q]), 1e-14) << q;
    EXPECT_NEAR(host(q, 1), std::sqrt(5.0), 1e-14) << q;  // the hypotenuse
  }
}

// Facets of every orientation (a sphere, its poles degenerate): the brute-force facet.
TYPED_TEST(Search, SphereMatchesBruteForce) {
  using E = TypeParam;
  Facets facets;
  std::vector<double> x;
  const double c[3] = {0.5, 0.4, 0.3};
  t::sphere(24, 0.5, c, facets, x);
  std::mt19937 rng(19);
  std::normal_distribution<double> dn(0, 1);
  for (const double margin : {0.01, 0.06}) {
    const auto grid = TestFixture::grid(facets, x, margin);
    std::vector<double> y;
    for (int q = 0; q < 3000; ++q) {
      const double u[3] = {dn(rng), dn(rng), dn(rng)};
      const double nu = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
      const double r = 0.5 + 1.2 * margin * (2.0 * (rng() % 1001) / 1000 - 1);
      for (int i = 0; i < 3; ++i) y.push_back(c[i] + r * u[i] / nu);
    }
    const auto hits = TestFixture::locate_all(grid, y);
    int found = 0;
    for (int q = 0; q < 3000; ++q) {
      expect_same(hits[q], brute_force(&y[3 * q], facets, x, margin, grid.tie()), t::bitwise<E>(),
                  q);
      found += hits[q].facet >= 0;
    }
    EXPECT_GT(found, 2000);
  }
}

// In a kernel on E: locate with and without a current facet (hysteresis), and a summary of
// for_each_candidate (count, a sum over the candidates in their order); the same as a host loop
// over the reference backend's grid.
TYPED_TEST(Search, QueriesInKernelMatchReference) {
  using E = TypeParam;
  using M = typename E::memory_space;
  const t::Sheet s(40);
  const auto grid = TestFixture::grid(s.facets, s.x, 0.05);
  const auto ref = Search<t::Reference>::grid(s.facets, s.x, 0.05);
  const auto yh = s.near_points(5000, 9, -0.1, 1.1, 0.08, 40);
  const int n = static_cast<int>(yh.size() / 3);
  Kokkos::View<k::Hit* [2], M> hits("test::hits", n);
  Kokkos::View<double* [2], M> cand("test::candidates", n);
  kernel_queries(E(), grid, t::rows<double, 3, M>(yh.data(), n, "test::y"), hits, cand);
  const auto hh = t::on_host(hits);
  const auto ch = t::on_host(cand);
  int with_candidates = 0;
  for (int q = 0; q < n; ++q) {
    const double* p = &yh[3 * q];
    expect_same(hh(q, 0), ref.locate(p), t::bitwise<E>(), q);
    expect_same(hh(q, 1), ref.locate(p, q % 7 == 0 ? -1 : (37 * q) % ref.num_facets(), 1e-3),
                t::bitwise<E>(), q);
    CandidateSum<std::decay_t<decltype(ref)>> c{ref};
    ref.for_each_candidate(p, c);
    EXPECT_EQ(ch(q, 0), c.count) << "query " << q;
    if (t::bitwise<E>())
      EXPECT_EQ(ch(q, 1), c.sum) << "query " << q;
    else
      EXPECT_NEAR(ch(q, 1), c.sum, 1e-12 * c.count) << "query " << q;
    with_candidates += c.count > 0;
  }
  EXPECT_GT(with_candidates, 1000);
}

/// The cell lists on the host: start offsets and blocks.
template <class Lists>
auto host_lists(const Lists& l) {
  return std::make_pair(t::on_host(l.start), t::on_host(l.blocks));
}

// Two builds on E: the same shape and cell lists bit for bit (a cell's facets sorted by id,
// unused lanes last); against the reference backend the cell size within 3 n_f eps.
TYPED_TEST(Search, BuildIsDeterministic) {
  const t::Sheet s(40);
  const auto a = TestFixture::grid(s.facets, s.x, 0.05);
  const auto b = TestFixture::grid(s.facets, s.x, 0.05);
  const auto ref = Search<t::Reference>::grid(s.facets, s.x, 0.05);
  const double nf = static_cast<double>(s.facets.size());
  EXPECT_NEAR(a.shape().h, ref.shape().h,
              3 * nf * std::numeric_limits<double>::epsilon() * ref.shape().h);
  ASSERT_EQ(a.shape().h, b.shape().h);
  ASSERT_EQ(a.num_cells(), b.num_cells());
  EXPECT_EQ(a.tie(), b.tie());
  for (const bool reach : {false, true}) {
    const auto [sa, ea] = host_lists(reach ? a.reach_lists() : a.box_lists());
    const auto [sb, eb] = host_lists(reach ? b.reach_lists() : b.box_lists());
    ASSERT_EQ(sa.extent(0), a.num_cells() + 1);
    ASSERT_EQ(ea.extent(0), eb.extent(0));
    std::size_t used = 0;
    for (std::size_t c = 0; c < a.num_cells(); ++c) {
      ASSERT_EQ(sa(c), sb(c));
      int last = -1;
      for (int e = k::CellBlock::W * sa(c); e < k::CellBlock::W * sa(c + 1); ++e) {
        const auto &ba = ea(e / k::CellBlock::W), &bb = eb(e / k::CellBlock::W);
        const int j = e % k::CellBlock::W, f = ba.facet[j];
        ASSERT_EQ(f, bb.facet[j]) << "cell " << c;
        for (int i = 0; i < 3; ++i) {
          EXPECT_EQ(ba.lo[i][j], bb.lo[i][j]);
          EXPECT_EQ(ba.hi[i][j], bb.hi[i][j]);
        }
        if (f < 0) {
          last = static_cast<int>(nf);  // unused lanes come last
          continue;
        }
        EXPECT_LT(last, f) << "cell " << c;
        last = f;
        ++used;
      }
    }
    EXPECT_EQ(used, (reach ? a.reach_lists() : a.box_lists()).entries);
    EXPECT_GT(used, s.facets.size());
  }
}

// No facets, no points: nothing found, nothing to do.
TYPED_TEST(Search, EmptyGridAndEmptyBatch) {
  using E = TypeParam;
  using M = typename E::memory_space;
  const k::FacetGrid<M> empty(E(), Facets{}, std::vector<double>{}, 0.1);
  const std::vector<double> y = {0, 0, 0};
  const auto one = TestFixture::locate_all(empty, y);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].facet, -1);
  const t::Sheet s(4);
  const auto grid = TestFixture::grid(s.facets, s.x, 0.05);
  typename k::FacetGrid<M>::HitsView none("test::none", 0);
  grid.locate_all(E(), Kokkos::View<double* [3], Kokkos::LayoutRight, M>("test::no_y", 0), none);
  std::vector<k::Hit> hits(3);
  grid.locate_all(E(), nullptr, 0, hits);
  EXPECT_TRUE(hits.empty());
}

}  // namespace
