// docs/THEORY.md §3.1: P is the identity except in the constrained rows. It is written as local
// CRS arrays by loops over the owned rows (rows, then entries), so that its cost does not grow
// with the rank's rows on one thread; the special rows, one per active slave dof, are
// flattened on the host first.
#include "emcontact/linalg/p_matrix.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <algorithm>
#include <string>
#include <utility>

#include "emcontact/error.hpp"

namespace emc::linalg {

namespace {

using Teuchos::RCP;
using Teuchos::rcp;
using RowPtrs = Graph::local_graph_device_type::row_map_type::non_const_type;
using ColInds = Graph::local_graph_device_type::entries_type::non_const_type;
using Values = Matrix::local_matrix_device_type::values_type;
constexpr int kPlain = -1, kFixed = -2;  ///< a row's kind, else the index of its special row

/// Special rows as flat arrays: row k is the owned local row `lrow(k)` with the entries
/// start(k) .. start(k+1) (local columns, weights).
struct SpecialRows {
  Kokkos::View<LO*, ExecSpace> lrow;
  Kokkos::View<int*, ExecSpace> start;
  Kokkos::View<LO*, ExecSpace> col;
  Kokkos::View<double*, ExecSpace> weight;
};

LO owned_row(const Map& owned, GO g) {
  const LO l = owned.getLocalElement(g);
  if (l == Tpetra::Details::OrdinalTraits<LO>::invalid())
    throw Error("internal: a special row of P is not owned by its rank");
  return l;
}

/// `col_of(g)`: the local column of global column g. With `merge`, each row's entries are
/// sorted by local column and a repeated column's weights are summed.
template <class ColOf>
SpecialRows flatten(const Map& owned, const std::vector<PRow>& rows, ColOf col_of, bool merge) {
  std::vector<LO> lrow, col;
  std::vector<int> start = {0};
  std::vector<double> weight;
  std::vector<std::pair<LO, double>> e;
  for (const auto& r : rows) {
    lrow.push_back(owned_row(owned, r.row));
    e.clear();
    for (std::size_t j = 0; j < r.cols.size(); ++j) e.emplace_back(col_of(r.cols[j]), r.weights[j]);
    if (merge) std::sort(e.begin(), e.end());
    for (std::size_t j = 0; j < e.size(); ++j) {
      if (merge && j > 0 && e[j].first == e[j - 1].first) {
        weight.back() += e[j].second;
        continue;
      }
      col.push_back(e[j].first);
      weight.push_back(e[j].second);
    }
    start.push_back(static_cast<int>(col.size()));
  }
  SpecialRows s;
  const auto copy = [](auto& view, const auto& v, const char* label) {
    using View = std::decay_t<decltype(view)>;
    view = View(std::string(label), v.size());
    auto h = Kokkos::create_mirror_view(view);
    for (std::size_t k = 0; k < v.size(); ++k) h(k) = v[k];
    Kokkos::deep_copy(view, h);
  };
  copy(s.lrow, lrow, "emc::P::special_rows");
  copy(s.start, start, "emc::P::special_start");
  copy(s.col, col, "emc::P::special_cols");
  copy(s.weight, weight, "emc::P::special_weights");
  return s;
}

/// kind(i) for every owned row: plain, fixed, or the index of its special row (a special row
/// wins over a fixed one).
Kokkos::View<int*, ExecSpace> row_kinds(const Map& owned, const std::vector<GO>& fixed,
                                        const SpecialRows& s) {
  Kokkos::View<int*, ExecSpace> kind(Kokkos::ViewAllocateWithoutInitializing("emc::P::kind"),
                                     owned.getNodeNumElements());
  Kokkos::deep_copy(kind, kPlain);
  Kokkos::View<LO*, ExecSpace> fixed_rows("emc::P::fixed_rows", fixed.size());
  auto fh = Kokkos::create_mirror_view(fixed_rows);
  for (std::size_t k = 0; k < fixed.size(); ++k) fh(k) = owned_row(owned, fixed[k]);
  Kokkos::deep_copy(fixed_rows, fh);
  Kokkos::parallel_for(
      "emcontact::linalg::P_fixed_rows", Kokkos::RangePolicy<ExecSpace>(0, fixed_rows.extent(0)),
      KOKKOS_LAMBDA(const int k) { kind(fixed_rows(k)) = kFixed; });
  const auto lrow = s.lrow;
  Kokkos::parallel_for(
      "emcontact::linalg::P_special_rows", Kokkos::RangePolicy<ExecSpace>(0, lrow.extent(0)),
      KOKKOS_LAMBDA(const int k) { kind(lrow(k)) = k; });
  return kind;
}

/// The CRS arrays of P: a plain row i holds e_i (local column i: the column map starts with the
/// owned rows), a fixed row nothing, a special row its flattened entries.
void fill_crs(const Kokkos::View<int*, ExecSpace> kind, const SpecialRows s, RowPtrs& ptr,
              ColInds& cols, Values& vals) {
  const LO n = static_cast<LO>(kind.extent(0));
  ptr = RowPtrs("emc::P::row_ptr", n + 1);
  const auto start = s.start;
  Kokkos::parallel_scan(
      "emcontact::linalg::P_row_ptr", Kokkos::RangePolicy<ExecSpace>(0, n),
      KOKKOS_LAMBDA(const int i, std::size_t& sum, const bool final) {
        const int k = kind(i);
        sum += k == kPlain ? 1 : k == kFixed ? 0 : start(k + 1) - start(k);
        if (final) ptr(i + 1) = sum;
      });
  std::size_t nnz = 0;
  Kokkos::deep_copy(nnz, Kokkos::subview(ptr, n));
  cols = ColInds(Kokkos::ViewAllocateWithoutInitializing("emc::P::cols"), nnz);
  vals = Values(Kokkos::ViewAllocateWithoutInitializing("emc::P::values"), nnz);
  const auto col = s.col;
  const auto weight = s.weight;
  Kokkos::parallel_for(
      "emcontact::linalg::P_entries", Kokkos::RangePolicy<ExecSpace>(0, n),
      KOKKOS_LAMBDA(const int i) {
        const int k = kind(i);
        auto e = ptr(i);
        if (k == kPlain) {
          cols(e) = i;
          vals(e) = 1.0;
        } else if (k != kFixed) {
          for (int j = start(k); j < start(k + 1); ++j, ++e) {
            cols(e) = col(j);
            vals(e) = weight(j);
          }
        }
      });
}

/// The owned global ids, then `remote` (sorted, unique).
RCP<const Map> column_map(const RCP<const Map>& owned, const std::vector<GO>& remote) {
  const LO n = static_cast<LO>(owned->getNodeNumElements());
  Kokkos::View<GO*, ExecSpace> gids(Kokkos::ViewAllocateWithoutInitializing("emc::P::col_gids"),
                                    n + remote.size());
  const auto local = owned->getLocalMap();
  Kokkos::parallel_for(
      "emcontact::linalg::P_col_gids", Kokkos::RangePolicy<ExecSpace>(0, n),
      KOKKOS_LAMBDA(const int i) { gids(i) = local.getGlobalElement(i); });
  auto tail = Kokkos::subview(gids, std::make_pair(static_cast<std::size_t>(n), gids.extent(0)));
  auto th = Kokkos::create_mirror_view(tail);
  for (std::size_t k = 0; k < remote.size(); ++k) th(k) = remote[k];
  Kokkos::deep_copy(tail, th);
  const auto invalid = Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid();
  return rcp(new Map(invalid, Kokkos::View<const GO*, ExecSpace>(gids), owned->getIndexBase(),
                     owned->getComm()));
}

}  // namespace

RCP<Matrix> make_P(const RCP<const Map>& owned, const std::vector<GO>& fixed,
                   const std::vector<PRow>& rows) {
  const auto invalid = Tpetra::Details::OrdinalTraits<LO>::invalid();
  std::vector<GO> remote;
  for (const auto& r : rows)
    for (GO c : r.cols)
      if (owned->getLocalElement(c) == invalid) remote.push_back(c);
  std::sort(remote.begin(), remote.end());
  remote.erase(std::unique(remote.begin(), remote.end()), remote.end());
  int any = remote.empty() ? 0 : 1, all = 0;
  Teuchos::reduceAll(*owned->getComm(), Teuchos::REDUCE_MAX, 1, &any, &all);
  const RCP<const Map> col_map = all ? column_map(owned, remote) : owned;
  const LO n = static_cast<LO>(owned->getNodeNumElements());
  const auto col_of = [&](GO c) {
    const LO l = owned->getLocalElement(c);
    if (l != invalid) return l;
    return n + static_cast<LO>(std::lower_bound(remote.begin(), remote.end(), c) - remote.begin());
  };
  const SpecialRows s = flatten(*owned, rows, col_of, true);
  RowPtrs ptr;
  ColInds cols;
  Values vals;
  fill_crs(row_kinds(*owned, fixed, s), s, ptr, cols, vals);
  auto P = rcp(new Matrix(owned, col_map, ptr, cols, vals));
  P->expertStaticFillComplete(owned, owned);
  return P;
}

void write_P_rows(Matrix& P, const std::vector<PRow>& rows) {
  const auto& col_map = *P.getColMap();
  const auto col_of = [&](GO c) {
    const LO l = col_map.getLocalElement(c);
    if (l == Tpetra::Details::OrdinalTraits<LO>::invalid())
      throw Error("internal: a special row of P has a column its graph does not hold");
    return l;
  };
  const SpecialRows s = flatten(*P.getRowMap(), rows, col_of, false);
  const auto A = P.getLocalMatrixDevice();
  const auto lrow = s.lrow;
  const auto start = s.start;
  const auto col = s.col;
  const auto weight = s.weight;
  int missing = 0;  // entries whose column the row does not hold (a caller's error)
  Kokkos::parallel_reduce(
      "emcontact::linalg::P_write_rows", Kokkos::RangePolicy<ExecSpace>(0, lrow.extent(0)),
      KOKKOS_LAMBDA(const int k, int& miss) {
        const LO i = lrow(k);
        const auto b = A.graph.row_map(i), e = A.graph.row_map(i + 1);
        for (auto p = b; p < e; ++p) A.values(p) = 0.0;
        for (int j = start(k); j < start(k + 1); ++j) {  // a repeated column adds its weights
          auto p = b;
          while (p < e && A.graph.entries(p) != col(j)) ++p;
          if (p < e)
            A.values(p) += weight(j);
          else
            ++miss;
        }
      },
      missing);
  if (missing > 0) throw Error("internal: a special row of P has a column its row does not hold");
}

}  // namespace emc::linalg
