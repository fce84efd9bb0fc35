// Contact geometry without MPI (ALGORITHM.md §2): the facet CPP is the orthogonal projection,
// and the grid search returns exactly what a brute-force loop over all facets returns.
#include <gtest/gtest.h>

#include <cmath>
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

emc::contact::Hit brute_force(const double y[3], const std::vector<std::array<int, 3>>& facets,
                              const std::vector<double>& x, double margin) {
  emc::contact::Hit best;
  for (int f = 0; f < static_cast<int>(facets.size()); ++f) {
    double xm[3][3], lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < 3; ++i) {
        xm[a][i] = x[3 * facets[f][a] + i];
        lo[i] = std::min(lo[i], xm[a][i] - margin);
        hi[i] = std::max(hi[i], xm[a][i] + margin);
      }
    bool in_box = true;
    for (int i = 0; i < 3; ++i) in_box = in_box && y[i] >= lo[i] && y[i] <= hi[i];
    double xi[2], gap;
    if (!in_box || !k::facet_cpp(y, xm, xi, gap) || k::facet_outside(xi) > 1e-9) continue;
    if (best.facet < 0 || std::fabs(gap) < std::fabs(best.gap) - 1e-14 * 0.01) {
      best.facet = f;
      best.gap = gap;
      best.xi[0] = xi[0];
      best.xi[1] = xi[1];
    }
  }
  return best;
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
  EXPECT_GT(grid.num_cells(), 100u);
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
    const auto b = brute_force(y, facets, x, margin);
    ASSERT_EQ(a.facet, b.facet) << "query " << t;
    if (a.facet >= 0) {
      ++found;
      EXPECT_DOUBLE_EQ(a.gap, b.gap);
    }
  }
  EXPECT_GT(found, 3800);  // a few queries near the outer border project outside every facet
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
  EXPECT_GT(found, 1000);  // about a quarter lie within the margin over the surface
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
