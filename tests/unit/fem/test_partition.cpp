// The element partition (fem/partition.hpp) on 1, 2 and 4 ranks (ctest test_partition_np1,
// _np2, _np4): every tet in exactly one part, every used node owned by exactly one rank (one of
// the ranks that use it, the interface shared out evenly), the owned/shared lists consistent
// with it; the parts balanced within Zoltan2's imbalance tolerance; no more interface nodes than
// the Morton split it replaced; the same result from two calls. distribute() (rank 0 handing out
// the tets) gives the same parts as partition() of the whole model, each rank its own tets and one
// layer of ghosts.
#include <gtest/gtest.h>

#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_Core.hpp>
#include <algorithm>
#include <climits>
#include <iterator>
#include <numeric>
#include <set>

#include "emcontact/fem/partition.hpp"
#include "emcontact/parallel.hpp"
#include "support/box_model.hpp"

namespace {

using emc::fem::Model;
using emc::fem::Partition;

/// The box of n^3 cubes stretched to 3 x 1 x 1.5 (the parts are not the octants of a cube).
Model stretched_box(int n) {
  Model m = emc::test::box_model(n);
  for (int k = 0; k < m.num_nodes(); ++k) {
    m.X[3 * k] *= 3.0;
    m.X[3 * k + 2] *= 1.5;
  }
  return m;
}

/// The part (rank) of every tet, from every rank's my_tets (-1: in no part; -2: in several).
std::vector<int> part_of_tet(const Model& m, const Partition& p, const emc::Comm& comm) {
  const auto tets = emc::allgather(comm, p.my_tets);
  const auto counts = emc::allgather(comm, std::vector<int>{static_cast<int>(p.my_tets.size())});
  std::vector<int> part(m.num_tets(), -1);
  std::size_t k = 0;
  for (int r = 0; r < comm.getSize(); ++r)
    for (int i = 0; i < counts[r]; ++i, ++k) {
      int& t = part.at(tets[k]);
      t = t == -1 ? r : -2;
    }
  return part;
}

/// The nodes used by tets of more than one part.
int interface_nodes(const Model& m, const std::vector<int>& part) {
  std::vector<int> lo(m.num_nodes(), INT_MAX), hi(m.num_nodes(), -1);
  for (int e = 0; e < m.num_tets(); ++e)
    for (int a = 0; a < 4; ++a) {
      const int n = m.tets[4 * e + a];
      lo[n] = std::min(lo[n], part[e]);
      hi[n] = std::max(hi[n], part[e]);
    }
  int count = 0;
  for (int n = 0; n < m.num_nodes(); ++n) count += hi[n] >= 0 && lo[n] != hi[n];
  return count;
}

/// The partition this one replaced: the tets along the Morton curve cut into equal chunks.
std::vector<int> morton_split(const Model& m, int num_ranks) {
  const auto order = emc::fem::morton_order(m);
  const long long ne = m.num_tets();
  std::vector<int> part(ne);
  for (int r = 0; r < num_ranks; ++r)
    for (long long k = ne * r / num_ranks; k < ne * (r + 1) / num_ranks; ++k) part[order[k]] = r;
  return part;
}

TEST(Partition, EveryTetInOnePartEveryNodeOwnedByOneOfItsUsers) {
  const auto comm = Tpetra::getDefaultComm();
  const Model m = stretched_box(6);
  const Partition p = emc::fem::partition(m, comm);
  const auto part = part_of_tet(m, p, *comm);
  for (int e = 0; e < m.num_tets(); ++e) ASSERT_GE(part[e], 0) << "tet " << e;
  // the owner: of the k ranks with a tet touching node n, ascending, the (n mod k)-th; on every
  // rank the same
  std::vector<std::set<int>> users(m.num_nodes());
  for (int e = 0; e < m.num_tets(); ++e)
    for (int a = 0; a < 4; ++a) users[m.tets[4 * e + a]].insert(part[e]);
  for (int n = 0; n < m.num_nodes(); ++n) {
    ASSERT_FALSE(users[n].empty());
    EXPECT_EQ(p.node_owner[n], *std::next(users[n].begin(), n % users[n].size())) << "node " << n;
  }
  // owned + shared: exactly the nodes of my tets, split by owner, sorted
  std::vector<int> used;
  for (int t : p.my_tets) used.insert(used.end(), &m.tets[4 * t], &m.tets[4 * t] + 4);
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  std::vector<int> both;
  std::merge(p.owned_nodes.begin(), p.owned_nodes.end(), p.shared_nodes.begin(),
             p.shared_nodes.end(), std::back_inserter(both));
  EXPECT_EQ(both, used);
  EXPECT_TRUE(std::is_sorted(p.owned_nodes.begin(), p.owned_nodes.end()));
  EXPECT_TRUE(std::is_sorted(p.shared_nodes.begin(), p.shared_nodes.end()));
  for (int n : p.owned_nodes) EXPECT_EQ(p.node_owner[n], comm->getRank());
  for (int n : p.shared_nodes) EXPECT_NE(p.node_owner[n], comm->getRank());
  // every node owned exactly once over the ranks
  auto owned = emc::allgather(*comm, p.owned_nodes);
  std::sort(owned.begin(), owned.end());
  std::vector<int> all(m.num_nodes());
  std::iota(all.begin(), all.end(), 0);
  EXPECT_EQ(owned, all);
}

TEST(Partition, MyTetsAlongTheMortonCurve) {
  const auto comm = Tpetra::getDefaultComm();
  const Model m = stretched_box(6);
  const Partition p = emc::fem::partition(m, comm);
  const auto order = emc::fem::morton_order(m);
  std::vector<int> rank_in_curve(m.num_tets());
  for (int k = 0; k < m.num_tets(); ++k) rank_in_curve[order[k]] = k;
  for (std::size_t k = 1; k < p.my_tets.size(); ++k)
    EXPECT_LT(rank_in_curve[p.my_tets[k - 1]], rank_in_curve[p.my_tets[k]]);
  if (comm->getSize() == 1) EXPECT_EQ(p.my_tets, order);
}

TEST(Partition, BalancedWithinZoltan2sImbalanceTolerance) {
  const auto comm = Tpetra::getDefaultComm();
  const Model m = stretched_box(8);
  const Partition p = emc::fem::partition(m, comm);
  // imbalance_tolerance bounds the largest part's weight over the mean (unit weights: tets)
  const double mean = double(m.num_tets()) / comm->getSize();
  const auto sizes = emc::allgather(*comm, std::vector<int>{static_cast<int>(p.my_tets.size())});
  const int largest = *std::max_element(sizes.begin(), sizes.end());
  EXPECT_LE(largest, emc::fem::partition_imbalance_tolerance * mean)
      << "mean " << mean << ", smallest " << *std::min_element(sizes.begin(), sizes.end());
}

TEST(Partition, NoMoreInterfaceNodesThanTheMortonSplit) {
  const auto comm = Tpetra::getDefaultComm();
  const Model m = stretched_box(8);
  const int zoltan2 = interface_nodes(m, part_of_tet(m, emc::fem::partition(m, comm), *comm));
  const int morton = interface_nodes(m, morton_split(m, comm->getSize()));
  if (comm->getRank() == 0)
    std::printf("interface nodes on %d ranks: Zoltan2 %d, Morton split %d\n", comm->getSize(),
                zoltan2, morton);
  EXPECT_LE(zoltan2, morton);
  if (comm->getSize() == 1) EXPECT_EQ(zoltan2, 0);
}

TEST(Partition, TheSameTwice) {
  const auto comm = Tpetra::getDefaultComm();
  const Model m = stretched_box(6);
  const Partition a = emc::fem::partition(m, comm), b = emc::fem::partition(m, comm);
  EXPECT_EQ(a.my_tets, b.my_tets);
  EXPECT_EQ(a.owned_nodes, b.owned_nodes);
  EXPECT_EQ(a.shared_nodes, b.shared_nodes);
  EXPECT_EQ(a.node_owner, b.node_owner);
}

}  // namespace

namespace {

/// The box with its bottom layer's nodes massless (as for a massless slave surface), the fit
/// taken on every rank from the whole model.
Model box_with_massless_bottom(int n) {
  Model m = stretched_box(n);
  m.massless.assign(m.num_nodes(), 0);
  for (int k = 0; k < m.num_nodes(); ++k) m.massless[k] = m.X[3 * k + 2] == 0.0;
  EXPECT_EQ(emc::fem::fit_massless_nodes(m), -1);
  return m;
}

/// distribute() of rank 0's copy of `whole` (the other ranks holding no tets, as after
/// app::build_meshes) against partition() of the whole model on every rank.
void expect_distribute_matches_partition(const Model& whole) {
  const auto comm = Tpetra::getDefaultComm();
  const int rank = comm->getRank(), np = comm->getSize();
  const Partition ref = emc::fem::partition(whole, comm);
  Model m = whole;
  if (rank != 0) {
    m.tets.clear();
    m.body_of_tet.clear();
    m.owned_tets = 0;
    m.mesh_fnv = 0;
    m.bodies[0].centre = {};
    m.bodies[0].median_edge = m.bodies[0].radius = 0;
    m.massless_fit = {};
  }
  const Partition p = emc::fem::distribute(m, comm);
  // the same tets in the same order, the same owners
  ASSERT_EQ(p.my_tets.size(), ref.my_tets.size());
  for (std::size_t k = 0; k < p.my_tets.size(); ++k)
    EXPECT_EQ(m.tet_id(p.my_tets[k]), ref.my_tets[k]);
  ASSERT_EQ(p.node_owner.size(), static_cast<std::size_t>(m.held_nodes()));
  for (int l = 0; l < m.held_nodes(); ++l)
    EXPECT_EQ(p.node_owner[l], ref.node_owner[m.node_id(l)]) << "node " << m.node_id(l);
  EXPECT_EQ(p.owned_nodes, ref.owned_nodes);
  EXPECT_EQ(p.shared_nodes, ref.shared_nodes);
  // every held tet as in the whole model; own tets first, each group ascending
  ASSERT_EQ(m.tets.size(), 4 * m.tet_gid.size() + (np == 1 ? m.tets.size() : 0));
  for (int e = 0; e < m.num_tets(); ++e) {
    const long long g = m.tet_id(e);
    for (int a = 0; a < 4; ++a) EXPECT_EQ(m.tets[4 * e + a], whole.tets[4 * g + a]);
    EXPECT_EQ(m.body_of_tet[e], whole.body_of_tet[g]);
    if (e > 0 && e != m.owned_tets) EXPECT_LT(m.tet_id(e - 1), g);
  }
  // the ghosts: exactly the other ranks' tets touching a node I own, and those with a massless
  // node
  std::vector<long long> ghosts, expected;
  for (int e = m.owned_tets; e < m.num_tets(); ++e) ghosts.push_back(m.tet_id(e));
  std::vector<char> mine(whole.num_tets(), 0);
  for (int e : ref.my_tets) mine[e] = 1;
  for (int e = 0; e < whole.num_tets() && np > 1; ++e) {
    if (mine[e]) continue;
    bool touches = emc::fem::massless_mask(whole, e) != 0;
    for (int a = 0; a < 4; ++a) touches = touches || ref.node_owner[whole.tets[4 * e + a]] == rank;
    if (touches) expected.push_back(e);
  }
  EXPECT_EQ(ghosts, expected);
  if (np > 1 && rank == 0) EXPECT_FALSE(expected.empty());  // the owner of the interface
  // the per-node arrays: exactly the held tets' nodes and the massless fits' (these test models
  // have no surfaces), each as in the whole model
  std::set<int> used(m.tets.begin(), m.tets.end());
  const auto& fit = whole.massless_fit;
  used.insert(fit.node.begin(), fit.node.end());
  used.insert(fit.support.begin(), fit.support.end());
  EXPECT_EQ(m.num_nodes(), whole.num_nodes());
  ASSERT_EQ(m.held_nodes(), static_cast<int>(used.size()));
  int l = 0;
  for (int n : used) {
    EXPECT_EQ(m.node_id(l), n);
    EXPECT_EQ(m.local_node(n), l);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(m.x(n)[c], whole.X[3 * n + c]);
    EXPECT_EQ(m.is_fixed(n), whole.fixed[n] != 0);
    EXPECT_EQ(m.is_massless(n), !whole.massless.empty() && whole.massless[n] != 0);
    ++l;
  }
  if (np > 1 && whole.massless.empty())  // a rank's share and a layer, not the whole
    EXPECT_LT(m.held_nodes(), whole.num_nodes() * (1.0 / np + 0.35));
  // rank 0's results on every rank; the own tets add up to the whole
  EXPECT_EQ(m.mesh_fnv, whole.mesh_fnv);
  EXPECT_EQ(m.bodies[0].centre, whole.bodies[0].centre);
  EXPECT_EQ(m.bodies[0].median_edge, whole.bodies[0].median_edge);
  EXPECT_EQ(m.massless_fit.support, whole.massless_fit.support);
  EXPECT_EQ(m.massless_fit.weight, whole.massless_fit.weight);
  int owned = m.owned_tets, total = 0;
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, 1, &owned, &total);
  EXPECT_EQ(total, whole.num_tets());
}

}  // namespace

// The owner of a node is the (n mod k)-th of the k ranks touching it, for any rank count (here
// 100 parts dealt out tet by tet, so that most nodes touch many of them, beyond 64).
TEST(Partition, NodeOwnerAmongItsRanksForAnyRankCount) {
  const Model m = stretched_box(6);
  std::vector<int> part(m.num_tets());
  for (int e = 0; e < m.num_tets(); ++e) part[e] = (7 * e) % 100;
  const std::vector<int> owner = emc::fem::node_owners(m, part);
  std::vector<std::set<int>> touching(m.num_nodes());
  for (int e = 0; e < m.num_tets(); ++e)
    for (int a = 0; a < 4; ++a) touching[m.tets[4 * e + a]].insert(part[e]);
  ASSERT_EQ(owner.size(), touching.size());
  int many = 0;
  for (int n = 0; n < m.num_nodes(); ++n) {
    const std::vector<int> ranks(touching[n].begin(), touching[n].end());
    ASSERT_FALSE(ranks.empty());
    EXPECT_EQ(owner[n], ranks[n % ranks.size()]) << "node " << n;
    many += ranks.size() > 1;
  }
  EXPECT_GT(many, m.num_nodes() / 2);
}

// The interface nodes shared out: every rank owns about as many nodes, within 5 % of the mean on
// the 10^3 box (given all to the lowest rank, rank 0 owns its half and the 121 interface nodes
// at 2 ranks: 9 % above the mean).
TEST(Partition, OwnedNodesBalanced) {
  const auto comm = Tpetra::getDefaultComm();
  const Model m = stretched_box(10);
  const Partition p = emc::fem::partition(m, comm);
  const auto owned =
      emc::allgather(*comm, std::vector<int>{static_cast<int>(p.owned_nodes.size())});
  const double mean = double(m.num_nodes()) / comm->getSize();
  for (int n : owned) EXPECT_LE(n, 1.05 * mean) << "of " << m.num_nodes() << " nodes";
}

// Rank 0 hands out the tets: the same parts as the partition of the whole model, each rank
// holding its own tets and one layer of ghosts, rank 0 no more than the others.
TEST(Distribute, SamePartsAsThePartitionOfTheWholeModel) {
  Model whole = stretched_box(10);
  whole.mesh_fnv = 12345;  // as build_model's, on rank 0
  expect_distribute_matches_partition(whole);
}

TEST(Distribute, MasslessTetsOnEveryRank) {
  Model whole = box_with_massless_bottom(8);
  whole.mesh_fnv = 6789;
  expect_distribute_matches_partition(whole);
}
