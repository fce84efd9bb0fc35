#include "emcontact/fem/partition.hpp"

#include <Zoltan2_BasicVectorAdapter.hpp>
#include <Zoltan2_PartitioningProblem.hpp>
#include <algorithm>
#include <array>
#include <climits>
#include <cstdint>
#include <numeric>

#include "emcontact/error.hpp"
#include "emcontact/parallel.hpp"

namespace emc::fem {

namespace {

/// Spreads the low 21 bits of v so that two zero bits separate consecutive bits.
std::uint64_t spread3(std::uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

double centroid(const Model& m, int e, int i) {
  double c = 0;
  for (int a = 0; a < 4; ++a) c += 0.25 * m.x(m.tets[4 * e + a])[i];
  return c;
}

std::vector<std::uint64_t> morton_keys(const Model& m) {
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (int n = 0; n < m.held_nodes(); ++n)  // the kept nodes' box is the whole model's
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], m.X[3 * n + i]);
      hi[i] = std::max(hi[i], m.X[3 * n + i]);
    }
  double ext = 0;
  for (int i = 0; i < 3; ++i) ext = std::max(ext, hi[i] - lo[i]);
  const double scale = ext > 0 ? ((1 << 21) - 1) / ext : 0;
  std::vector<std::uint64_t> key(m.num_tets());
  for (int e = 0; e < m.num_tets(); ++e) {
    std::uint64_t k = 0;
    for (int i = 0; i < 3; ++i)
      k |= spread3(static_cast<std::uint64_t>((centroid(m, e, i) - lo[i]) * scale)) << i;
    key[e] = k;
  }
  return key;
}

/// Sorts tet ids along the Morton curve (stable: ties keep their order).
void sort_along_curve(std::vector<int>& tets, const std::vector<std::uint64_t>& key) {
  std::stable_sort(tets.begin(), tets.end(), [&](int a, int b) { return key[a] < key[b]; });
}

/// Zoltan2's part of each tet of [first, first + n), this rank's share of the input, from their
/// centroids (3 per tet; collective).
/// Multi-jagged rather than RCB (Zoltan's, `algorithm = rcb`): on the 506k-tet ball both give
/// parts within one tet of the mean, and on 2 ranks the same cut; on 4 ranks multi-jagged's
/// parts share 5241 interface nodes, RCB's 5326 (the Morton split: 5526). Unit weights: weighting
/// the tets on the bodies' surfaces (where the contact nodes are) did not change the contact
/// nodes owned by other ranks on the ball's impact at 2 and 4 ranks.
/// Deterministic: mj_migration_option = 2 keeps every tet on the rank that fed it, so that
/// the cuts are found from global reductions alone, whose sums are of unit weights (integers,
/// exact in any order) and min/max of coordinates. So the same input and rank count give the
/// same parts, also with Kokkos threads.
std::vector<int> zoltan2_parts(long long first, const std::vector<double>& centroids,
                               const Teuchos::RCP<const Comm>& comm) {
  using Adapter = Zoltan2::BasicVectorAdapter<Zoltan2::BasicUserTypes<double, int, long long>>;
  const int n = static_cast<int>(centroids.size() / 3);
  std::vector<long long> gid(n);
  std::vector<double> x(n), y(n), z(n);
  for (int k = 0; k < n; ++k) {
    gid[k] = first + k;
    x[k] = centroids[3 * k];
    y[k] = centroids[3 * k + 1];
    z[k] = centroids[3 * k + 2];
  }
  Adapter adapter(n, gid.data(), x.data(), y.data(), z.data());
  Teuchos::ParameterList params("emcontact partition");
  params.set("algorithm", "multijagged");
  params.set("num_global_parts", comm->getSize());
  params.set("imbalance_tolerance", partition_imbalance_tolerance);
  params.set("mj_migration_option", 2);
  Zoltan2::PartitioningProblem<Adapter> problem(&adapter, &params, comm);
  problem.solve();
  const int* part = problem.getSolution().getPartListView();
  return std::vector<int>(part, part + n);
}

/// The centroids of tets [begin, end) of m (3 each).
std::vector<double> centroids(const Model& m, long long begin, long long end) {
  std::vector<double> c;
  c.reserve(3 * (end - begin));
  for (long long e = begin; e < end; ++e)
    for (int i = 0; i < 3; ++i) c.push_back(centroid(m, static_cast<int>(e), i));
  return c;
}

/// The first tet of rank r's share of ne tets among np ranks (Zoltan2's input blocks).
long long block_begin(long long ne, int r, int np) {
  return ne * r / np;
}

/// The nodes of p.my_tets (tets of m) into p.owned_nodes and p.shared_nodes by p.node_owner.
void split_nodes(const Model& m, Partition& p, int rank) {
  std::vector<int> used;
  used.reserve(4 * p.my_tets.size());
  for (int t : p.my_tets)
    for (int a = 0; a < 4; ++a) used.push_back(m.tets[4 * std::size_t(t) + a]);
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  for (int n : used) (p.node_owner[n] == rank ? p.owned_nodes : p.shared_nodes).push_back(n);
}

/// The partition for the part of every tet: my tets along the curve, the owners of node_owners.
Partition assemble(const Model& m, const std::vector<int>& part_of_tet,
                   const std::vector<std::uint64_t>& key, int rank) {
  Partition p;
  p.node_owner = node_owners(m, part_of_tet);
  for (int e = 0; e < m.num_tets(); ++e)
    if (part_of_tet[e] == rank) p.my_tets.push_back(e);
  sort_along_curve(p.my_tets, key);
  split_nodes(m, p, rank);
  return p;
}

}  // namespace

// docs/developer-guide.md, "Decisions" (partition): the owner of every node of m (all its tets
// held, `part` the rank of each) among the k ranks with a tet touching node n, in ascending
// order, is the (n mod k)-th, so that the interface nodes are shared out evenly (given all to
// the lowest rank, rank 0 owned the most rows and had the largest peak memory); -1 where no
// tet touches it. A node with one touching rank is decided from the lowest and highest rank
// touching it; only the interface nodes' (node, rank) pairs are listed, so that the memory
// is O(nodes + interface) for any rank count.
std::vector<int> node_owners(const Model& m, const std::vector<int>& part) {
  std::vector<int> lo(m.num_nodes(), INT_MAX), hi(m.num_nodes(), -1);
  for (int e = 0; e < m.num_tets(); ++e)
    for (int a = 0; a < 4; ++a) {
      const int n = m.tets[4 * std::size_t(e) + a];
      lo[n] = std::min(lo[n], part[e]);
      hi[n] = std::max(hi[n], part[e]);
    }
  std::vector<std::uint64_t> shared;  // (node << 32 | rank) of the interface nodes
  for (int e = 0; e < m.num_tets(); ++e)
    for (int a = 0; a < 4; ++a) {
      const int n = m.tets[4 * std::size_t(e) + a];
      if (lo[n] != hi[n]) shared.push_back(std::uint64_t(n) << 32 | std::uint32_t(part[e]));
    }
  std::sort(shared.begin(), shared.end());
  shared.erase(std::unique(shared.begin(), shared.end()), shared.end());
  std::vector<int> owner = std::move(hi);  // one touching rank: its owner; none: -1
  for (std::size_t i = 0; i < shared.size();) {
    const int n = static_cast<int>(shared[i] >> 32);
    std::size_t k = i;
    while (k < shared.size() && static_cast<int>(shared[k] >> 32) == n) ++k;
    owner[n] = static_cast<int>(shared[i + n % (k - i)] & 0xffffffffu);
    i = k;
  }
  return owner;
}

std::vector<int> morton_order(const Model& m) {
  std::vector<int> order(m.num_tets());
  std::iota(order.begin(), order.end(), 0);
  sort_along_curve(order, morton_keys(m));
  return order;
}

// Each rank gives Zoltan2 a contiguous share of the tet ids and gets their parts back. The
// model is replicated, so the parts are all-gathered and every rank derives its tets and the
// owner of every node from them.
Partition partition(const Model& m, const Teuchos::RCP<const Comm>& comm) {
  const int ne = m.num_tets(), rank = comm->getRank(), np = comm->getSize();
  std::vector<int> part_of_tet(ne, 0);
  if (np > 1) {
    const long long begin = block_begin(ne, rank, np), end = block_begin(ne, rank + 1, np);
    part_of_tet = allgather(*comm, zoltan2_parts(begin, centroids(m, begin, end), comm));
  }
  return assemble(m, part_of_tet, morton_keys(m), rank);
}

namespace {

/// Rank 0's centroids of the tets of every rank's Zoltan2 block, scattered (MPI_Scatterv).
std::vector<double> scatter_centroids(const Model& m, long long ne, const Comm& comm) {
  const int np = comm.getSize(), rank = comm.getRank();
  std::vector<int> count(np), displ(np);
  for (int r = 0; r < np; ++r) {
    count[r] = static_cast<int>(3 * (block_begin(ne, r + 1, np) - block_begin(ne, r, np)));
    displ[r] = static_cast<int>(3 * block_begin(ne, r, np));
  }
  const std::vector<double> all = rank == 0 ? centroids(m, 0, ne) : std::vector<double>();
  std::vector<double> mine(count[rank]);
  MPI_Scatterv(all.data(), count.data(), displ.data(), MPI_DOUBLE, mine.data(), count[rank],
               MPI_DOUBLE, 0, raw_comm(comm));
  return mine;
}

/// Every block's parts on rank 0, in tet order (MPI_Gatherv; empty on the other ranks).
std::vector<int> gather_parts(const std::vector<int>& mine, long long ne, const Comm& comm) {
  const int np = comm.getSize(), rank = comm.getRank();
  std::vector<int> count(np), displ(np);
  for (int r = 0; r < np; ++r) {
    count[r] = static_cast<int>(block_begin(ne, r + 1, np) - block_begin(ne, r, np));
    displ[r] = static_cast<int>(block_begin(ne, r, np));
  }
  std::vector<int> all(rank == 0 ? ne : 0);
  MPI_Gatherv(mine.data(), static_cast<int>(mine.size()), MPI_INT, all.data(), count.data(),
              displ.data(), MPI_INT, 0, raw_comm(comm));
  return all;
}

/// The held tets of one rank: ids ascending, its own first.
struct TetList {
  std::vector<int> owned, ghost;
};

/// Rank 0: each rank's own tets and ghosts (the tets of other ranks touching a node it owns,
/// and every tet with a massless node).
std::vector<TetList> tet_lists(const Model& m, const std::vector<int>& part,
                               const std::vector<int>& owner, int np) {
  std::vector<TetList> lists(np);
  for (int e = 0; e < m.num_tets(); ++e) {
    const int r = part[e];
    lists[r].owned.push_back(e);
    if (massless_mask(m, e)) {
      for (int o = 0; o < np; ++o)
        if (o != r) lists[o].ghost.push_back(e);
      continue;
    }
    int need[4], n = 0;
    for (int a = 0; a < 4; ++a) {
      const int o = owner[m.tets[4 * e + a]];
      if (o != r && std::find(need, need + n, o) == need + n) need[n++] = o;
    }
    for (int k = 0; k < n; ++k) lists[need[k]].ghost.push_back(e);
  }
  return lists;
}

/// The held tets of a list: ids, 4 node ids and the body of each.
struct HeldTets {
  std::vector<long long> gid;
  std::vector<int> tets, body;
  int owned = 0;
};

HeldTets held_tets(const Model& m, const TetList& list) {
  HeldTets h;
  h.owned = static_cast<int>(list.owned.size());
  for (const auto* ids : {&list.owned, &list.ghost})
    for (int e : *ids) {
      h.gid.push_back(e);
      h.tets.insert(h.tets.end(), m.tets.begin() + 4 * std::size_t(e),
                    m.tets.begin() + 4 * std::size_t(e + 1));
      h.body.push_back(m.body_of_tet[e]);
    }
  return h;
}

constexpr int kTagHeld = 4501;

/// Rank 0 sends each other rank its held tets, one rank at a time (so that only one rank's
/// part is ever copied out), and returns its own.
HeldTets send_held_tets(const Model& m, const std::vector<TetList>& lists, const Comm& comm) {
  const MPI_Comm c = raw_comm(comm);
  for (int r = 1; r < comm.getSize(); ++r) {
    const HeldTets h = held_tets(m, lists[r]);
    long long head[2] = {static_cast<long long>(h.gid.size()), h.owned};
    MPI_Send(head, 2, MPI_LONG_LONG, r, kTagHeld, c);
    MPI_Send(h.gid.data(), static_cast<int>(h.gid.size()), MPI_LONG_LONG, r, kTagHeld, c);
    MPI_Send(h.tets.data(), static_cast<int>(h.tets.size()), MPI_INT, r, kTagHeld, c);
    MPI_Send(h.body.data(), static_cast<int>(h.body.size()), MPI_INT, r, kTagHeld, c);
  }
  return held_tets(m, lists[0]);
}

HeldTets receive_held_tets(const Comm& comm) {
  const MPI_Comm c = raw_comm(comm);
  long long head[2];
  MPI_Recv(head, 2, MPI_LONG_LONG, 0, kTagHeld, c, MPI_STATUS_IGNORE);
  HeldTets h;
  h.owned = static_cast<int>(head[1]);
  h.gid.resize(head[0]);
  h.tets.resize(4 * head[0]);
  h.body.resize(head[0]);
  MPI_Recv(h.gid.data(), static_cast<int>(h.gid.size()), MPI_LONG_LONG, 0, kTagHeld, c,
           MPI_STATUS_IGNORE);
  MPI_Recv(h.tets.data(), static_cast<int>(h.tets.size()), MPI_INT, 0, kTagHeld, c,
           MPI_STATUS_IGNORE);
  MPI_Recv(h.body.data(), static_cast<int>(h.body.size()), MPI_INT, 0, kTagHeld, c,
           MPI_STATUS_IGNORE);
  return h;
}

/// Rank 0's bodies' geometry, mesh identity and massless fit on every rank.
void broadcast_rank0_results(Model& m, const Comm& comm) {
  std::vector<double> g;
  for (const Body& b : m.bodies)
    g.insert(g.end(), {b.centre[0], b.centre[1], b.centre[2], b.median_edge, b.radius});
  broadcast_vector(comm, g);
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    for (int i = 0; i < 3; ++i) m.bodies[b].centre[i] = g[5 * b + i];
    m.bodies[b].median_edge = g[5 * b + 3];
    m.bodies[b].radius = g[5 * b + 4];
  }
  unsigned long long fnv = m.mesh_fnv;
  Teuchos::broadcast(comm, 0, 1, &fnv);
  m.mesh_fnv = fnv;
  if (m.massless.empty()) return;
  broadcast_vector(comm, m.massless_fit.node);
  broadcast_vector(comm, m.massless_fit.start);
  broadcast_vector(comm, m.massless_fit.support);
  broadcast_vector(comm, m.massless_fit.weight);
}

/// This rank's part of a distributed model: its own tets along the curve, the owners.
Partition part_of_held(const Model& m, std::vector<int> node_owner, int rank) {
  Partition p;
  p.node_owner = std::move(node_owner);
  p.my_tets.resize(m.owned_tets);
  std::iota(p.my_tets.begin(), p.my_tets.end(), 0);
  sort_along_curve(p.my_tets, morton_keys(m));
  split_nodes(m, p, rank);
  return p;
}

/// The nodes a rank keeps (ascending): those of its held tets, every deformable body's
/// boundary and named surfaces (contact's slaves and masters, the Dirichlet surfaces), the
/// massless nodes and their fits' supports. The boundary nodes hold the bodies' extremes, so
/// bounding boxes over the kept nodes are the whole model's (morton_keys, the scale checks).
std::vector<int> nodes_to_keep(const Model& m) {
  std::vector<int> keep(m.tets.begin(), m.tets.end());
  const auto add = [&](const Body& b, const std::vector<std::array<int, 3>>& tris) {
    for (const auto& t : tris)
      for (int a : t) keep.push_back(b.node_begin + a);
  };
  for (const Body& b : m.bodies) {
    if (b.rigid) continue;
    add(b, b.mesh.boundary);
    for (const auto& named : b.mesh.surfaces) add(b, named.second);
  }
  const auto& fit = m.massless_fit;
  keep.insert(keep.end(), fit.node.begin(), fit.node.end());
  keep.insert(keep.end(), fit.support.begin(), fit.support.end());
  std::sort(keep.begin(), keep.end());
  keep.erase(std::unique(keep.begin(), keep.end()), keep.end());
  return keep;
}

/// The model's per-node arrays and the partition's owners reduced to the nodes to keep.
void keep_my_nodes(Model& m, Partition& p) {
  std::vector<int> keep = nodes_to_keep(m);
  std::vector<int> owner(keep.size());
  for (std::size_t l = 0; l < keep.size(); ++l) owner[l] = p.owner(m, keep[l]);
  p.node_owner = std::move(owner);
  keep_nodes(m, std::move(keep));
}

}  // namespace

Partition distribute(Model& m, const Teuchos::RCP<const Comm>& comm) {
  const int rank = comm->getRank(), np = comm->getSize();
  const long long ne = m.global_tets;
  if (rank == 0 && !m.holds_all_tets())
    throw Error("internal: fem::distribute needs every tet on rank 0");
  if (np == 1) {
    m.owned_tets = m.num_tets();
    return partition(m, comm);
  }
  broadcast_rank0_results(m, *comm);
  const long long first = block_begin(ne, rank, np);
  const std::vector<int> part =
      gather_parts(zoltan2_parts(first, scatter_centroids(m, ne, *comm), comm), ne, *comm);
  std::vector<int> owner;
  std::vector<TetList> lists;
  if (rank == 0) {
    owner = node_owners(m, part);
    lists = tet_lists(m, part, owner, np);
  }
  broadcast_vector(*comm, owner);
  HeldTets h = rank == 0 ? send_held_tets(m, lists, *comm) : receive_held_tets(*comm);
  m.tets = std::move(h.tets);
  m.body_of_tet = std::move(h.body);
  m.tet_gid = std::move(h.gid);
  m.owned_tets = h.owned;
  Partition p = part_of_held(m, std::move(owner), rank);
  keep_my_nodes(m, p);
  return p;
}

}  // namespace emc::fem
