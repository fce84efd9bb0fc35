#pragma once
// Contact search (ALGORITHM.md §2): a uniform grid of the master facets' bounding boxes
// (expanded by a margin), rebuilt from the current positions whenever it is needed, and the
// projection of a point on the closest valid facet among the candidates of its cell.
// Everything lives in Views on the node's device (built with labelled parallel kernels); the
// queries are device functions, so a FacetGrid copied by value into a kernel can be queried
// there, one thread per slave node (issue 15: ArborX-style search in Views).
#include <Kokkos_Core.hpp>
#include <array>
#include <vector>

#include "emcontact/types.hpp"
#include "kernels/facet.hpp"

namespace emc::contact {

struct Hit {
  int facet = -1;
  double xi[2] = {0, 0};
  double gap = 0;
  bool inside = false;  ///< CPP inside the facet (up to the tolerance asked)
};

/// One entry of a cell's list: the facet's grown box relative to the grid's origin, rounded
/// outwards to float (a test that never rejects a point the exact box holds), and the facet id.
struct CellEntry {
  float lo[3], hi[3];
  int facet, pad;
};

/// The grid's geometry: origin, cell size and cells per direction.
struct GridShape {
  double lo[3] = {1e300, 1e300, 1e300};
  double h = 1;
  int dims[3] = {1, 1, 1};

  /// The cell holding y (its indices in d), or -1 outside the grid.
  KOKKOS_INLINE_FUNCTION int cell_of(const double y[3], int d[3]) const {
    for (int i = 0; i < 3; ++i) {
      const double t = (y[i] - lo[i]) / h;
      if (!(t >= 0 && t < dims[i])) return -1;
      d[i] = static_cast<int>(t);  // t >= 0: the floor
    }
    return (d[2] * dims[1] + d[1]) * dims[0] + d[0];
  }
  /// The cell index along axis i of coordinate v, clamped to the grid.
  KOKKOS_INLINE_FUNCTION int clamp_index(double v, int i) const {
    const double t = (v - lo[i]) / h;
    return t < 1 ? 0 : (t > dims[i] - 1 ? dims[i] - 1 : static_cast<int>(t));
  }
  std::size_t num_cells() const { return std::size_t(dims[0]) * dims[1] * dims[2]; }
};

class FacetGrid {
 public:
  using FacetsView = Kokkos::View<const int* [3], ExecSpace>;
  using PointsView = Kokkos::View<const double* [3], ExecSpace>;
  /// Per facet, what the CPP's xi needs (one record, read together): the exact grown box
  /// (lo, hi), x_m1, tau_xi, tau_eta, g11, g12, g22, det and |tau_xi x tau_eta|.
  using Records = Kokkos::View<double* [20], Kokkos::LayoutRight, ExecSpace>;
  /// Per facet, what the gap needs besides: x_m2, x_m3 and n.
  using GapRecords = Kokkos::View<double* [9], Kokkos::LayoutRight, ExecSpace>;

  /// Bins the facets (3 indices into x each) with their boxes grown by margin, in parallel.
  /// Only the records are kept: facets and x may go once the grid is built.
  FacetGrid(FacetsView facets, PointsView x, double margin);
  /// The same from host containers (geometry node ids into x, 3 coordinates per node).
  FacetGrid(const std::vector<std::array<int, 3>>& facets, const std::vector<double>& x,
            double margin);

  /// The closest valid facet to y (§2): among the candidates whose CPP lies inside up to
  /// 1e-9, the smallest |g_N|, ties to the lowest facet id. If `current` >= 0 it is kept while
  /// its CPP is inside up to `hyst`. If none is valid and `current` >= 0, the candidate least
  /// outside is returned with inside = (outside <= hyst); otherwise facet = -1.
  KOKKOS_INLINE_FUNCTION Hit locate(const double y[3], int current = -1, double hyst = 0) const {
    const double tol = 1e-9;
    if (current >= 0) {
      Hit h;
      if (cpp(current, y, h) && kernels::facet_outside(h.xi) <= (hyst < tol ? tol : hyst)) {
        h.inside = true;
        return h;
      }
    }
    Hit best, least;
    double least_out = 1e300;
    for_each_box(y, [&](int f) {
      double xi[2];
      if (!project(f, y, xi)) return;
      const double out = kernels::facet_outside(xi);
      if (out <= tol) {  // §2: a valid CPP; the gap only for these
        const double g = gap(f, y, xi);
        if (best.facet < 0 || abs(g) < abs(best.gap) - tie_) set(best, f, xi, g, true);
      }
      if (out < least_out) {  // the gap of the least outside is computed at the end
        least_out = out;
        set(least, f, xi, 0, false);
      }
    });
    if (best.facet >= 0 || current < 0) return best;
    if (least.facet < 0) {  // nothing near: keep the current facet, extrapolated
      cpp(current, y, least);
      least_out = kernels::facet_outside(least.xi);
    } else {
      least.gap = gap(least.facet, y, least.xi);
    }
    least.inside = least_out <= hyst;
    return least;
  }

  /// locate(y_k) for every point: hits(k), the same bits, in a labelled parallel_for over
  /// the points visited in the Morton order of their grid cells (a parallel bin sort), so that
  /// consecutive queries read the same cell lists and facet records, as tree searches sort
  /// their queries (ArborX). For many queries in no particular order.
  void locate_all(PointsView y, Kokkos::View<Hit*, ExecSpace> hits) const;
  /// The same for n points (3 coordinates each) on the host.
  void locate_all(const double* y, std::size_t n, std::vector<Hit>& hits) const;

  /// Calls fn(hit, outside) for every facet whose grown box holds y, with its CPP (hit.gap,
  /// hit.xi) and kernels::facet_outside(hit.xi); degenerate facets are skipped. Facets come in
  /// increasing id order.
  template <class F>
  KOKKOS_INLINE_FUNCTION void for_each_candidate(const double y[3], F&& fn) const {
    for_each_box(y, [&](int f) {
      Hit h;
      if (cpp(f, y, h)) fn(h, kernels::facet_outside(h.xi));
    });
  }

  /// The frame and metric of facet f in the grid's configuration.
  KOKKOS_INLINE_FUNCTION kernels::FacetMetric metric(int f) const {
    kernels::FacetMetric m;
    for (int i = 0; i < 3; ++i) {
      m.f.t1[i] = rec_(f, 9 + i);
      m.f.t2[i] = rec_(f, 12 + i);
      m.f.n[i] = gap_(f, 6 + i);
    }
    m.f.area2 = rec_(f, 19);
    m.g11 = rec_(f, 15);
    m.g12 = rec_(f, 16);
    m.g22 = rec_(f, 17);
    m.det = rec_(f, 18);
    return m;
  }

  /// |g_N| closer than this are ties, broken to the lowest facet id (§2).
  KOKKOS_INLINE_FUNCTION double tie() const { return tie_; }
  std::size_t num_cells() const { return shape_.num_cells(); }
  KOKKOS_INLINE_FUNCTION int num_facets() const { return static_cast<int>(rec_.extent(0)); }
  const GridShape& shape() const { return shape_; }
  /// The cell lists (CSR): cell c holds entries cell_start()(c) .. cell_start()(c + 1) - 1.
  Kokkos::View<const int*, ExecSpace> cell_start() const { return cell_start_; }
  Kokkos::View<const CellEntry*, ExecSpace> cell_entries() const { return entries_; }

 private:
  GridShape shape_;
  double tie_ = 0;  ///< |g_N| closer than this are ties (1e-14 of the mean facet size, §2)
  Kokkos::View<int*, ExecSpace> cell_start_;
  Kokkos::View<CellEntry*, ExecSpace> entries_;
  Records rec_;
  GapRecords gap_;

  KOKKOS_INLINE_FUNCTION static double abs(double v) { return v < 0 ? -v : v; }
  KOKKOS_INLINE_FUNCTION static void set(Hit& h, int f, const double xi[2], double g, bool in) {
    h.facet = f;
    h.xi[0] = xi[0];
    h.xi[1] = xi[1];
    h.gap = g;
    h.inside = in;
  }

  /// Calls fn(f) for every facet whose grown box holds y, in increasing id order: the float
  /// boxes of the cell's list first, then the exact box of the record.
  template <class F>
  KOKKOS_INLINE_FUNCTION void for_each_box(const double y[3], F&& fn) const {
    int d[3];
    const int c = shape_.cell_of(y, d);
    if (c < 0) return;
    float yf[3];  // relative to the origin, as the float boxes
    for (int i = 0; i < 3; ++i) yf[i] = static_cast<float>(y[i] - shape_.lo[i]);
    const int end = cell_start_(c + 1);
    for (int k = cell_start_(c); k < end; ++k) {
      const CellEntry& e = entries_(k);
      // rounding is monotone: yf < lo (float, rounded down) implies y < lo: no point is lost
      if (yf[0] < e.lo[0] || yf[0] > e.hi[0] || yf[1] < e.lo[1] || yf[1] > e.hi[1] ||
          yf[2] < e.lo[2] || yf[2] > e.hi[2])
        continue;
      const int f = e.facet;
      if (y[0] < rec_(f, 0) || y[0] > rec_(f, 3) || y[1] < rec_(f, 1) || y[1] > rec_(f, 4) ||
          y[2] < rec_(f, 2) || y[2] > rec_(f, 5))
        continue;
      fn(f);
    }
  }

  /// The xi of kernels::facet_cpp (the same operations, so the same bits); false if the
  /// facet is degenerate.
  KOKKOS_INLINE_FUNCTION bool project(int f, const double y[3], double xi[2]) const {
    const double det = rec_(f, 18);
    if (!(det > 0)) return false;
    double b1 = 0, b2 = 0;
    for (int i = 0; i < 3; ++i) {
      const double d = y[i] - rec_(f, 6 + i);
      b1 += rec_(f, 9 + i) * d;
      b2 += rec_(f, 12 + i) * d;
    }
    xi[0] = (rec_(f, 17) * b1 - rec_(f, 16) * b2) / det;
    xi[1] = (rec_(f, 15) * b2 - rec_(f, 16) * b1) / det;
    return true;
  }
  /// The gap of kernels::facet_cpp at xi (the same operations, so the same bits).
  KOKKOS_INLINE_FUNCTION double gap(int f, const double y[3], const double xi[2]) const {
    double N[3];
    kernels::facet_shape(xi, N);
    double g = 0;
    for (int i = 0; i < 3; ++i)
      g += (y[i] - N[0] * rec_(f, 6 + i) - N[1] * gap_(f, i) - N[2] * gap_(f, 3 + i)) *
           gap_(f, 6 + i);
    return g;
  }
  KOKKOS_INLINE_FUNCTION bool cpp(int f, const double y[3], Hit& h) const {
    h.facet = f;
    if (!project(f, y, h.xi)) return false;
    h.gap = gap(f, y, h.xi);
    return true;
  }
};

}  // namespace emc::contact
