#pragma once
// The element partition, one part per rank (docs/developer-guide.md, "Decisions"): Zoltan2's
// multi-jagged geometric partition of the tets' centroids (recursive cuts of space into boxes
// of equal tet counts). Within a part the tets are ordered along a Morton (Z-order) curve of
// their centroids, for memory locality in the element loops and the colouring. A node is owned
// by one of the ranks that have a tet touching it, the interface nodes shared out evenly among
// them (node_owners in partition.cpp). The same model and rank count always give the
// same partition; on one rank Zoltan2 is not called.
#include <Teuchos_RCP.hpp>
#include <vector>

#include "emcontact/fem/model.hpp"
#include "emcontact/types.hpp"

namespace emc::fem {

struct Partition {
  std::vector<int>
      my_tets;  ///< this rank's tets (indices of the model's held tets), in Morton order
  std::vector<int> owned_nodes;   ///< sorted global node ids this rank owns
  std::vector<int> shared_nodes;  ///< sorted global node ids used by my tets, owned elsewhere
  /// The owner rank of each node the model holds (Model::node_ids' order; -1: used by no tet).
  std::vector<int> node_owner;
  /// The owner rank of global node n, held by m.
  int owner(const Model& m, int n) const { return node_owner[m.held_node(n)]; }
};

/// Zoltan2's imbalance_tolerance: the largest part holds at most this times the mean number
/// of tets per rank.
inline constexpr double partition_imbalance_tolerance = 1.01;

/// This rank's part of m over comm's ranks. Collective: every rank of comm calls it with the
/// same (replicated) model.
Partition partition(const Model& m, const Teuchos::RCP<const Comm>& comm);

/// Hands every rank its part of rank 0's tets (collective): Zoltan2 partitions their centroids,
/// given to it in blocks of ids scattered from rank 0 (the blocks partition() gives it), then
/// rank 0 sends each rank, one after the other, its own tets and its ghosts, and keeps only its
/// own. Before: rank 0's m holds every tet (build_model); the other ranks' hold none (or a
/// replicated copy, ignored). After: see Model::tet_gid; the bodies' geometry, mesh_fnv and
/// the massless fit are rank 0's on every rank, and the per-node arrays (Model::node_ids) keep
/// only the nodes of the held tets, of every deformable body's boundary and named surfaces
/// (contact's and the boundary conditions' nodes), the massless nodes and their fits' supports.
/// Returns this rank's part: the same tets in the same order, owners and shared nodes as
/// partition() of the whole model (my_tets then index the held tets; node_owner the held
/// nodes). On one rank the model stays as it is.
Partition distribute(Model& m, const Teuchos::RCP<const Comm>& comm);

/// The owner rank of every node of m (every tet held, part[e] the rank of tet e): among the k
/// ranks with a tet touching node n, in ascending order, the (n mod k)-th; -1 where no tet
/// touches it (any rank count).
std::vector<int> node_owners(const Model& m, const std::vector<int>& part);

/// Every global tet id, ordered along the Morton curve of the tets' centroids (in the cube
/// around all nodes, 2^21 cells a side); ties in id order.
std::vector<int> morton_order(const Model& m);

}  // namespace emc::fem
