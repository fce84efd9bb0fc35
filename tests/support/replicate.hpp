#pragma once
// Every node's values of an owned dof vector on every rank (tests only: the solver itself never
// replicates the model, docs/THEORY.md §8).
#include <vector>

#include "emcontact/fem/discretization.hpp"

namespace emc::testing {

inline std::vector<double> replicate(const emc::fem::Discretization& disc, const emc::Vector& u) {
  const emc::GO n = 3LL * disc.model().num_nodes();
  auto all = Teuchos::rcp(new emc::Map(n, 0, disc.comm(), Tpetra::LocallyReplicated));
  emc::Import to_all(disc.owned_map(), all);
  emc::Vector v(all);
  v.doImport(u, to_all, Tpetra::INSERT);
  auto h = v.getLocalViewHost(Tpetra::Access::ReadOnly);
  return std::vector<double>(h.data(), h.data() + h.extent(0));
}

}  // namespace emc::testing
