#pragma once
// Moves owned vectors (dofs or elements) to and from rank 0 in global order: output fields and
// checkpoints.
#include <vector>

#include "emcontact/types.hpp"

namespace emc::app {

class RootGather {
 public:
  RootGather(Teuchos::RCP<const Map> owned, GO n_global) {
    const auto invalid = Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid();
    std::vector<GO> ids;
    if (owned->getComm()->getRank() == 0)
      for (GO g = 0; g < n_global; ++g) ids.push_back(g);
    root_ = Teuchos::rcp(new Map(invalid, Teuchos::ArrayView<const GO>(ids), 0, owned->getComm()));
    import_ = Teuchos::rcp(new Import(owned, root_));
  }
  /// Every entry on rank 0 (empty elsewhere).
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
