#pragma once
// The sparsity pattern of P1 tetrahedra (docs/THEORY.md §1.4: the element matrices couple the 12
// dofs of a tet) as a CRS matrix in a memory space, built by parallel kernels: dof 3 n + c of
// node n, row 3 n + c holding the columns 3 m + d of every node m that shares a tet with n (n
// included), sorted. The arrays are those of KokkosSparse::CrsMatrix (row_map, entries,
// values), in Views of the library's own so that nothing but Kokkos is needed.
#include <Kokkos_Core.hpp>

#include "kernels/types.hpp"

namespace emc::kernels {

/// A square CRS matrix (rows row_map(r) .. row_map(r + 1) - 1 of entries and values).
template <class MemorySpace>
struct CrsMatrix {
  Kokkos::View<int*, MemorySpace> row_map;    ///< num_rows + 1 offsets
  Kokkos::View<int*, MemorySpace> entries;    ///< column indices, sorted in each row
  Kokkos::View<double*, MemorySpace> values;  ///< one per entry
  int num_rows() const { return row_map.extent(0) ? static_cast<int>(row_map.extent(0)) - 1 : 0; }
};

/// The pattern of a tet mesh and where each tet's entries lie: row 3 n_a + c holds the columns
/// 3 n_b .. 3 n_b + 2 of tet k's nodes a, b at values row_map(3 n_a + c) + block(k, a, b) + d
/// (d = 0, 1, 2), so that an element matrix is added without searching a row.
template <class MemorySpace>
struct TetPattern {
  CrsMatrix<MemorySpace> matrix;
  Kokkos::View<int* [4][4], Kokkos::LayoutRight, MemorySpace> block;

  TetPattern() = default;
  /// The pattern of the tets (node ids below num_nodes) with zero values, built on space: the
  /// node neighbours of every node gathered with atomics, then sorted per node (so the result
  /// never depends on the threads), then expanded to 3 x 3 dof blocks.
  template <class ExecutionSpace>
  TetPattern(const ExecutionSpace& space, const Tetrahedra<MemorySpace>& tets, int num_nodes);
};

namespace crs_detail {

/// Sorts v(first) .. v(last - 1) (a short list: insertion sort) and removes repeats; returns
/// how many distinct values remain at the front.
template <class V>
KOKKOS_INLINE_FUNCTION int sort_unique(const V& v, int first, int last) {
  for (int k = first + 1; k < last; ++k) {
    const int x = v(k);
    int j = k;
    for (; j > first && v(j - 1) > x; --j) v(j) = v(j - 1);
    v(j) = x;
  }
  int n = 0;
  for (int k = first; k < last; ++k)
    if (n == 0 || v(first + n - 1) != v(k)) v(first + n++) = v(k);
  return n;
}

/// Exclusive sum of count(0 .. n - 1) into start(0 .. n), returned total.
template <class ExecutionSpace, class Count, class Start>
int exclusive_sum(const ExecutionSpace& space, const char* label, const Count& count,
                  const Start& start, int n) {
  int total = 0;
  Kokkos::parallel_scan(
      label, range(space, n),
      KOKKOS_LAMBDA(const int i, int& sum, const bool final) {
        if (final) start(i) = sum;
        sum += count(i);
        if (final && i == n - 1) start(n) = sum;
      },
      total);
  if (n == 0) Kokkos::deep_copy(space, start, 0);
  return total;
}

}  // namespace crs_detail

namespace crs_detail {

/// The pattern's arrays (a free function: a device lambda is never in a constructor).
template <class ExecutionSpace, class MemorySpace>
void build(const ExecutionSpace& space, const Tetrahedra<MemorySpace>& tets, int num_nodes,
           CrsMatrix<MemorySpace>& A,
           Kokkos::View<int* [4][4], Kokkos::LayoutRight, MemorySpace>& block) {
  using Ints = Kokkos::View<int*, MemorySpace>;
  const int ne = static_cast<int>(tets.extent(0)), nn = num_nodes;
  Ints slots("emc::tet_pattern_slots", nn), start("emc::tet_pattern_start", nn + 1);
  Kokkos::parallel_for(
      "emcontact::fem::tet_pattern_count", range(space, ne), KOKKOS_LAMBDA(const int k) {
        for (int a = 0; a < 4; ++a) Kokkos::atomic_add(&slots(tets(k, a)), 4);
      });
  const int total = exclusive_sum(space, "emcontact::fem::tet_pattern_scan", slots, start, nn);
  Ints next("emc::tet_pattern_next", nn);
  Ints ids(Kokkos::ViewAllocateWithoutInitializing("emc::tet_pattern_ids"), total);
  Kokkos::parallel_for(
      "emcontact::fem::tet_pattern_fill", range(space, ne), KOKKOS_LAMBDA(const int k) {
        for (int a = 0; a < 4; ++a) {
          const int n = tets(k, a), at = start(n) + Kokkos::atomic_fetch_add(&next(n), 4);
          for (int b = 0; b < 4; ++b) ids(at + b) = tets(k, b);
        }
      });
  Ints degree(Kokkos::ViewAllocateWithoutInitializing("emc::tet_pattern_degree"), nn);
  Kokkos::parallel_for(
      "emcontact::fem::tet_pattern_sort", range(space, nn),
      KOKKOS_LAMBDA(const int n) { degree(n) = sort_unique(ids, start(n), start(n + 1)); });
  Ints first(Kokkos::ViewAllocateWithoutInitializing("emc::tet_pattern_first"), nn + 1);
  const int pairs = exclusive_sum(space, "emcontact::fem::tet_pattern_offsets", degree, first, nn);
  A.row_map = Ints(Kokkos::ViewAllocateWithoutInitializing("emc::crs_row_map"), 3 * nn + 1);
  A.entries = Ints(Kokkos::ViewAllocateWithoutInitializing("emc::crs_entries"), 9 * pairs);
  A.values = Kokkos::View<double*, MemorySpace>("emc::crs_values", 9 * pairs);
  const auto row_map = A.row_map, entries = A.entries;
  Kokkos::parallel_for(
      "emcontact::fem::tet_pattern_rows", range(space, nn), KOKKOS_LAMBDA(const int n) {
        const int deg = degree(n);
        for (int c = 0; c < 3; ++c) {
          const int row = 9 * first(n) + 3 * c * deg;
          row_map(3 * n + c) = row;
          for (int t = 0; t < deg; ++t)
            for (int e = 0; e < 3; ++e) entries(row + 3 * t + e) = 3 * ids(start(n) + t) + e;
        }
        if (n == nn - 1) row_map(3 * nn) = 9 * first(nn);
      });
  if (nn == 0) Kokkos::deep_copy(space, A.row_map, 0);
  block = Kokkos::View<int* [4][4], Kokkos::LayoutRight, MemorySpace>(
      Kokkos::ViewAllocateWithoutInitializing("emc::tet_pattern_block"), ne);
  const auto blk = block;
  Kokkos::parallel_for(
      "emcontact::fem::tet_pattern_blocks", range(space, ne), KOKKOS_LAMBDA(const int k) {
        for (int a = 0; a < 4; ++a) {
          const int n = tets(k, a);
          for (int b = 0; b < 4; ++b) {  // bisect n's sorted neighbours for tets(k, b)
            int lo = start(n), hi = start(n) + degree(n) - 1;
            const int m = tets(k, b);
            while (lo < hi) {
              const int mid = (lo + hi) / 2;
              if (ids(mid) < m)
                lo = mid + 1;
              else
                hi = mid;
            }
            blk(k, a, b) = 3 * (lo - start(n));
          }
        }
      });
}

}  // namespace crs_detail

template <class MemorySpace>
template <class ExecutionSpace>
TetPattern<MemorySpace>::TetPattern(const ExecutionSpace& space,
                                    const Tetrahedra<MemorySpace>& tets, int num_nodes) {
  check_access<ExecutionSpace, MemorySpace>();
  crs_detail::build(space, tets, num_nodes, matrix, block);
}

/// values(at(k)) += c * from(k) for every k: entries of one matrix added into another's values at
/// their positions there (each at its own position: no two adds meet), in a loop labelled label.
template <class ExecutionSpace, class Values, class At, class From>
void add_at(const ExecutionSpace& space, const char* label, const Values& values, const At& at,
            double c, const From& from) {
  Kokkos::parallel_for(
      label, range(space, from.extent(0)),
      KOKKOS_LAMBDA(const int k) { values(at(k)) += c * from(k); });
}

/// out(at(k)) = from(k) for every k (at: distinct positions), in a loop labelled label.
template <class ExecutionSpace, class Out, class At, class From>
void set_at(const ExecutionSpace& space, const char* label, const Out& out, const At& at,
            const From& from) {
  Kokkos::parallel_for(
      label, range(space, from.extent(0)), KOKKOS_LAMBDA(const int k) { out(at(k)) = from(k); });
}

}  // namespace emc::kernels
