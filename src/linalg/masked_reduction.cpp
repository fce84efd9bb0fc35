#include "emcontact/linalg/masked_reduction.hpp"

namespace emc::linalg {

using Teuchos::RCP;
using Teuchos::rcp;

RCP<Vector> keep_vector(const RCP<const Map>& owned, const std::vector<GO>& constrained) {
  auto keep = rcp(new Vector(owned));
  keep->putScalar(1.0);
  auto k = keep->getLocalViewHost(Tpetra::Access::ReadWrite);
  for (GO g : constrained) k(owned->getLocalElement(g), 0) = 0.0;
  return keep;
}

Vector keep_on_columns(const Vector& keep, const Matrix& A) {
  Vector col(A.getColMap());
  if (A.getCrsGraph()->getImporter().is_null())
    col.assign(keep);  // the column map is the row map
  else
    col.doImport(keep, *A.getCrsGraph()->getImporter(), Tpetra::INSERT);
  return col;
}

void MaskedReduction::set_keep(RCP<const Vector> keep) {
  keep_ = std::move(keep);
  keep_col_stale_ = true;
}

// The graph is copied (local arrays, the same maps, importer and exporter) so that the
// reduced matrix does not share the FE graph, which switches between owned and owned+shared
// rows at every assembly.
namespace {

// The position of each row's diagonal entry in the values (-1 if none): a kernel in a free
// function (device code is never in a private member).
template <class Rows, class Cols, class LocalMap>
void diagonal_positions(const Rows rows, const Cols cols, const LocalMap col_map,
                        const LocalMap row_map, const Kokkos::View<long*, ExecSpace> diag_pos) {
  Kokkos::parallel_for(
      "emcontact::linalg::masked_diagonal", Kokkos::RangePolicy<ExecSpace>(0, diag_pos.extent(0)),
      KOKKOS_LAMBDA(const int i) {
        const LO diag_col = col_map.getLocalElement(row_map.getGlobalElement(i));
        diag_pos(i) = -1;
        for (auto j = rows(i); j < rows(i + 1); ++j)
          if (cols(j) == diag_col) diag_pos(i) = static_cast<long>(j);
      });
}

}  // namespace

void MaskedReduction::copy_graph(const Matrix& A) {
  const auto& g = *A.getCrsGraph();
  const auto lcl = g.getLocalGraphDevice();
  using RowPtrs = typename Graph::local_graph_device_type::row_map_type::non_const_type;
  using ColInds = typename Graph::local_graph_device_type::entries_type::non_const_type;
  RowPtrs rows("emc::masked::rows", lcl.row_map.extent(0));
  ColInds cols("emc::masked::cols", lcl.entries.extent(0));
  Kokkos::deep_copy(rows, lcl.row_map);
  Kokkos::deep_copy(cols, lcl.entries);
  // the position of each row's diagonal entry in the values, found once
  diag_pos_ = Kokkos::View<long*, ExecSpace>("emc::masked::diag_pos", rows.extent(0) - 1);
  diagonal_positions(rows, cols, g.getColMap()->getLocalMap(), g.getRowMap()->getLocalMap(),
                     diag_pos_);
  auto copy = rcp(new Graph(g.getRowMap(), g.getColMap(), rows, cols));
  copy->expertStaticFillComplete(g.getDomainMap(), g.getRangeMap(), g.getImporter(),
                                 g.getExporter());
  graph_ = copy;
  col_map_ = g.getColMap();
  keep_col_stale_ = true;
}

void MaskedReduction::import_keep(const Matrix& A) {
  const Vector col = keep_on_columns(*keep_, A);
  auto v = col.getLocalViewDevice(Tpetra::Access::ReadOnly);
  keep_col_ = Kokkos::View<double*, ExecSpace>("emc::masked::keep_col", v.extent(0));
  Kokkos::deep_copy(keep_col_, Kokkos::subview(v, Kokkos::ALL(), 0));
  keep_col_stale_ = false;
}

// docs/THEORY.md §3.6: (P^T A P + D)_ij = p_i A_ij p_j + D_ij with p the 0/1 diagonal of P.
RCP<Matrix> MaskedReduction::apply(const Matrix& A) {
  if (graph_.is_null() || col_map_.get() != A.getColMap().get() ||
      graph_->getNodeNumEntries() != A.getNodeNumEntries())
    copy_graph(A);
  if (keep_col_stale_) import_keep(A);
  const auto lA = A.getLocalMatrixDevice();
  const auto rows = lA.graph.row_map;
  const auto cols = lA.graph.entries;
  const auto vA = lA.values;
  typename Matrix::local_matrix_device_type::values_type::non_const_type vals(
      Kokkos::ViewAllocateWithoutInitializing("emc::masked::values"), vA.extent(0));
  const auto keep_col = keep_col_;
  const auto keep = keep_->getLocalViewDevice(Tpetra::Access::ReadOnly);
  const auto d = d_->getLocalViewDevice(Tpetra::Access::ReadOnly);
  const auto diag_pos = diag_pos_;
  Kokkos::parallel_for(
      "emcontact::linalg::masked_ptap", Kokkos::RangePolicy<ExecSpace>(0, keep.extent(0)),
      KOKKOS_LAMBDA(const int i) {
        // P's entries are 1 or absent: A_ij itself or nothing (no 0 * inf)
        for (auto j = rows(i); j < rows(i + 1); ++j)
          vals(j) = keep(i, 0) != 0 && keep_col(cols(j)) != 0 ? vA(j) : 0.0;
        if (diag_pos(i) >= 0) vals(diag_pos(i)) += d(i, 0);
      });
  auto out = rcp(new Matrix(graph_, vals));
  out->fillComplete(A.getDomainMap(), A.getRangeMap());
  return out;
}

}  // namespace emc::linalg
