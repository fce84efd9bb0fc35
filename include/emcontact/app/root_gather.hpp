#pragma once
// Moves owned vectors (dofs or elements) to and from contiguous blocks of global ids: to rank 0
// whole (checkpoints), or to every rank's block of rows of the field files (FieldLayout).
#include <vector>

#include "emcontact/types.hpp"

namespace emc::app {

class RootGather {
 public:
  /// Every one of the n_global ids on rank 0.
  RootGather(Teuchos::RCP<const Map> owned, GO n_global)
      : RootGather(owned, 0, owned->getComm()->getRank() == 0 ? n_global : 0) {}
  /// Ids [first, first + count) on this rank (the ranks' blocks cover the owned ids once).
  RootGather(Teuchos::RCP<const Map> owned, GO first, GO count) {
    const auto invalid = Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid();
    std::vector<GO> ids(static_cast<std::size_t>(count));
    for (GO k = 0; k < count; ++k) ids[k] = first + k;
    root_ = Teuchos::rcp(new Map(invalid, Teuchos::ArrayView<const GO>(ids), 0, owned->getComm()));
    import_ = Teuchos::rcp(new Import(owned, root_));
  }
  /// This rank's block of entries (rank 0's: every entry, with the first constructor).
  std::vector<double> operator()(const Vector& v) const {
    Vector r(root_);
    r.doImport(v, *import_, Tpetra::INSERT);
    auto h = r.getLocalViewHost(Tpetra::Access::ReadOnly);
    return std::vector<double>(h.data(), h.data() + h.extent(0));
  }
  /// The reverse: rank 0's global array (ignored elsewhere) into the owned vector v.
  void scatter(const std::vector<double>& global, Vector& v) const {
    Vector r(root_);
    {
      auto h = r.getLocalViewHost(Tpetra::Access::OverwriteAll);
      for (std::size_t k = 0; k < h.extent(0); ++k) h(k, 0) = global.at(k);
    }
    v.doExport(r, *import_, Tpetra::INSERT);
  }

 private:
  Teuchos::RCP<const Map> root_;
  Teuchos::RCP<const Import> import_;
};

}  // namespace emc::app
