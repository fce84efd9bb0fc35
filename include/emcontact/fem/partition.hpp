#pragma once
// The element partition, one part per rank (docs/developer-guide.md, "Decisions"): Zoltan2's
// multi-jagged geometric partition of the tets' centroids (recursive cuts of space into boxes
// of equal tet counts). Within a part the tets are ordered along a Morton (Z-order) curve of
// their centroids, for memory locality in the element loops and the colouring. A node is owned
// by the lowest rank that has a tet touching it. The same model and rank count always give the
// same partition; on one rank Zoltan2 is not called.
#include <Teuchos_RCP.hpp>
#include <vector>

#include "emcontact/fem/model.hpp"
#include "emcontact/types.hpp"

namespace emc::fem {

struct Partition {
  std::vector<int> my_tets;       ///< global tet ids of this rank, in Morton order
  std::vector<int> owned_nodes;   ///< sorted global node ids this rank owns
  std::vector<int> shared_nodes;  ///< sorted global node ids used by my tets, owned elsewhere
  std::vector<int> node_owner;    ///< owner rank of every global node (-1: used by no tet)
};

/// Zoltan2's imbalance_tolerance: the largest part holds at most this times the mean number
/// of tets per rank.
inline constexpr double partition_imbalance_tolerance = 1.01;

/// This rank's part of m over comm's ranks. Collective: every rank of comm calls it with the
/// same (replicated) model.
Partition partition(const Model& m, const Teuchos::RCP<const Comm>& comm);

/// Every global tet id, ordered along the Morton curve of the tets' centroids (in the cube
/// around all nodes, 2^21 cells a side); ties in id order.
std::vector<int> morton_order(const Model& m);

}  // namespace emc::fem
