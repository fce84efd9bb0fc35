// The element partition (fem/partition.hpp) on 1, 2 and 4 ranks (ctest test_partition_np1,
// _np2, _np4): every tet in exactly one part, every used node owned by exactly one rank (the
// lowest that uses it), the owned/shared lists consistent with it; the parts balanced within
// Zoltan2's imbalance tolerance; no more interface nodes than the Morton split it replaced;
// the same result from two calls.
#include <gtest/gtest.h>

#include <Tpetra_Core.hpp>
#include <algorithm>
#include <climits>
#include <numeric>

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

TEST(Partition, EveryTetInOnePartEveryNodeOwnedByItsLowestUser) {
  const auto comm = Tpetra::getDefaultComm();
  const Model m = stretched_box(6);
  const Partition p = emc::fem::partition(m, comm);
  const auto part = part_of_tet(m, p, *comm);
  for (int e = 0; e < m.num_tets(); ++e) ASSERT_GE(part[e], 0) << "tet " << e;
  // the owner: the lowest rank with a tet touching the node, on every rank the same
  std::vector<int> owner(m.num_nodes(), INT_MAX);
  for (int e = 0; e < m.num_tets(); ++e)
    for (int a = 0; a < 4; ++a)
      owner[m.tets[4 * e + a]] = std::min(owner[m.tets[4 * e + a]], part[e]);
  for (int n = 0; n < m.num_nodes(); ++n)
    EXPECT_EQ(p.node_owner[n], owner[n] == INT_MAX ? -1 : owner[n]) << "node " << n;
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
