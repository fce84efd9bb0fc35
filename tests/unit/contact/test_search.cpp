// Contact geometry without MPI (docs/THEORY.md §2.3, §2.5): the facet CPP is the orthogonal
// projection, and the grid search returns exactly what a brute-force loop over all facets
// returns.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

#include "emcontact/contact/search.hpp"
#include "kernels/facet.hpp"

namespace k = emc::kernels;

TEST(Facet, ProjectionIsOrthogonalAndGapSigned) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> d(-1, 1);
  for (int t = 0; t < 100; ++t) {
    double xm[3][3], y[3], xi[2], gap;
    for (auto& p : xm)
      for (double& c : p) c = d(rng);
    for (double& c : y) c = 2 * d(rng);
    ASSERT_TRUE(k::facet_cpp(y, xm, xi, gap));
    const k::Facet f = k::facet(xm);
    double N[3], r[3];
    k::facet_shape(xi, N);
    for (int i = 0; i < 3; ++i) r[i] = y[i] - (N[0] * xm[0][i] + N[1] * xm[1][i] + N[2] * xm[2][i]);
    double rt1 = 0, rt2 = 0, rn = 0, rr = 0;
    for (int i = 0; i < 3; ++i) {
      rt1 += r[i] * f.t1[i];
      rt2 += r[i] * f.t2[i];
      rn += r[i] * f.n[i];
      rr += r[i] * r[i];
    }
    EXPECT_NEAR(rt1, 0, 1e-12);
    EXPECT_NEAR(rt2, 0, 1e-12);
    EXPECT_NEAR(rn, gap, 1e-12);
    EXPECT_NEAR(std::fabs(gap), std::sqrt(rr), 1e-12);
    // moving y along n does not change its CPP (§2: flat facets)
    double y2[3], xi2[2], gap2;
    for (int i = 0; i < 3; ++i) y2[i] = y[i] + 0.3 * f.n[i];
    k::facet_cpp(y2, xm, xi2, gap2);
    EXPECT_NEAR(xi2[0], xi[0], 1e-12);
    EXPECT_NEAR(gap2, gap + 0.3, 1e-12);
  }
}

namespace {

/// A bumpy triangulated surface z = 0.1 sin(3x) cos(2y) on [0,1]^2, n x n squares.
void bumpy(int n, std::vector<std::array<int, 3>>& facets, std::vector<double>& x,
           double amp = 0.1) {
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double px = double(i) / n, py = double(j) / n;
      x.insert(x.end(), {px, py, amp * std::sin(3 * px) * std::cos(2 * py)});
    }
  auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      facets.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      facets.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
}

/// The exact box test and CPP of facet f, as a plain loop over the facets does it.
bool brute_cpp(const double y[3], const std::vector<std::array<int, 3>>& facets,
               const std::vector<double>& x, double margin, int f, emc::contact::Hit& h) {
  double xm[3][3], lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i < 3; ++i) {
      xm[a][i] = x[3 * facets[f][a] + i];
      lo[i] = std::min(lo[i], xm[a][i]);
      hi[i] = std::max(hi[i], xm[a][i]);
    }
  bool in_box = true;
  for (int i = 0; i < 3; ++i) in_box = in_box && y[i] >= lo[i] - margin && y[i] <= hi[i] + margin;
  h = emc::contact::Hit{};
  h.facet = f;
  return k::facet_cpp(y, xm, h.xi, h.gap) && (in_box || margin < 0);
}

/// docs/THEORY.md §2.5 and §5.5 over all facets (no grid): what FacetGrid::locate answers,
/// with the same tie tolerance.
emc::contact::Hit brute_force(const double y[3], const std::vector<std::array<int, 3>>& facets,
                              const std::vector<double>& x, double margin, double tie,
                              int current = -1, double hyst = 0) {
  const double tol = 1e-9;
  emc::contact::Hit h, best, least;
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

/// The same bits: facet, xi, gap and inside.
void expect_same(const emc::contact::Hit& a, const emc::contact::Hit& b, int t) {
  ASSERT_EQ(a.facet, b.facet) << "query " << t;
  EXPECT_EQ(a.inside, b.inside) << "query " << t;
  EXPECT_EQ(a.xi[0], b.xi[0]) << "query " << t;
  EXPECT_EQ(a.xi[1], b.xi[1]) << "query " << t;
  EXPECT_EQ(a.gap, b.gap) << "query " << t;
}

/// Query points near the bumpy surface, a quarter exactly on grid edges or vertices (ties).
std::vector<double> near_points(int count, unsigned seed, double lo, double hi, double dz) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(lo, hi), ddz(-dz, dz);
  std::vector<double> y;
  for (int t = 0; t < count; ++t) {
    double p[2] = {d(rng), d(rng)};
    if (t % 4 == 0) {
      p[0] = std::round(p[0] * 40) / 40;
      if (t % 8 == 0) p[1] = std::round(p[1] * 40) / 40;
    }
    y.insert(y.end(), {p[0], p[1], 0.1 * std::sin(3 * p[0]) * std::cos(2 * p[1]) + ddz(rng)});
  }
  return y;
}

}  // namespace

// Every query near the surface (within the margin) finds the brute-force facet, including
// points on shared edges and vertices (ties to the lowest facet id).
TEST(FacetGrid, MatchesBruteForce) {
  std::vector<std::array<int, 3>> facets;
  std::vector<double> x;
  bumpy(40, facets, x);
  const double margin = 0.05;
  emc::contact::FacetGrid grid(facets, x, margin);
  EXPECT_GT(grid.num_cells(), 20u);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> d(0, 1), dz(-0.04, 0.04);
  int found = 0;
  for (int t = 0; t < 4000; ++t) {
    double y[3] = {d(rng), d(rng), 0};
    if (t % 4 == 0) {  // exactly on a grid vertex or edge: ties
      y[0] = std::round(y[0] * 40) / 40;
      if (t % 8 == 0) y[1] = std::round(y[1] * 40) / 40;
    }
    y[2] = 0.1 * std::sin(3 * y[0]) * std::cos(2 * y[1]) + dz(rng);
    const auto a = grid.locate(y);
    const auto b = brute_force(y, facets, x, margin, grid.tie());
    expect_same(a, b, t);
    found += a.facet >= 0;
  }
  EXPECT_GT(found, 3800);  // a few queries near the outer border project outside every facet
}

namespace {

/// Whether the segment from a to b meets the box lo - m .. hi + m (slabs).
bool segment_meets(const double a[3], const double b[3], const double lo[3], const double hi[3],
                   double m) {
  double t0 = 0, t1 = 1;
  for (int i = 0; i < 3; ++i) {
    const double d = b[i] - a[i];
    if (d == 0) {
      if (a[i] < lo[i] - m || a[i] > hi[i] + m) return false;
      continue;
    }
    double ta = (lo[i] - m - a[i]) / d, tb = (hi[i] + m - a[i]) / d;
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t0 <= t1;
}

/// The facets whose box, at x or at `from` (empty: x only), grown by m meets the segment.
std::vector<int> brute_segment(const double a[3], const double b[3],
                               const std::vector<std::array<int, 3>>& facets,
                               const std::vector<double>& x, const std::vector<double>& from,
                               double m) {
  std::vector<int> out;
  for (std::size_t f = 0; f < facets.size(); ++f) {
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (const auto* v : {&x, &from})
      for (int n : facets[f])
        for (int i = 0; i < 3 && !v->empty(); ++i) {
          lo[i] = std::min(lo[i], (*v)[3 * n + i]);
          hi[i] = std::max(hi[i], (*v)[3 * n + i]);
        }
    if (segment_meets(a, b, lo, hi, m)) out.push_back(static_cast<int>(f));
  }
  return out;
}

/// The grid of the facets' sweeps from `from` to x (FacetGrid with `from`).
emc::contact::FacetGrid swept_grid(const std::vector<std::array<int, 3>>& facets,
                                   const std::vector<double>& x, double margin,
                                   const std::vector<double>& from) {
  const auto dev = [](auto v) {
    return Kokkos::create_mirror_view_and_copy(emc::ExecSpace::memory_space(), v);
  };
  using Points = Kokkos::View<const double* [3], Kokkos::HostSpace>;
  return emc::contact::FacetGrid(
      dev(Kokkos::View<const int* [3], Kokkos::HostSpace>(facets.front().data(), facets.size())),
      dev(Points(x.data(), x.size() / 3)), margin, dev(Points(from.data(), from.size() / 3)));
}

}  // namespace

// docs/THEORY.md §6.3: the cells along a segment hold every facet whose grown box (of its sweep
// from `from` to x) the segment meets: short and long segments, along the axes, ending far
// outside the grid, and points; every facet visited meets the segment's box.
TEST(FacetGrid, SegmentVisitsEveryBoxItMeets) {
  std::vector<std::array<int, 3>> facets;
  std::vector<double> x, from;
  bumpy(20, facets, x);
  from = x;
  for (std::size_t n = 0; n < x.size(); n += 3) from[n + 2] += 0.3 * x[n];  // a sheared sweep
  const double margin = 0.02;
  for (const bool swept : {false, true}) {
    std::vector<double> none;
    const auto& f0 = swept ? from : none;
    const auto grid =
        swept ? swept_grid(facets, x, margin, from) : emc::contact::FacetGrid(facets, x, margin);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> d(-0.2, 1.2), far(-50, 50);
    for (int t = 0; t < 600; ++t) {
      double a[3] = {d(rng), d(rng), 0.5 * d(rng)}, b[3] = {d(rng), d(rng), 0.5 * d(rng)};
      if (t % 5 == 1)
        for (double& c : b) c = a[0] + 0.01 * (c - a[0]);  // short
      if (t % 5 == 2) b[0] = a[0], b[1] = a[1];            // along z
      if (t % 5 == 3)
        for (double& c : b) c = far(rng);  // far outside the grid
      if (t % 5 == 4)
        for (int i = 0; i < 3; ++i) b[i] = a[i];  // a point
      std::vector<int> seen;
      grid.for_each_on_segment(a, b, [&](int f) { seen.push_back(f); });
      std::sort(seen.begin(), seen.end());
      seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
      const auto want = brute_segment(a, b, facets, x, f0, margin);
      for (int f : want)
        ASSERT_TRUE(std::binary_search(seen.begin(), seen.end(), f))
            << "segment " << t << " misses facet " << f;
      double lo[3], hi[3];
      for (int i = 0; i < 3; ++i) {
        lo[i] = std::min(a[i], b[i]);
        hi[i] = std::max(a[i], b[i]);
      }
      for (int f : seen) {  // every facet visited meets the segment's box
        double flo[3] = {1e300, 1e300, 1e300}, fhi[3] = {-1e300, -1e300, -1e300};
        for (const std::vector<double>* v :
             std::initializer_list<const std::vector<double>*>{&x, &f0})
          for (int n : facets[f])
            for (int i = 0; i < 3 && !v->empty(); ++i) {
              flo[i] = std::min(flo[i], (*v)[3 * n + i]);
              fhi[i] = std::max(fhi[i], (*v)[3 * n + i]);
            }
        for (int i = 0; i < 3; ++i) {
          EXPECT_LE(flo[i] - margin, hi[i] + 1e-12) << t;
          EXPECT_GE(fhi[i] + margin, lo[i] - 1e-12) << t;
        }
      }
    }
  }
}

// The batch query (visited in grid-cell order) gives every point the same hit, bit for bit, as
// its own locate(), including points outside the grid (no hit).
TEST(FacetGrid, BatchInCellOrderMatchesSingleQueries) {
  std::vector<std::array<int, 3>> facets;
  std::vector<double> x;
  bumpy(40, facets, x);
  emc::contact::FacetGrid grid(facets, x, 0.05);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> d(-0.2, 1.2), dz(-0.1, 0.1);
  std::vector<double> y;
  for (int t = 0; t < 5000; ++t) {
    const double a = d(rng), b = d(rng);
    y.insert(y.end(), {a, b, 0.1 * std::sin(3 * a) * std::cos(2 * b) + dz(rng)});
  }
  std::vector<emc::contact::Hit> hits;
  grid.locate_all(y.data(), y.size() / 3, hits);
  ASSERT_EQ(hits.size(), y.size() / 3);
  int found = 0, outside = 0;
  for (std::size_t k = 0; k < hits.size(); ++k) {
    const auto one = grid.locate(&y[3 * k]);
    ASSERT_EQ(hits[k].facet, one.facet) << "point " << k;
    EXPECT_EQ(hits[k].gap, one.gap);
    EXPECT_EQ(hits[k].xi[0], one.xi[0]);
    EXPECT_EQ(hits[k].xi[1], one.xi[1]);
    found += one.facet >= 0;
    outside += y[3 * k] < -0.1 || y[3 * k] > 1.1;
  }
  EXPECT_GT(found, 1000);   // about a quarter lie within the margin over the surface
  EXPECT_GT(outside, 100);  // some points lie outside the grid
}

// Hysteresis (§5 step 2): the current facet is kept while its CPP is inside up to hyst.
TEST(FacetGrid, KeepsCurrentFacetWithinHysteresis) {
  std::vector<std::array<int, 3>> facets;
  std::vector<double> x;
  bumpy(4, facets, x, 0.0);  // flat: the CPP on the neighbour is exactly 1e-5 outside
  emc::contact::FacetGrid grid(facets, x, 0.05);
  const double y[3] = {0.25 + 1e-5, 0.1, 0.01};  // just across the edge x = 0.25
  const auto h0 = grid.locate(y);
  ASSERT_GE(h0.facet, 0);
  // a neighbour whose CPP is only slightly outside stays current with hyst 1e-3
  int other = -1;
  for (int f = 0; f < static_cast<int>(facets.size()); ++f)
    if (f != h0.facet) {
      const auto h = grid.locate(y, f, 1e-3);
      if (h.facet == f) {
        other = f;
        break;
      }
    }
  EXPECT_GE(other, 0);
  // without hysteresis the neighbour is left for the facet that contains the point
  if (other >= 0) EXPECT_EQ(grid.locate(y, other, 0.0).facet, h0.facet);
}

namespace {

/// A copy of host data in a View on the execution space (n rows of 3).
template <class T>
Kokkos::View<T* [3], emc::ExecSpace> to_view(const T* data, std::size_t n) {
  Kokkos::View<T* [3], emc::ExecSpace> v("test::rows", n);
  Kokkos::deep_copy(
      v, Kokkos::View<const T* [3], Kokkos::HostSpace, Kokkos::MemoryUnmanaged>(data, n));
  return v;
}

/// The facets renumbered on the nodes they use (local contact-node indices) and those nodes.
void local_nodes(const std::vector<std::array<int, 3>>& facets, const std::vector<double>& x,
                 std::vector<std::array<int, 3>>& lf, std::vector<double>& lx) {
  std::vector<int> local(x.size() / 3, -1);
  lf = facets;
  for (auto& f : lf)
    for (int& n : f) {
      if (local[n] < 0) {
        local[n] = static_cast<int>(lx.size() / 3);
        lx.insert(lx.end(), {x[3 * n], x[3 * n + 1], x[3 * n + 2]});
      }
      n = local[n];
    }
}

/// In a parallel_for over the points k: locate(y_k), locate(y_k, current, 1e-3) and a
/// summary of for_each_candidate (count, a sum over the candidates in their order, and the
/// last facet id, or 1e9 if the ids did not increase).
void grid_queries(const emc::contact::FacetGrid& grid, Kokkos::View<double* [3], emc::ExecSpace> y,
                  Kokkos::View<emc::contact::Hit* [2], emc::ExecSpace> hits,
                  Kokkos::View<double* [3], emc::ExecSpace> cand) {
  const emc::contact::FacetGrid g = grid;
  Kokkos::parallel_for(
      "test::grid_queries", Kokkos::RangePolicy<emc::ExecSpace>(0, y.extent(0)),
      KOKKOS_LAMBDA(const int k) {
        const double p[3] = {y(k, 0), y(k, 1), y(k, 2)};
        hits(k, 0) = g.locate(p);
        hits(k, 1) = g.locate(p, k % 7 == 0 ? -1 : (37 * k) % g.num_facets(), 1e-3);
        double count = 0, sum = 0, last = -1;
        g.for_each_candidate(p, [&](const emc::contact::Hit& h, double out) {
          count += 1;
          sum += h.gap * (h.facet + 1) + out + g.metric(h.facet).f.n[2];
          last = h.facet > last ? h.facet : 1e9;
        });
        cand(k, 0) = count;
        cand(k, 1) = sum;
        cand(k, 2) = last;
      });
}

}  // namespace

// Bit for bit the brute-force rule with a current facet and hysteresis (§5 step 2): kept,
// left for a valid neighbour, or the least-outside candidate; also with a far current facet.
TEST(FacetGrid, MatchesBruteForceWithCurrentFacet) {
  std::vector<std::array<int, 3>> facets;
  std::vector<double> x;
  bumpy(40, facets, x);
  for (const double margin : {0.05, 0.01}) {  // about 50 and 700 cells
    emc::contact::FacetGrid grid(facets, x, margin);
    const auto y = near_points(3000, 7, -0.05, 1.05, 0.06);
    std::mt19937 rng(8);
    std::uniform_int_distribution<int> pick(0, static_cast<int>(facets.size()) - 1);
    const double hysts[4] = {0.0, 1e-3, 0.05, 0.5};
    for (int t = 0; t < 3000; ++t) {
      const int current = t % 3 == 0 ? -1 : (t % 3 == 1 ? grid.locate(&y[3 * t]).facet : pick(rng));
      const double hyst = hysts[t % 4];
      expect_same(grid.locate(&y[3 * t], current, hyst),
                  brute_force(&y[3 * t], facets, x, margin, grid.tie(), current, hyst), t);
    }
  }
}

// The queries inside a Kokkos parallel_for give the bits of a plain host loop (a test per
// contact kernel): locate with and without a current facet, and for_each_candidate.
TEST(FacetGrid, QueriesInKernelMatchHostLoop) {
  std::vector<std::array<int, 3>> facets;
  std::vector<double> x;
  bumpy(40, facets, x);
  const emc::contact::FacetGrid grid(facets, x, 0.05);
  const auto yh = near_points(5000, 9, -0.1, 1.1, 0.08);
  const int n = static_cast<int>(yh.size() / 3);
  const auto y = to_view(yh.data(), n);
  Kokkos::View<emc::contact::Hit* [2], emc::ExecSpace> hits("test::hits", n);
  Kokkos::View<double* [3], emc::ExecSpace> cand("test::candidates", n);
  grid_queries(grid, y, hits, cand);
  const auto hh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), hits);
  const auto ch = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), cand);
  int with_candidates = 0;
  for (int k = 0; k < n; ++k) {
    const double* p = &yh[3 * k];
    expect_same(hh(k, 0), grid.locate(p), k);
    expect_same(hh(k, 1), grid.locate(p, k % 7 == 0 ? -1 : (37 * k) % grid.num_facets(), 1e-3), k);
    double count = 0, sum = 0;
    grid.for_each_candidate(p, [&](const emc::contact::Hit& h, double out) {
      count += 1;
      sum += h.gap * (h.facet + 1) + out + grid.metric(h.facet).f.n[2];
    });
    EXPECT_EQ(ch(k, 0), count);
    EXPECT_EQ(ch(k, 1), sum);
    EXPECT_LT(ch(k, 2), 1e9);
    with_candidates += count > 0;
  }
  EXPECT_GT(with_candidates, 1000);
}

// The parallel batch query on Views gives every point its own locate()'s bits.
TEST(FacetGrid, BatchOnViewsMatchesSingleQueries) {
  std::vector<std::array<int, 3>> facets;
  std::vector<double> x;
  bumpy(40, facets, x);
  const emc::contact::FacetGrid grid(facets, x, 0.05);
  const auto yh = near_points(5000, 11, -0.2, 1.2, 0.1);
  const int n = static_cast<int>(yh.size() / 3);
  Kokkos::View<emc::contact::Hit*, emc::ExecSpace> hits("test::hits", n);
  grid.locate_all(to_view(yh.data(), n), hits);
  const auto hh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), hits);
  for (int k = 0; k < n; ++k) expect_same(hh(k), grid.locate(&yh[3 * k]), k);
}

// The parallel build is deterministic: from Views on local node indices or from host
// containers, the same cells in the same order; every list sorted by facet id, its unused lanes
// last; every facet in exactly the cells its box overlaps, with its box quantized in the cell;
// every facet's reach box (the reach lists) in its grown box and so in fewer cells.
TEST(FacetGrid, BuildIsDeterministicAndListsSorted) {
  std::vector<std::array<int, 3>> facets, lf;
  std::vector<double> x, lx;
  bumpy(40, facets, x);
  local_nodes(facets, x, lf, lx);
  const emc::contact::FacetGrid a(facets, x, 0.05);
  const emc::contact::FacetGrid b(to_view(lf.front().data(), lf.size()),
                                  to_view(lx.data(), lx.size() / 3), 0.05);
  ASSERT_EQ(a.num_cells(), b.num_cells());
  EXPECT_EQ(a.tie(), b.tie());
  const auto& g = a.shape();
  const int W = emc::contact::CellBlock::W;
  // per facet: its cells, and its quantized box in each (cell -> lo, hi)
  using Quanta = std::map<std::size_t, std::array<int, 6>>;
  auto lists = [&](const emc::contact::CellLists& la, const emc::contact::CellLists& lb) {
    const auto sa = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), la.start);
    const auto sb = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), lb.start);
    const auto ea = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), la.blocks);
    const auto eb = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), lb.blocks);
    EXPECT_EQ(sa.extent(0), a.num_cells() + 1);
    EXPECT_EQ(ea.extent(0), eb.extent(0));
    EXPECT_EQ(la.entries, lb.entries);
    std::vector<Quanta> of(facets.size());
    std::size_t entries = 0;
    for (std::size_t c = 0; c < a.num_cells(); ++c) {
      EXPECT_EQ(sa(c), sb(c));
      int last = -1;
      for (int e = W * sa(c); e < W * sa(c + 1); ++e) {
        const auto& ba = ea(e / W);
        const auto& bb = eb(e / W);
        const int j = e % W, f = ba.facet[j];
        EXPECT_EQ(f, bb.facet[j]);
        for (int i = 0; i < 3; ++i) {
          EXPECT_EQ(ba.lo[i][j], bb.lo[i][j]);
          EXPECT_EQ(ba.hi[i][j], bb.hi[i][j]);
        }
        if (f < 0) {  // unused: last, in the cell's last block only, never holding a point
          EXPECT_GE(e, W * (sa(c + 1) - 1)) << "cell " << c;
          last = int(facets.size());
          for (int i = 0; i < 3; ++i) {
            EXPECT_EQ(ba.lo[i][j], 0x7FFF);
            EXPECT_EQ(ba.hi[i][j], 0);
          }
          continue;
        }
        EXPECT_LT(last, f) << "cell " << c;
        last = f;
        ++entries;
        of[f][c] = {ba.lo[0][j], ba.lo[1][j], ba.lo[2][j], ba.hi[0][j], ba.hi[1][j], ba.hi[2][j]};
      }
      if (sa(c + 1) > sa(c)) EXPECT_NE(ea(sa(c)).facet[0], -1) << "empty block, cell " << c;
    }
    EXPECT_EQ(entries, la.entries);
    return of;
  };
  const auto boxes = lists(a.box_lists(), b.box_lists());
  const auto reach = lists(a.reach_lists(), b.reach_lists());
  std::size_t fewer = 0;
  for (std::size_t f = 0; f < facets.size(); ++f) {  // the cells its grown box overlaps
    double lo[3], hi[3];
    int n = 1;
    for (int i = 0; i < 3; ++i) {
      lo[i] = 1e300;
      hi[i] = -1e300;
      for (int p = 0; p < 3; ++p) {
        lo[i] = std::min(lo[i], x[3 * facets[f][p] + i]);
        hi[i] = std::max(hi[i], x[3 * facets[f][p] + i]);
      }
      lo[i] -= 0.05;
      hi[i] += 0.05;
      n *= g.clamp_index(hi[i], i) - g.clamp_index(lo[i], i) + 1;
    }
    EXPECT_EQ(int(boxes[f].size()), n) << "facet " << f;
    for (const auto& [c, q] : boxes[f]) {
      const int d[3] = {int(c % g.dims[0]), int(c / g.dims[0] % g.dims[1]),
                        int(c / g.dims[0] / g.dims[1])};
      for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(q[i], g.quantum(lo[i], i, d[i]));
        EXPECT_EQ(q[3 + i], g.quantum(hi[i], i, d[i]));
      }
    }
    EXPECT_LE(reach[f].size(), boxes[f].size());
    fewer += reach[f].size() < boxes[f].size();
    for (const auto& [c, q] : reach[f]) {  // within the grown box, in the same cells
      ASSERT_EQ(boxes[f].count(c), 1u) << "facet " << f << " cell " << c;
      const auto& qb = boxes[f].at(c);
      for (int i = 0; i < 3; ++i) {
        EXPECT_GE(q[i], qb[i]);
        EXPECT_LE(q[3 + i], qb[3 + i]);
        EXPECT_LE(q[i], q[3 + i]);
      }
    }
  }
  EXPECT_GT(fewer, facets.size() / 4);  // the reach boxes are smaller
  const auto y = near_points(2000, 13, -0.1, 1.1, 0.08);
  for (int t = 0; t < 2000; ++t) expect_same(a.locate(&y[3 * t]), b.locate(&y[3 * t]), t);
}

namespace {

/// A sphere of radius r about c, nt x 2nt latitude-longitude quads cut in two (the poles'
/// triangles repeat a node: degenerate facets): every orientation of the normal.
void sphere(int nt, double r, const double c[3], std::vector<std::array<int, 3>>& facets,
            std::vector<double>& x) {
  const double pi = std::acos(-1.0);
  const int np = 2 * nt;
  for (int j = 0; j <= nt; ++j)
    for (int i = 0; i < np; ++i) {
      const double th = pi * j / nt, ph = 2 * pi * i / np;
      x.insert(x.end(), {c[0] + r * std::sin(th) * std::cos(ph),
                         c[1] + r * std::sin(th) * std::sin(ph), c[2] + r * std::cos(th)});
    }
  auto id = [np](int i, int j) { return j * np + i % np; };
  for (int j = 0; j < nt; ++j)
    for (int i = 0; i < np; ++i) {
      facets.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      facets.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
}

}  // namespace

// Facets of every orientation (the reach boxes bound the CPP's region along each axis from
// the normal): without a current facet, the brute-force bits near a sphere, with margins
// small and large against the facets, at random points and at the facets' nodes (ties); the
// batch query gives the same bits, also at random points of the whole grid.
TEST(FacetGrid, AnyOrientationMatchesBruteForce) {
  std::vector<std::array<int, 3>> facets;
  std::vector<double> x;
  const double c[3] = {0.5, 0.4, 0.3};
  sphere(24, 0.5, c, facets, x);
  std::mt19937 rng(19);
  std::normal_distribution<double> dn(0, 1);
  std::uniform_real_distribution<double> du(-0.2, 1.2);
  for (const double margin : {0.01, 0.06}) {
    const emc::contact::FacetGrid grid(facets, x, margin);
    std::vector<double> y;
    for (int t = 0; t < 3000; ++t) {
      double p[3];
      if (t % 5 == 0) {  // a node, moved along its radius: on edges of several facets
        const int v = static_cast<int>(rng() % (x.size() / 3));
        const double s = 1 + margin * (t % 3 - 1.0);
        for (int i = 0; i < 3; ++i) p[i] = c[i] + s * (x[3 * v + i] - c[i]);
      } else {
        double u[3] = {dn(rng), dn(rng), dn(rng)};
        const double nu = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        const double rr = 0.5 + 1.2 * margin * (2.0 * (rng() % 1001) / 1000 - 1);
        for (int i = 0; i < 3; ++i) p[i] = c[i] + rr * u[i] / nu;
      }
      y.insert(y.end(), {p[0], p[1], p[2]});
    }
    int found = 0;
    for (int t = 0; t < 3000; ++t) {
      const auto a = grid.locate(&y[3 * t]);
      expect_same(a, brute_force(&y[3 * t], facets, x, margin, grid.tie()), t);
      found += a.facet >= 0;
    }
    EXPECT_GT(found, 2000);
    for (int t = 0; t < 3000; ++t) y.insert(y.end(), {du(rng), du(rng), du(rng)});
    const int n = static_cast<int>(y.size() / 3);
    Kokkos::View<emc::contact::Hit*, emc::ExecSpace> hits("test::hits", n);
    grid.locate_all(to_view(y.data(), n), hits);
    const auto hh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), hits);
    for (int t = 0; t < n; ++t) expect_same(hh(t), grid.locate(&y[3 * t]), t);
  }
}

// Slivers (angles far below the float test's limit) and degenerate facets (collinear or
// repeated nodes) among regular ones: still the brute-force bits (the exact CPP decides).
TEST(FacetGrid, DistortedFacetsMatchBruteForce) {
  std::vector<std::array<int, 3>> facets;
  std::vector<double> x;
  bumpy(8, facets, x);
  auto node = [&x](double a, double b, double c) {
    x.insert(x.end(), {a, b, c});
    return static_cast<int>(x.size() / 3 - 1);
  };
  for (int k = 0; k < 8; ++k) {
    const double o = 0.1 * k;
    facets.push_back(
        {node(o, 0.5, 0.02), node(o + 0.3, 0.5, 0.02), node(o + 0.15, 0.5 + 1e-7, 0.02)});
    facets.push_back({node(o, 0.3, 0.0), node(o + 0.1, 0.3, 0.0), node(o + 0.2, 0.3, 0.0)});
    const int r = node(o, 0.7, 0.01);
    facets.push_back({r, r, node(o + 0.1, 0.75, 0.01)});
  }
  const double margin = 0.05;
  const emc::contact::FacetGrid grid(facets, x, margin);
  const auto y = near_points(4000, 17, 0.0, 1.0, 0.05);
  int found = 0;
  for (int t = 0; t < 4000; ++t) {
    const double* p = &y[3 * t];
    const int current = t % 2 ? -1 : static_cast<int>(facets.size()) - 1 - t % 24;
    const auto a = grid.locate(p, current, 1e-3);
    expect_same(a, brute_force(p, facets, x, margin, grid.tie(), current, 1e-3), t);
    expect_same(grid.locate(p), brute_force(p, facets, x, margin, grid.tie()), t);
    found += a.facet >= 128;
  }
  EXPECT_GT(found, 10);  // some land on the slivers
}

// No facets, no points: nothing found, nothing to do.
TEST(FacetGrid, EmptyGridAndEmptyBatch) {
  const emc::contact::FacetGrid empty(std::vector<std::array<int, 3>>{}, std::vector<double>{},
                                      0.1);
  const double y[3] = {0, 0, 0};
  EXPECT_EQ(empty.locate(y).facet, -1);
  EXPECT_EQ(empty.locate(y, -1, 0.5).facet, -1);
  std::vector<emc::contact::Hit> hits;
  empty.locate_all(y, 1, hits);
  ASSERT_EQ(hits.size(), 1u);
  EXPECT_EQ(hits[0].facet, -1);
  std::vector<std::array<int, 3>> facets;
  std::vector<double> x;
  bumpy(4, facets, x);
  const emc::contact::FacetGrid grid(facets, x, 0.05);
  grid.locate_all(nullptr, 0, hits);
  EXPECT_TRUE(hits.empty());
}
