#pragma once
// A simple, documented element partition: tets are ordered along a Morton (Z-order) curve of
// their centroids (which also improves memory locality), then cut into equal contiguous
// chunks, one per rank. A node is owned by the lowest rank that has a tet touching it.
#include <vector>

#include "emcontact/fem/model.hpp"

namespace emc::fem {

struct Partition {
  std::vector<int> my_tets;       ///< global tet ids of this rank, in Morton order
  std::vector<int> owned_nodes;   ///< sorted global node ids this rank owns
  std::vector<int> shared_nodes;  ///< sorted global node ids used by my tets, owned elsewhere
  std::vector<int> node_owner;    ///< owner rank of every global node (-1: used by no tet)
};

Partition partition(const Model& m, int rank, int num_ranks);

}  // namespace emc::fem
