#include "emcontact/contact/search.hpp"

#include <Kokkos_Sort.hpp>
#include <algorithm>
#include <cmath>

#include "kernels/facet.hpp"

namespace emc::contact {

namespace {

using Policy = Kokkos::RangePolicy<ExecSpace>;

/// Per facet f (docs/THEORY.md §2.3, §2.5): its grown box and what the CPP needs, computed once per
/// grid with kernels::facet_metric, so that the queries give kernels::facet_cpp's bits.
void fill_records(FacetGrid::FacetsView facets, FacetGrid::PointsView x, double margin,
                  FacetGrid::Records rec, FacetGrid::Boxes box) {
  using G = FacetGrid;
  Kokkos::parallel_for(
      "emcontact::contact::grid_records", Policy(0, facets.extent(0)), KOKKOS_LAMBDA(const int f) {
        double xm[3][3];
        for (int a = 0; a < 3; ++a)
          for (int i = 0; i < 3; ++i) xm[a][i] = x(facets(f, a), i);
        const kernels::FacetMetric m = kernels::facet_metric(xm);
        for (int i = 0; i < 3; ++i) {
          const double lo = xm[0][i] < xm[1][i] ? xm[0][i] : xm[1][i];
          const double hi = xm[0][i] < xm[1][i] ? xm[1][i] : xm[0][i];
          box(f, i) = (lo < xm[2][i] ? lo : xm[2][i]) - margin;
          box(f, 3 + i) = (hi < xm[2][i] ? xm[2][i] : hi) + margin;
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
void fill_prisms(const GridShape& s, FacetGrid::Records rec,
                 Kokkos::View<Prism*, ExecSpace> prism) {
  using G = FacetGrid;
  Kokkos::parallel_for(
      "emcontact::contact::grid_prisms", Policy(0, rec.extent(0)), KOKKOS_LAMBDA(const int f) {
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

struct BoundsReduce {
  using value_type = Bounds;
  FacetGrid::Boxes box;
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
  KOKKOS_INLINE_FUNCTION void join(volatile Bounds& a, const volatile Bounds& b) const {
    for (int i = 0; i < 3; ++i) {
      a.lo[i] = b.lo[i] < a.lo[i] ? b.lo[i] : a.lo[i];
      a.hi[i] = b.hi[i] > a.hi[i] ? b.hi[i] : a.hi[i];
    }
    a.ext += b.ext;
  }
};

Bounds bounds(FacetGrid::Boxes box, double margin) {
  Bounds b;
  Kokkos::parallel_reduce("emcontact::contact::grid_bounds", Policy(0, box.extent(0)),
                          BoundsReduce{box, margin}, b);
  return b;
}

/// Calls fn(c) for every cell that facet f's grown box overlaps.
template <class F>
KOKKOS_INLINE_FUNCTION void for_each_cell(const GridShape& s, FacetGrid::Boxes box, int f, F&& fn) {
  int a[3], b[3];
  for (int i = 0; i < 3; ++i) {
    a[i] = s.clamp_index(box(f, i), i);
    b[i] = s.clamp_index(box(f, 3 + i), i);
  }
  for (int k = a[2]; k <= b[2]; ++k)
    for (int j = a[1]; j <= b[1]; ++j)
      for (int i = a[0]; i <= b[0]; ++i) fn((k * s.dims[1] + j) * s.dims[0] + i);
}

/// How many facets every cell holds, in start(c + 1).
void count_cells(const GridShape& s, FacetGrid::Boxes box, Kokkos::View<int*, ExecSpace> start) {
  Kokkos::parallel_for(
      "emcontact::contact::grid_count", Policy(0, box.extent(0)), KOKKOS_LAMBDA(const int f) {
        for_each_cell(s, box, f, [&](int c) { Kokkos::atomic_increment(&start(c + 1)); });
      });
}

/// start(c) = the sum of the counts of the cells before c; returns the total.
int scan_cells(Kokkos::View<int*, ExecSpace> start) {
  int total = 0;
  Kokkos::parallel_scan(
      "emcontact::contact::grid_scan", Policy(0, start.extent(0)),
      KOKKOS_LAMBDA(const int c, int& sum, const bool final) {
        sum += start(c);
        if (final) start(c) = sum;
      },
      total);
  return total;
}

/// Every cell's facets in increasing id order: in any order with atomics, then sorted (the
/// lists are short); the order of the candidates, hence ties, never depends on the threads.
void fill_cells(const GridShape& s, FacetGrid::Boxes box,
                Kokkos::View<const Prism*, ExecSpace> prism,
                Kokkos::View<const int*, ExecSpace> start,
                Kokkos::View<CellEntry*, ExecSpace> entries) {
  Kokkos::View<int*, ExecSpace> next("emc::grid_next", start.extent(0) - 1);
  Kokkos::View<int*, ExecSpace> ids(Kokkos::ViewAllocateWithoutInitializing("emc::grid_ids"),
                                    entries.extent(0));
  Kokkos::parallel_for(
      "emcontact::contact::grid_fill", Policy(0, box.extent(0)), KOKKOS_LAMBDA(const int f) {
        for_each_cell(s, box, f,
                      [&](int c) { ids(start(c) + Kokkos::atomic_fetch_add(&next(c), 1)) = f; });
      });
  Kokkos::parallel_for(
      "emcontact::contact::grid_sort", Policy(0, next.extent(0)), KOKKOS_LAMBDA(const int c) {
        for (int k = start(c) + 1; k < start(c + 1); ++k) {  // insertion sort
          const int f = ids(k);
          int j = k;
          for (; j > start(c) && ids(j - 1) > f; --j) ids(j) = ids(j - 1);
          ids(j) = f;
        }
        const int d[3] = {c % s.dims[0], c / s.dims[0] % s.dims[1], c / s.dims[0] / s.dims[1]};
        for (int k = start(c); k < start(c + 1); ++k) {  // the entries, written in order
          const int f = ids(k);
          CellEntry e;
          e.facet = f;
          e.prism = prism(f);
          for (int i = 0; i < 3; ++i) {
            e.lo[i] = s.quantum(box(f, i), i, d[i]);
            e.hi[i] = s.quantum(box(f, 3 + i), i, d[i]);
          }
          entries(k) = e;
        }
      });
}

}  // namespace

// docs/THEORY.md §2.5: the grid of the grown boxes, built in parallel.
FacetGrid::FacetGrid(FacetsView facets, PointsView x, double margin)
    : rec_(Kokkos::ViewAllocateWithoutInitializing("emc::grid_records"), facets.extent(0)),
      box_(Kokkos::ViewAllocateWithoutInitializing("emc::grid_boxes"), facets.extent(0)) {
  const int nf = static_cast<int>(facets.extent(0));
  fill_records(facets, x, margin, rec_, box_);
  const Bounds b = bounds(box_, margin);
  // ties: 1e-14 of the mean grown box (its extent + 2 margin), or of 1/128 of the grid
  double h = nf ? std::max(b.ext / (3.0 * nf), 1e-12) + 2 * margin : 1.0;
  for (int i = 0; i < 3; ++i) h = std::max(h, (b.hi[i] - b.lo[i]) / 128.0);
  tie_ = 1e-14 * h;
  // cells twice that: a third of the entries of cells of size h, a 3x faster build, and the
  // same query speed (perf/README.md, BM_ContactGridBuild and BM_ContactQueries)
  h *= 2;
  shape_.h = h;
  shape_.inv_h = 1 / h;
  shape_.q_scale = 16384 / h;
  for (int i = 0; i < 3; ++i) {
    shape_.lo[i] = b.lo[i];
    // + 1: the cell of the highest box bound lies inside the grid (at most 65 per direction)
    shape_.dims[i] = nf ? int(std::floor((b.hi[i] - b.lo[i]) * shape_.inv_h)) + 1 : 1;
  }
  const GridShape s = shape_;
  Kokkos::View<Prism*, ExecSpace> prism(Kokkos::ViewAllocateWithoutInitializing("emc::grid_prisms"),
                                        nf);
  fill_prisms(s, rec_, prism);
  cell_start_ = Kokkos::View<int*, ExecSpace>("emc::grid_start", s.num_cells() + 1);
  count_cells(s, box_, cell_start_);
  const int total = scan_cells(cell_start_);
  entries_ = Kokkos::View<CellEntry*, ExecSpace>(
      Kokkos::ViewAllocateWithoutInitializing("emc::grid_entries"), total);
  fill_cells(s, box_, prism, cell_start_, entries_);
}

FacetGrid::FacetGrid(const std::vector<std::array<int, 3>>& facets, const std::vector<double>& x,
                     double margin)
    : FacetGrid(Kokkos::create_mirror_view_and_copy(
                    ExecSpace::memory_space(),
                    Kokkos::View<const int* [3], Kokkos::HostSpace, Kokkos::MemoryUnmanaged>(
                        facets.empty() ? nullptr : facets.front().data(), facets.size())),
                Kokkos::create_mirror_view_and_copy(
                    ExecSpace::memory_space(),
                    Kokkos::View<const double* [3], Kokkos::HostSpace, Kokkos::MemoryUnmanaged>(
                        x.data(), x.size() / 3)),
                margin) {
  static_assert(sizeof(std::array<int, 3>) == 3 * sizeof(int));
}

}  // namespace emc::contact

namespace emc::contact {

namespace {

/// Bit b of v (< 2^10: at most 65 cells per direction) to bit 3b.
KOKKOS_INLINE_FUNCTION unsigned spread(unsigned v) {
  unsigned r = 0;
  for (int b = 0; b < 10; ++b) r |= ((v >> b) & 1u) << (3 * b);
  return r;
}

/// The Morton code of the cell of every point, points outside the grid after all cells.
Kokkos::View<int*, ExecSpace> morton_keys(const GridShape& s, FacetGrid::PointsView y,
                                          int outside) {
  Kokkos::View<int*, ExecSpace> key(Kokkos::ViewAllocateWithoutInitializing("emc::grid_keys"),
                                    y.extent(0));
  Kokkos::parallel_for(
      "emcontact::contact::grid_query_keys", Policy(0, y.extent(0)), KOKKOS_LAMBDA(const int k) {
        const double p[3] = {y(k, 0), y(k, 1), y(k, 2)};
        int d[3];
        key(k) = s.cell_of(p, d) < 0 ? outside
                                     : int(spread(d[0]) | spread(d[1]) << 1 | spread(d[2]) << 2);
      });
  return key;
}

}  // namespace

// docs/THEORY.md §2.5 for every point (locate), visited in an order that reuses the cache.
void FacetGrid::locate_all(PointsView y, Kokkos::View<Hit*, ExecSpace> hits) const {
  const int n = static_cast<int>(y.extent(0));
  const GridShape& s = shape_;
  const int outside =
      int(spread(s.dims[0] - 1) | spread(s.dims[1] - 1) << 1 | spread(s.dims[2] - 1) << 2) + 1;
  const auto key = morton_keys(s, y, outside);
  // about 4 points per bin: the order inside a bin does not matter
  using Op = Kokkos::BinOp1D<Kokkos::View<int*, ExecSpace>>;
  Kokkos::BinSort<Kokkos::View<int*, ExecSpace>, Op> sort(key, Op(std::max(1, n / 4), 0, outside));
  sort.create_permute_vector();
  const auto order = sort.get_permute_vector();
  const FacetGrid grid = *this;  // by value: never capture `this` in a device lambda
  // the points in that order first: independent loads, not the head of each query's chain
  Kokkos::View<double* [3], ExecSpace> ys(Kokkos::ViewAllocateWithoutInitializing("emc::grid_ys"),
                                          n);
  Kokkos::View<Hit*, ExecSpace> hs(Kokkos::ViewAllocateWithoutInitializing("emc::grid_hs"), n);
  Kokkos::parallel_for(
      "emcontact::contact::grid_gather", Policy(0, n), KOKKOS_LAMBDA(const int t) {
        for (int i = 0; i < 3; ++i) ys(t, i) = y(order(t), i);
      });
  Kokkos::parallel_for(
      "emcontact::contact::grid_locate_all", Policy(0, n), KOKKOS_LAMBDA(const int t) {
        const double p[3] = {ys(t, 0), ys(t, 1), ys(t, 2)};
        hs(t) = grid.locate(p);
      });
  Kokkos::parallel_for(
      "emcontact::contact::grid_scatter", Policy(0, n),
      KOKKOS_LAMBDA(const int t) { hits(order(t)) = hs(t); });
}

void FacetGrid::locate_all(const double* y, std::size_t n, std::vector<Hit>& hits) const {
  hits.assign(n, Hit{});
  const auto yd = Kokkos::create_mirror_view_and_copy(
      ExecSpace::memory_space(),
      Kokkos::View<const double* [3], Kokkos::HostSpace, Kokkos::MemoryUnmanaged>(y, n));
  Kokkos::View<Hit*, Kokkos::HostSpace, Kokkos::MemoryUnmanaged> hh(hits.data(), n);
  auto hd = Kokkos::create_mirror_view(ExecSpace::memory_space(), hh);
  locate_all(yd, hd);
  Kokkos::deep_copy(hh, hd);
}

}  // namespace emc::contact
