#pragma once
// Contact search (docs/THEORY.md §2.5): a uniform grid of the master facets' bounding boxes
// (expanded by a margin), rebuilt from the current positions whenever it is needed, and the
// projection of a point on the closest valid facet among the candidates of its cell.
// Everything lives in Views of a memory space (built with labelled parallel kernels); the
// queries are device functions, so a FacetGrid copied by value into a kernel can be queried
// there, one thread per query point. The build is in kernels/search_build.hpp.
#include <Kokkos_Core.hpp>
#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

#include "kernels/facet.hpp"
#include "kernels/math.hpp"
#include "kernels/types.hpp"

namespace emc::kernels {

struct Hit {
  int facet = -1;
  double xi[2] = {0, 0};
  double gap = 0;
  bool inside = false;  ///< CPP inside the facet (up to the tolerance asked)
};

/// Per facet, a cheap test that a point's CPP lies outside it (32 bytes): the dual basis
/// a1, a2 of (tau_xi, tau_eta) and c_k = a_k . (x_m1 - origin), in float, so that
/// xi ~ a1 . (y - origin) - c1 and eta ~ a2 . (y - origin) - c2. A facet too distorted for
/// float bounds gets a = 0, c = -1/2: its estimate (1/2, 1/2) always passes.
struct Prism {
  float a1[3], a2[3], c1, c2;
};

/// Eight entries of a cell's list (128 bytes, two cache lines), lane by lane: facet ids and
/// boxes quantized in the cell by GridShape::quantum, a monotone map (a point's quantum below
/// lo or above hi is outside the box, strictly between them inside; only equal quanta need the
/// exact box). A query tests its quanta against the eight boxes at once, in a loop the compiler
/// vectorizes. Unused lanes: lo = 0x7FFF, hi = 0 (no quantum lies between), facet -1.
struct CellBlock {
  enum { W = 8 };
  short lo[3][W], hi[3][W];  // quanta < 2^15
  int facet[W];
};

/// Cell lists (CSR): cell c holds blocks start(c) .. start(c + 1) - 1, its facets in
/// increasing id order, lane by lane, the unused lanes last.
template <class MemorySpace>
struct CellLists {
  Kokkos::View<int*, MemorySpace> start;
  Kokkos::View<CellBlock*, MemorySpace> blocks;
  std::size_t entries = 0;  ///< the used lanes
};

/// The grid's geometry: origin, cell size and cells per direction.
struct GridShape {
  double lo[3] = {1e300, 1e300, 1e300};
  double h = 1;
  double inv_h = 1;        ///< 1 / h: cells and quanta by products (the same in build and queries)
  double q_scale = 16384;  ///< 2^14 / h
  int dims[3] = {1, 1, 1};

  /// The cell holding y (its indices in d), or -1 outside the grid.
  KOKKOS_INLINE_FUNCTION int cell_of(const double y[3], int d[3]) const {
    for (int i = 0; i < 3; ++i) {
      const double t = (y[i] - lo[i]) * inv_h;
      if (!(t >= 0 && t < dims[i])) return -1;
      d[i] = static_cast<int>(t);  // t >= 0: the floor
    }
    return (d[2] * dims[1] + d[1]) * dims[0] + d[0];
  }
  /// The cell index along axis i of coordinate v, clamped to the grid.
  KOKKOS_INLINE_FUNCTION int clamp_index(double v, int i) const {
    const double t = (v - lo[i]) * inv_h;
    return t < 1 ? 0 : (t > dims[i] - 1 ? dims[i] - 1 : static_cast<int>(t));
  }
  /// The quantum of coordinate v along axis i in cell index d: about (v - corner) / h * 2^14,
  /// clamped to [0, 2^14 + 2] (< 2^15: a guard bit per 16-bit lane); built only of rounded
  /// monotone operations, so that it never decreases with v (the same bits in the build and
  /// the queries).
  KOKKOS_INLINE_FUNCTION unsigned short quantum(double v, int i, int d) const {
    double t = (v - (lo[i] + d * h)) * q_scale + 1;
    t = t < 0 ? 0 : (t > 16386 ? 16386 : t);
    return static_cast<unsigned short>(t);  // t >= 0: truncation
  }
  std::size_t num_cells() const { return std::size_t(dims[0]) * dims[1] * dims[2]; }
};

/// The grid of a triangulated surface's facets in MemorySpace (docs/THEORY.md §2.5), ArborX
/// style: built by the kernels of an execution space instance, queried one point at a time in
/// any kernel that can read MemorySpace (a FacetGrid copied by value into it: Views only) or for
/// many points by locate_all. The constructors and locate_all without a space run on
/// MemorySpace's default execution space.
template <class MemorySpace>
class FacetGrid {
  static_assert(Kokkos::is_memory_space<MemorySpace>::value, "FacetGrid<a Kokkos memory space>");

 public:
  using memory_space = MemorySpace;
  using FacetsView = Triangles<MemorySpace>;
  using PointsView = Points<MemorySpace>;
  using HitsView = Kokkos::View<Hit*, MemorySpace>;
  /// Per facet, what the CPP needs, in three cache lines read together: x_m1, tau_xi,
  /// tau_eta, g11, g12, g22, det, n, x_m2, x_m3 and |tau_xi x tau_eta| (offsets below).
  using Records = Kokkos::View<double* [24], Kokkos::LayoutRight, MemorySpace>;
  enum { X1 = 0, T1 = 3, T2 = 6, G11 = 9, G12 = 10, G22 = 11, DET = 12, NRM = 13, X2 = 16 };
  enum { X3 = 19, AREA = 22 };
  /// Per facet, its exact grown box (lo, hi), read only when the quantized box cannot decide.
  using Boxes = Kokkos::View<double* [6], Kokkos::LayoutRight, MemorySpace>;

  /// Bins the facets (3 indices into x each) with their boxes grown by margin, in parallel on
  /// space. Only the records are kept: facets and x may go once the grid is built. With `from`
  /// (the positions at the start of a step), each box holds the facet at x and at `from`: the
  /// grid of the facets' sweeps (for_each_on_segment), its records at x.
  template <class ExecutionSpace>
  FacetGrid(const ExecutionSpace& space, const FacetsView& facets, const PointsView& x,
            double margin, const PointsView& from = PointsView());
  FacetGrid(const FacetsView& facets, const PointsView& x, double margin,
            const PointsView& from = PointsView())
      : FacetGrid(DefaultExecutionSpace<MemorySpace>(), facets, x, margin, from) {}
  /// The same from host containers (geometry node ids into x, 3 coordinates per node).
  template <class ExecutionSpace>
  FacetGrid(const ExecutionSpace& space, const std::vector<std::array<int, 3>>& facets,
            const std::vector<double>& x, double margin);
  FacetGrid(const std::vector<std::array<int, 3>>& facets, const std::vector<double>& x,
            double margin)
      : FacetGrid(DefaultExecutionSpace<MemorySpace>(), facets, x, margin) {}

  /// The closest valid facet to y (§2): among the candidates whose CPP lies inside up to
  /// 1e-9, the smallest |g_N|, ties to the lowest facet id. If `current` >= 0 it is kept while
  /// its CPP is inside up to `hyst`. If none is valid and `current` >= 0, the candidate least
  /// outside is returned with inside = (outside <= hyst); otherwise facet = -1.
  KOKKOS_INLINE_FUNCTION Hit locate(const double y[3], int current = -1, double hyst = 0) const {
    const double tol = 1e-9;
    if (current >= 0) {
      Hit h;
      if (cpp(current, y, h) && facet_outside(h.xi) <= (hyst < tol ? tol : hyst)) {
        h.inside = true;
        return h;
      }
    }
    Hit best, least;
    double least_out = 1e300;
    // without a current facet only valid CPPs count: the others are skipped by the float test
    const bool all = current >= 0;
    for_each_box(y, all, [&](int f) {
      double xi[2];
      if (!project(f, y, xi)) return;
      const double out = facet_outside(xi);
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
      least_out = facet_outside(least.xi);
    } else {
      least.gap = gap(least.facet, y, least.xi);
    }
    least.inside = least_out <= hyst;
    return least;
  }

  /// locate(y_k) for every point: hits(k), the same bits, in a labelled parallel_for over
  /// the points visited cell by cell (a parallel bin sort, a bin per cell), so that
  /// consecutive queries read the same cell lists and facet records, as tree searches sort
  /// their queries (ArborX). For many queries in no particular order.
  template <class ExecutionSpace>
  void locate_all(const ExecutionSpace& space, const PointsView& y, const HitsView& hits) const;
  void locate_all(const PointsView& y, const HitsView& hits) const {
    locate_all(DefaultExecutionSpace<MemorySpace>(), y, hits);
  }
  /// The same for n points (3 coordinates each) on the host.
  template <class ExecutionSpace>
  void locate_all(const ExecutionSpace& space, const double* y, std::size_t n,
                  std::vector<Hit>& hits) const;
  void locate_all(const double* y, std::size_t n, std::vector<Hit>& hits) const {
    locate_all(DefaultExecutionSpace<MemorySpace>(), y, n, hits);
  }

  /// Calls fn(hit, outside) for every facet whose grown box holds y, with its CPP (hit.gap,
  /// hit.xi) and facet_outside(hit.xi); degenerate facets are skipped. Facets come in
  /// increasing id order.
  template <class F>
  KOKKOS_INLINE_FUNCTION void for_each_candidate(const double y[3], F&& fn) const {
    for_each_box(y, true, [&](int f) {
      Hit h;
      if (cpp(f, y, h)) fn(h, facet_outside(h.xi));
    });
  }

  /// Calls fn(f) for every facet whose grown box overlaps a grid cell that the segment from a
  /// to b passes through and meets the segment's box (docs/THEORY.md §6.3, a node crossing a
  /// facet by more than the max penetration: the point where it crosses lies in the facet's
  /// box). The cells are walked along the segment (Amanatides and Woo), at most the sum of the
  /// grid's dimensions, so that the cost does not grow with the segment's length; a facet may
  /// come more than once (from several cells).
  template <class F>
  KOKKOS_INLINE_FUNCTION void for_each_on_segment(const double a[3], const double b[3],
                                                  F&& fn) const {
    double t0 = 0, t1 = 1, d[3], lo[3], hi[3];
    for (int i = 0; i < 3; ++i) {  // the part of the segment in the grid: t0 <= t <= t1
      d[i] = b[i] - a[i];
      lo[i] = a[i] < b[i] ? a[i] : b[i];
      hi[i] = a[i] < b[i] ? b[i] : a[i];
      const double g0 = shape_.lo[i], g1 = shape_.lo[i] + shape_.dims[i] * shape_.h;
      if (d[i] == 0) {
        if (!(a[i] >= g0 && a[i] <= g1)) return;
        continue;
      }
      double ta = (g0 - a[i]) / d[i], tb = (g1 - a[i]) / d[i];
      if (ta > tb) {
        const double t = ta;
        ta = tb;
        tb = t;
      }
      t0 = ta > t0 ? ta : t0;
      t1 = tb < t1 ? tb : t1;
    }
    if (!(t0 <= t1)) return;
    int c[3], step[3];
    double next[3], delta[3];  // the t of the next cell boundary along each axis, and its period
    for (int i = 0; i < 3; ++i) {
      c[i] = shape_.clamp_index(a[i] + t0 * d[i], i);
      step[i] = d[i] > 0 ? 1 : (d[i] < 0 ? -1 : 0);
      next[i] = delta[i] = 1e300;
      if (step[i] == 0) continue;
      next[i] = (shape_.lo[i] + (c[i] + (step[i] > 0)) * shape_.h - a[i]) / d[i];
      delta[i] = shape_.h / kernels::fabs(d[i]);
    }
    const int most = shape_.dims[0] + shape_.dims[1] + shape_.dims[2];
    for (int n = 0; n < most; ++n) {
      const int cell = (c[2] * shape_.dims[1] + c[1]) * shape_.dims[0] + c[0];
      for (int k = boxes_.start(cell); k < boxes_.start(cell + 1); ++k)
        for (int j = 0; j < CellBlock::W; ++j) {
          const int f = boxes_.blocks(k).facet[j];
          if (f >= 0 && !(hi[0] < box_(f, 0) || lo[0] > box_(f, 3) || hi[1] < box_(f, 1) ||
                          lo[1] > box_(f, 4) || hi[2] < box_(f, 2) || lo[2] > box_(f, 5)))
            fn(f);
        }
      const int i = next[0] < next[1] ? (next[0] < next[2] ? 0 : 2) : (next[1] < next[2] ? 1 : 2);
      if (next[i] > t1) return;
      c[i] += step[i];
      if (c[i] < 0 || c[i] >= shape_.dims[i]) return;
      next[i] += delta[i];
    }
  }

  /// Whether some facet's grown box holds y (exactly the facets for_each_candidate visits): a
  /// test before work that only the candidates need.
  KOKKOS_INLINE_FUNCTION bool any_box(const double y[3]) const {
    int d[3];
    const int c = shape_.cell_of(y, d);
    if (c < 0) return false;
    short q[3];
    for (int i = 0; i < 3; ++i) q[i] = static_cast<short>(shape_.quantum(y[i], i, d[i]));
    for (int k = boxes_.start(c); k < boxes_.start(c + 1); ++k) {
      const CellBlock& b = boxes_.blocks(k);
      for (unsigned m = lanes_holding(b, q); m; m &= m - 1) {
        const int j = lowest_set_bit(m);
        if (surely_holds(b, j, q) || in_box(b.facet[j], y)) return true;
      }
    }
    return false;
  }

  /// The frame and metric of facet f in the grid's configuration.
  KOKKOS_INLINE_FUNCTION FacetMetric metric(int f) const {
    FacetMetric m;
    for (int i = 0; i < 3; ++i) {
      m.f.t1[i] = rec_(f, T1 + i);
      m.f.t2[i] = rec_(f, T2 + i);
      m.f.n[i] = rec_(f, NRM + i);
    }
    m.f.area2 = rec_(f, AREA);
    m.g11 = rec_(f, G11);
    m.g12 = rec_(f, G12);
    m.g22 = rec_(f, G22);
    m.det = rec_(f, DET);
    return m;
  }

  /// |g_N| closer than this are ties, broken to the lowest facet id (§2).
  KOKKOS_INLINE_FUNCTION double tie() const { return tie_; }
  std::size_t num_cells() const { return shape_.num_cells(); }
  KOKKOS_INLINE_FUNCTION int num_facets() const { return static_cast<int>(rec_.extent(0)); }
  const GridShape& shape() const { return shape_; }
  /// The cells' lists of the facets whose grown box overlaps them, quantized grown boxes.
  const CellLists<MemorySpace>& box_lists() const { return boxes_; }
  /// The cells' lists of the facets whose reach box overlaps them, quantized reach boxes: the
  /// box of the points of the grown box whose CPP may lie inside the facet (docs/THEORY.md
  /// §2.5), which a locate() without a current facet scans.
  const CellLists<MemorySpace>& reach_lists() const { return reach_; }

 private:
  GridShape shape_;
  double tie_ = 0;  ///< |g_N| closer than this are ties (1e-14 of the mean facet size, §2)
  CellLists<MemorySpace> boxes_, reach_;
  Kokkos::View<Prism*, MemorySpace> prism_;
  Records rec_;
  Boxes box_;

  KOKKOS_INLINE_FUNCTION static double abs(double v) { return v < 0 ? -v : v; }
  KOKKOS_INLINE_FUNCTION static void set(Hit& h, int f, const double xi[2], double g, bool in) {
    h.facet = f;
    h.xi[0] = xi[0];
    h.xi[1] = xi[1];
    h.gap = g;
    h.inside = in;
  }

  /// Whether the CPP of y (yf: y - origin in float) on facet f may lie inside it up to tol:
  /// false only when the float estimate of facet_outside, with a bound of its
  /// round-off (below 8 2^-24 of the sum of the magnitudes summed), is beyond tol.
  KOKKOS_INLINE_FUNCTION static bool maybe_inside(const Prism& p, const float yf[3], double tol) {
    using kernels::fabs;  // no branch (a conditional negation may compile to one)
    float xi = -p.c1, eta = -p.c2;
    float size = 1 + fabs(p.c1) + fabs(p.c2);
    for (int i = 0; i < 3; ++i) {  // yf >= 0 inside the grid
      xi += p.a1[i] * yf[i];
      eta += p.a2[i] * yf[i];
      size += (fabs(p.a1[i]) + fabs(p.a2[i])) * yf[i];
    }
    float out = xi + eta - 1;  // -min(1 - xi - eta, xi, eta)
    out = out > -xi ? out : -xi;
    out = out > -eta ? out : -eta;
    return out <= static_cast<float>(tol) + 1e-5f * size;
  }

  KOKKOS_INLINE_FUNCTION static void prefetch(const void* p) {
#if defined(__GNUC__) && !defined(__CUDA_ARCH__) && !defined(__HIP_DEVICE_COMPILE__)
    __builtin_prefetch(p);
#else
    (void)p;
#endif
  }

  /// Whether the exact grown box of facet f holds y.
  KOKKOS_INLINE_FUNCTION bool in_box(int f, const double y[3]) const {
    return !(y[0] < box_(f, 0) || y[0] > box_(f, 3) || y[1] < box_(f, 1) || y[1] > box_(f, 4) ||
             y[2] < box_(f, 2) || y[2] > box_(f, 5));
  }
  /// The lanes of block b whose quantized box holds the quanta q (bit j for lane j). With quanta
  /// below 2^15, q - lo and hi - q fit in 16 bits, whose sign bits, or-ed over the axes, tell a
  /// lane outside: a loop of 16-bit operations over the lanes, which the compiler vectorizes;
  /// the eight results (bytes 0 or 1) are gathered into the bits of one byte by a product.
  KOKKOS_INLINE_FUNCTION static unsigned lanes_holding(const CellBlock& b, const short q[3]) {
    const short q0 = q[0], q1 = q[1], q2 = q[2];
    unsigned char in[CellBlock::W];
    for (int j = 0; j < CellBlock::W; ++j) {
      const short out =
          static_cast<short>((q0 - b.lo[0][j]) | (b.hi[0][j] - q0) | (q1 - b.lo[1][j]) |
                             (b.hi[1][j] - q1) | (q2 - b.lo[2][j]) | (b.hi[2][j] - q2));
      in[j] = out >= 0;
    }
    static_assert(CellBlock::W == sizeof(std::uint64_t), "one byte per lane in a word");
    std::uint64_t w;
    std::memcpy(&w, in, sizeof w);
    return static_cast<unsigned>((w * 0x0102040810204080ull) >> 56);  // byte j to bit j
  }
  /// Whether the quanta q lie strictly inside lane j's quantized box (then its box holds y).
  KOKKOS_INLINE_FUNCTION static bool surely_holds(const CellBlock& b, int j, const short q[3]) {
    return b.lo[0][j] < q[0] && q[0] < b.hi[0][j] && b.lo[1][j] < q[1] && q[1] < b.hi[1][j] &&
           b.lo[2][j] < q[2] && q[2] < b.hi[2][j];
  }

  /// Calls fn(f) for every facet whose grown box holds y (all) or, if not all, only for
  /// those that are maybe_inside, in increasing id order. Not all scans the reach lists, all
  /// the box lists (a reach box lies in its grown box: strictly inside the first, y is inside
  /// the second; on the boundary of the first, the second decides). The records of the facets
  /// found are prefetched together (batches of at most 32), so that their latencies overlap.
  template <class F>
  KOKKOS_INLINE_FUNCTION void for_each_box(const double y[3], bool all, F&& fn) const {
    int d[3];
    const int c = shape_.cell_of(y, d);
    if (c < 0) return;
    short q[3];
    float yf[3];
    for (int i = 0; i < 3; ++i) {
      q[i] = static_cast<short>(shape_.quantum(y[i], i, d[i]));
      yf[i] = static_cast<float>(y[i] - shape_.lo[i]);
    }
    const CellLists<MemorySpace>& lists = all ? boxes_ : reach_;
    const int end = lists.start(c + 1);
    int found[32], n = 0;
    for (int k = lists.start(c); k < end; ++k) {
      const CellBlock& b = lists.blocks(k);
      for (unsigned m = lanes_holding(b, q); m; m &= m - 1) {
        const int j = lowest_set_bit(m);
        const int f = b.facet[j];
        if (!surely_holds(b, j, q) && !in_box(f, y)) continue;
        prefetch(&rec_(f, 0));  // before the float test: its load and theirs overlap
        prefetch(&rec_(f, 8));
        prefetch(&rec_(f, 16));
        if (!all && !maybe_inside(prism_(f), yf, 1e-9)) continue;
        found[n++] = f;
        if (n == 32) {
          visit(found, n, fn);
          n = 0;
        }
      }
    }
    visit(found, n, fn);
  }
  template <class F>
  KOKKOS_INLINE_FUNCTION static void visit(const int* found, int n, F& fn) {
    for (int j = 0; j < n; ++j) fn(found[j]);
  }

  /// The xi of kernels::facet_cpp (the same operations, so the same bits); false if the
  /// facet is degenerate.
  KOKKOS_INLINE_FUNCTION bool project(int f, const double y[3], double xi[2]) const {
    const double det = rec_(f, DET);
    if (!(det > 0)) return false;
    double b1 = 0, b2 = 0;
    for (int i = 0; i < 3; ++i) {
      const double d = y[i] - rec_(f, X1 + i);
      b1 += rec_(f, T1 + i) * d;
      b2 += rec_(f, T2 + i) * d;
    }
    xi[0] = (rec_(f, G22) * b1 - rec_(f, G12) * b2) / det;
    xi[1] = (rec_(f, G11) * b2 - rec_(f, G12) * b1) / det;
    return true;
  }
  /// The gap of kernels::facet_cpp at xi (the same operations, so the same bits).
  KOKKOS_INLINE_FUNCTION double gap(int f, const double y[3], const double xi[2]) const {
    double N[3];
    facet_shape(xi, N);
    double g = 0;
    for (int i = 0; i < 3; ++i)
      g += (y[i] - N[0] * rec_(f, X1 + i) - N[1] * rec_(f, X2 + i) - N[2] * rec_(f, X3 + i)) *
           rec_(f, NRM + i);
    return g;
  }
  KOKKOS_INLINE_FUNCTION bool cpp(int f, const double y[3], Hit& h) const {
    h.facet = f;
    if (!project(f, y, h.xi)) return false;
    h.gap = gap(f, y, h.xi);
    return true;
  }
};

}  // namespace emc::kernels

#include "kernels/search_build.hpp"
