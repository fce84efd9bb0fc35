#pragma once
// The build of kernels/search.hpp's FacetGrid and its batch query (docs/THEORY.md §2.5): labelled
// parallel kernels on the execution space given, free functions whose lambdas capture Views
// only (never `this`). Included by kernels/search.hpp.
#include <Kokkos_Core.hpp>
#include <Kokkos_Sort.hpp>
#include <algorithm>
#include <cmath>

#include "kernels/facet.hpp"
#include "kernels/math.hpp"
#include "kernels/search.hpp"

namespace emc::kernels {
namespace search_detail {

/// Per facet f (docs/THEORY.md §2.3, §2.5): its grown box and what the CPP needs, computed once
/// per grid with facet_metric, so that the queries give facet_cpp's bits. With `from` (not
/// empty), each box also holds the facet at `from`: its sweep over the step.
template <class ExecutionSpace, class MemorySpace>
void fill_records(const ExecutionSpace& space, const Triangles<MemorySpace>& facets,
                  const Points<MemorySpace>& x, double margin, const Points<MemorySpace>& from,
                  const typename FacetGrid<MemorySpace>::Records& rec,
                  const typename FacetGrid<MemorySpace>::Boxes& box) {
  using G = FacetGrid<MemorySpace>;
  const bool swept = from.extent(0) > 0;
  Kokkos::parallel_for(
      "emcontact::contact::grid_records", range(space, facets.extent(0)),
      KOKKOS_LAMBDA(const int f) {
        double xm[3][3];
        for (int a = 0; a < 3; ++a)
          for (int i = 0; i < 3; ++i) xm[a][i] = x(facets(f, a), i);
        const FacetMetric m = facet_metric(xm);
        for (int i = 0; i < 3; ++i) {
          double lo = xm[0][i], hi = xm[0][i];
          for (int a = 0; a < 3; ++a)
            for (int k = 0; k < (swept ? 2 : 1); ++k) {
              const double v = k ? from(facets(f, a), i) : xm[a][i];
              lo = v < lo ? v : lo;
              hi = v > hi ? v : hi;
            }
          box(f, i) = lo - margin;
          box(f, 3 + i) = hi + margin;
          rec(f, G::X1 + i) = xm[0][i];
          rec(f, G::T1 + i) = m.f.t1[i];
          rec(f, G::T2 + i) = m.f.t2[i];
          rec(f, G::NRM + i) = m.f.n[i];
          rec(f, G::X2 + i) = xm[1][i];
          rec(f, G::X3 + i) = xm[2][i];
        }
        rec(f, G::G11) = m.g11;
        rec(f, G::G12) = m.g12;
        rec(f, G::G22) = m.g22;
        rec(f, G::DET) = m.det;
        rec(f, G::AREA) = m.f.area2;
        rec(f, G::AREA + 1) = 0;
      });
}

/// The float test of every facet (Prism): the dual basis a1 = (g22 tau_xi - g12 tau_eta) / det,
/// a2 = (g11 tau_eta - g12 tau_xi) / det; a facet with an angle below about 0.06 degrees
/// (det < 1e-6 g11 g22) or a degenerate one always passes (the exact CPP decides).
template <class ExecutionSpace, class MemorySpace>
void fill_prisms(const ExecutionSpace& space, const GridShape& s,
                 const typename FacetGrid<MemorySpace>::Records& rec,
                 const Kokkos::View<Prism*, MemorySpace>& prism) {
  using G = FacetGrid<MemorySpace>;
  Kokkos::parallel_for(
      "emcontact::contact::grid_prisms", range(space, rec.extent(0)), KOKKOS_LAMBDA(const int f) {
        const double g11 = rec(f, G::G11), g12 = rec(f, G::G12), g22 = rec(f, G::G22);
        const double det = rec(f, G::DET);
        const bool exact = !(det >= 1e-6 * g11 * g22 && det > 0);
        double c1 = 0, c2 = 0;
        for (int i = 0; i < 3; ++i) {
          const double a1 = exact ? 0 : (g22 * rec(f, G::T1 + i) - g12 * rec(f, G::T2 + i)) / det;
          const double a2 = exact ? 0 : (g11 * rec(f, G::T2 + i) - g12 * rec(f, G::T1 + i)) / det;
          c1 += a1 * (rec(f, G::X1 + i) - s.lo[i]);
          c2 += a2 * (rec(f, G::X1 + i) - s.lo[i]);
          prism(f).a1[i] = static_cast<float>(a1);
          prism(f).a2[i] = static_cast<float>(a2);
        }
        prism(f).c1 = exact ? -0.5f : static_cast<float>(c1);
        prism(f).c2 = exact ? -0.5f : static_cast<float>(c2);
      });
}

/// The bounds of all grown boxes and the sum of the facets' extents (3 per facet).
struct Bounds {
  double lo[3], hi[3], ext;
};

/// The reduction of Bounds: min, max, and the sum of the extents (a sum: its bits depend on the
/// order of the threads' partial sums, hence so may the grid's cell size and tie tolerance).
template <class Boxes>
struct BoundsReduce {
  using value_type = Bounds;
  Boxes box;
  double margin;
  KOKKOS_INLINE_FUNCTION void operator()(const int f, Bounds& b) const {
    for (int i = 0; i < 3; ++i) {
      b.ext += box(f, 3 + i) - box(f, i) - 2 * margin;
      b.lo[i] = box(f, i) < b.lo[i] ? box(f, i) : b.lo[i];
      b.hi[i] = box(f, 3 + i) > b.hi[i] ? box(f, 3 + i) : b.hi[i];
    }
  }
  KOKKOS_INLINE_FUNCTION void init(Bounds& b) const {
    for (int i = 0; i < 3; ++i) {
      b.lo[i] = 1e300;
      b.hi[i] = -1e300;
    }
    b.ext = 0;
  }
  EMC_KERNELS_REDUCER_JOIN(Bounds)
  template <class A, class B>
  KOKKOS_INLINE_FUNCTION static void join_into(A& a, const B& b) {
    for (int i = 0; i < 3; ++i) {
      a.lo[i] = b.lo[i] < a.lo[i] ? b.lo[i] : a.lo[i];
      a.hi[i] = b.hi[i] > a.hi[i] ? b.hi[i] : a.hi[i];
    }
    a.ext += b.ext;
  }
};

template <class ExecutionSpace, class Boxes>
Bounds bounds(const ExecutionSpace& space, const Boxes& box, double margin) {
  Bounds b;
  Kokkos::parallel_reduce("emcontact::contact::grid_bounds", range(space, box.extent(0)),
                          BoundsReduce<Boxes>{box, margin}, b);
  return b;
}

/// Per facet, its reach box (docs/THEORY.md §2.5): a box holding every point y of its grown box
/// whose CPP c may be valid (inside the facet up to the tolerance), so that only the facets
/// whose reach box holds y need the float test and the exact CPP when no facet is current.
/// With y = c + g n (n the unit normal) and k the axis of the largest |n_k|,
/// |g n_k| = |y_k - c_k| <= e_k + margin (e the facet's extents: y_k in the grown box, c_k in
/// the facet's box), so that along every axis y_i lies within |n_i / n_k| (e_k + margin) of the
/// facet's box. A slack of 1e-6 of the facet's size covers the round-off of n and the
/// tolerance on xi (1e-9); the box is clipped to the grown box, in which it then lies. A
/// degenerate facet (never valid) gets an empty box (lo > hi), one whose float test is not
/// trusted (Prism a = 0: slivers) its grown box.
template <class ExecutionSpace, class MemorySpace>
void fill_reach(const ExecutionSpace& space, const typename FacetGrid<MemorySpace>::Records& rec,
                const typename FacetGrid<MemorySpace>::Boxes& box,
                const Kokkos::View<const Prism*, MemorySpace>& prism, double margin,
                const typename FacetGrid<MemorySpace>::Boxes& reach) {
  using G = FacetGrid<MemorySpace>;
  Kokkos::parallel_for(
      "emcontact::contact::grid_reach", range(space, rec.extent(0)), KOKKOS_LAMBDA(const int f) {
        if (!(rec(f, G::DET) > 0)) {
          for (int i = 0; i < 3; ++i) {
            reach(f, i) = 1;
            reach(f, 3 + i) = -1;
          }
          return;
        }
        const bool trusted = prism(f).c1 != -0.5f || prism(f).a1[0] != 0 || prism(f).a1[1] != 0 ||
                             prism(f).a1[2] != 0;
        int k = 0;
        double size = 0;
        for (int i = 0; i < 3; ++i) {
          if (fabs(rec(f, G::NRM + i)) > fabs(rec(f, G::NRM + k))) k = i;
          const double e = box(f, 3 + i) - box(f, i);
          size = e > size ? e : size;
        }
        const double nk = fabs(rec(f, G::NRM + k));
        const double ek = box(f, 3 + k) - box(f, k) - 2 * margin;
        for (int i = 0; i < 3; ++i) {
          const double r = fabs(rec(f, G::NRM + i)) / nk * (ek + margin) + 1e-6 * size;
          const double lo = box(f, i) + margin - r, hi = box(f, 3 + i) - margin + r;
          reach(f, i) = !trusted || lo < box(f, i) ? box(f, i) : lo;
          reach(f, 3 + i) = !trusted || hi > box(f, 3 + i) ? box(f, 3 + i) : hi;
        }
      });
}

/// Calls fn(c) for every cell that box f overlaps (none if the box is empty).
template <class Boxes, class F>
KOKKOS_INLINE_FUNCTION void for_each_cell(const GridShape& s, const Boxes& box, int f, F&& fn) {
  if (box(f, 0) > box(f, 3)) return;
  int a[3], b[3];
  for (int i = 0; i < 3; ++i) {
    a[i] = s.clamp_index(box(f, i), i);
    b[i] = s.clamp_index(box(f, 3 + i), i);
  }
  for (int k = a[2]; k <= b[2]; ++k)
    for (int j = a[1]; j <= b[1]; ++j)
      for (int i = a[0]; i <= b[0]; ++i) fn((k * s.dims[1] + j) * s.dims[0] + i);
}

/// The cell lists of the boxes: every cell's facets in increasing id order, in any order with
/// atomics, then sorted (the lists are short), so that the order of the candidates, hence
/// ties, never depends on the threads; then their quantized boxes, lane by lane.
template <class ExecutionSpace, class MemorySpace>
CellLists<MemorySpace> cell_lists(const ExecutionSpace& space, const GridShape& s,
                                  const typename FacetGrid<MemorySpace>::Boxes& box) {
  constexpr int W = CellBlock::W;
  const int cells = static_cast<int>(s.num_cells());
  Kokkos::View<int*, MemorySpace> count("emc::grid_count", cells);
  Kokkos::parallel_for(
      "emcontact::contact::grid_count", range(space, box.extent(0)), KOKKOS_LAMBDA(const int f) {
        for_each_cell(s, box, f, [&](int c) { Kokkos::atomic_add(&count(c), 1); });
      });
  CellLists<MemorySpace> l;
  l.start = Kokkos::View<int*, MemorySpace>(
      Kokkos::ViewAllocateWithoutInitializing("emc::grid_start"), cells + 1);
  const auto start = l.start;
  int blocks = 0;  // start(c): the blocks of the cells before c
  Kokkos::parallel_scan(
      "emcontact::contact::grid_scan", range(space, cells),
      KOKKOS_LAMBDA(const int c, int& sum, const bool final) {
        if (final) start(c) = sum;
        sum += (count(c) + W - 1) / W;
        if (final && c == cells - 1) start(cells) = sum;
      },
      blocks);
  l.blocks = Kokkos::View<CellBlock*, MemorySpace>(
      Kokkos::ViewAllocateWithoutInitializing("emc::grid_blocks"), blocks);
  const auto out = l.blocks;
  Kokkos::View<int*, MemorySpace> next("emc::grid_next", cells);
  Kokkos::View<int*, MemorySpace> ids(Kokkos::ViewAllocateWithoutInitializing("emc::grid_ids"),
                                      W * std::size_t(blocks));
  Kokkos::parallel_for(
      "emcontact::contact::grid_fill", range(space, box.extent(0)), KOKKOS_LAMBDA(const int f) {
        for_each_cell(s, box, f, [&](int c) {
          ids(W * start(c) + Kokkos::atomic_fetch_add(&next(c), 1)) = f;
        });
      });
  int entries = 0;
  Kokkos::parallel_reduce(
      "emcontact::contact::grid_sort", range(space, cells),
      KOKKOS_LAMBDA(const int c, int& sum) {
        const int first = W * start(c), last = first + count(c);
        sum += count(c);
        for (int k = first + 1; k < last; ++k) {  // insertion sort
          const int f = ids(k);
          int j = k;
          for (; j > first && ids(j - 1) > f; --j) ids(j) = ids(j - 1);
          ids(j) = f;
        }
        const int d[3] = {c % s.dims[0], c / s.dims[0] % s.dims[1], c / s.dims[0] / s.dims[1]};
        for (int b = start(c); b < start(c + 1); ++b) {  // the blocks, lane by lane
          CellBlock& e = out(b);
          for (int j = 0; j < W; ++j) {
            const int k = W * b + j, f = k < last ? ids(k) : -1;
            e.facet[j] = f;
            for (int i = 0; i < 3; ++i) {
              e.lo[i][j] = f < 0 ? short(0x7FFF) : short(s.quantum(box(f, i), i, d[i]));
              e.hi[i][j] = f < 0 ? short(0) : short(s.quantum(box(f, 3 + i), i, d[i]));
            }
          }
        }
      },
      entries);
  l.entries = static_cast<std::size_t>(entries);
  return l;
}

/// Every point's key: its cell's rank in the visiting order of the cells, points outside the
/// grid last. The cells are visited along the axis with the fewest cells first, then the next
/// (so that, for a surface, the cells of a column across it come together), like the rows of
/// an array.
template <class ExecutionSpace, class MemorySpace>
Scratch<int*, ExecutionSpace, MemorySpace> cell_keys(const ExecutionSpace& space,
                                                     const GridShape& s,
                                                     const Points<MemorySpace>& y) {
  Scratch<int*, ExecutionSpace, MemorySpace> key(
      Kokkos::ViewAllocateWithoutInitializing("emc::grid_keys"), y.extent(0));
  int a[3] = {0, 1, 2};  // the axes, fewest cells first (ties: lower axis first)
  std::stable_sort(a, a + 3, [&s](int i, int j) { return s.dims[i] < s.dims[j]; });
  const int a0 = a[0], a1 = a[1], a2 = a[2], outside = static_cast<int>(s.num_cells());
  Kokkos::parallel_for(
      "emcontact::contact::grid_query_keys", range(space, y.extent(0)), KOKKOS_LAMBDA(const int k) {
        const double p[3] = {y(k, 0), y(k, 1), y(k, 2)};
        int d[3];
        key(k) = s.cell_of(p, d) < 0 ? outside : (d[a2] * s.dims[a1] + d[a1]) * s.dims[a0] + d[a0];
      });
  return key;
}

}  // namespace search_detail

// docs/THEORY.md §2.5: the grid of the grown boxes, built in parallel.
template <class MemorySpace>
template <class ExecutionSpace>
FacetGrid<MemorySpace>::FacetGrid(const ExecutionSpace& space, const FacetsView& facets,
                                  const PointsView& x, double margin, const PointsView& from)
    : rec_(Kokkos::ViewAllocateWithoutInitializing("emc::grid_records"), facets.extent(0)),
      box_(Kokkos::ViewAllocateWithoutInitializing("emc::grid_boxes"), facets.extent(0)) {
  check_access<ExecutionSpace, MemorySpace>();
  namespace d = search_detail;
  const int nf = static_cast<int>(facets.extent(0));
  d::fill_records(space, facets, x, margin, from, rec_, box_);
  const d::Bounds b = d::bounds(space, box_, margin);
  // ties: 1e-14 of the mean grown box (its extent + 2 margin), or of 1/128 of the grid
  double h = nf ? std::max(b.ext / (3.0 * nf), 1e-12) + 2 * margin : 1.0;
  for (int i = 0; i < 3; ++i) h = std::max(h, (b.hi[i] - b.lo[i]) / 128.0);
  tie_ = 1e-14 * h;
  // cells 1.5 times that: more queries per second in locate_all than cells of twice that (fewer
  // blocks per query) for a slower build, and than cells of h in random order one by one
  // (perf/README.md "Constants of the code, measured")
  h *= 1.5;
  shape_.h = h;
  shape_.inv_h = 1 / h;
  shape_.q_scale = 16384 / h;
  for (int i = 0; i < 3; ++i) {
    shape_.lo[i] = b.lo[i];
    // + 1: the cell of the highest box bound lies inside the grid (at most 86 per direction)
    shape_.dims[i] = nf ? int(std::floor((b.hi[i] - b.lo[i]) * shape_.inv_h)) + 1 : 1;
  }
  const GridShape s = shape_;
  prism_ = Kokkos::View<Prism*, MemorySpace>(
      Kokkos::ViewAllocateWithoutInitializing("emc::grid_prisms"), nf);
  d::fill_prisms(space, s, rec_, prism_);
  Boxes reach(Kokkos::ViewAllocateWithoutInitializing("emc::grid_reach"), nf);
  d::fill_reach<ExecutionSpace, MemorySpace>(space, rec_, box_, prism_, margin, reach);
  boxes_ = d::cell_lists<ExecutionSpace, MemorySpace>(space, s, box_);
  reach_ = d::cell_lists<ExecutionSpace, MemorySpace>(space, s, reach);
}

template <class MemorySpace>
template <class ExecutionSpace>
FacetGrid<MemorySpace>::FacetGrid(const ExecutionSpace& space,
                                  const std::vector<std::array<int, 3>>& facets,
                                  const std::vector<double>& x, double margin)
    : FacetGrid(
          space,
          Kokkos::create_mirror_view_and_copy(
              MemorySpace(), Kokkos::View<const int* [3], Kokkos::LayoutRight, Kokkos::HostSpace,
                                          Kokkos::MemoryUnmanaged>(
                                 facets.empty() ? nullptr : facets.front().data(), facets.size())),
          Kokkos::create_mirror_view_and_copy(
              MemorySpace(), Kokkos::View<const double* [3], Kokkos::LayoutRight, Kokkos::HostSpace,
                                          Kokkos::MemoryUnmanaged>(x.data(), x.size() / 3)),
          margin) {
  static_assert(sizeof(std::array<int, 3>) == 3 * sizeof(int));
}

// docs/THEORY.md §2.5 for every point (locate), visited cell by cell so that consecutive
// queries read the same cell lists and facet records (as tree searches sort their queries).
template <class MemorySpace>
template <class ExecutionSpace>
void FacetGrid<MemorySpace>::locate_all(const ExecutionSpace& space, const PointsView& y,
                                        const HitsView& hits) const {
  check_access<ExecutionSpace, MemorySpace>();
  using Keys = Scratch<int*, ExecutionSpace, MemorySpace>;
  const int n = static_cast<int>(y.extent(0));
  const int cells = static_cast<int>(shape_.num_cells());
  const Keys key = search_detail::cell_keys(space, shape_, y);
  // a bin per cell (and one for the points outside): a cell's points together, in any order;
  // Kokkos::BinSort runs on ExecutionSpace's default instance (Kokkos 3.4 takes none)
  using Op = Kokkos::BinOp1D<Keys>;
  space.fence();
  Kokkos::BinSort<Keys, Op> sort(key, Op(cells + 1, 0, cells));
  sort.create_permute_vector();
  ExecutionSpace().fence();
  const auto order = sort.get_permute_vector();
  const FacetGrid grid = *this;  // by value: never capture `this` in a device lambda
  // the points in that order first, the hits in order, then in place: sequential loads and
  // stores in the queries (faster than reading and writing through order there: perf/README.md
  // "Constants of the code, measured")
  Kokkos::View<double* [3], Kokkos::LayoutRight, MemorySpace> ys(
      Kokkos::ViewAllocateWithoutInitializing("emc::grid_ys"), n);
  HitsView hs(Kokkos::ViewAllocateWithoutInitializing("emc::grid_hs"), n);
  Kokkos::parallel_for(
      "emcontact::contact::grid_gather", range(space, n), KOKKOS_LAMBDA(const int t) {
        for (int i = 0; i < 3; ++i) ys(t, i) = y(order(t), i);
      });
  Kokkos::parallel_for(
      "emcontact::contact::grid_locate_all", range(space, n), KOKKOS_LAMBDA(const int t) {
        const double p[3] = {ys(t, 0), ys(t, 1), ys(t, 2)};
        hs(t) = grid.locate(p);
      });
  Kokkos::parallel_for(
      "emcontact::contact::grid_scatter", range(space, n),
      KOKKOS_LAMBDA(const int t) { hits(order(t)) = hs(t); });
}

template <class MemorySpace>
template <class ExecutionSpace>
void FacetGrid<MemorySpace>::locate_all(const ExecutionSpace& space, const double* y, std::size_t n,
                                        std::vector<Hit>& hits) const {
  hits.assign(n, Hit{});
  const auto yd = Kokkos::create_mirror_view_and_copy(
      MemorySpace(), Kokkos::View<const double* [3], Kokkos::LayoutRight, Kokkos::HostSpace,
                                  Kokkos::MemoryUnmanaged>(y, n));
  Kokkos::View<Hit*, Kokkos::HostSpace, Kokkos::MemoryUnmanaged> hh(hits.data(), n);
  auto hd = Kokkos::create_mirror_view(MemorySpace(), hh);
  locate_all(space, yd, hd);
  space.fence();
  Kokkos::deep_copy(hh, hd);
}

}  // namespace emc::kernels
