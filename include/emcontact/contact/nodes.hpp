#pragma once
// The contact nodes of this rank (docs/THEORY.md §8): the slave nodes it owns, their neighbours
// on the slave surface, and the nodes of the master facets within reach of its slaves over the
// step, with the facets of the chains through them. Only their positions are imported, so a
// rank's contact memory and traffic grow with its share of the contact surface, not the model.
#include <Kokkos_Core.hpp>
#include <algorithm>
#include <array>
#include <memory>
#include <unordered_map>
#include <vector>

#include "emcontact/contact/active.hpp"
#include "emcontact/contact/pairs.hpp"
#include "emcontact/contact/search.hpp"
#include "emcontact/fem/discretization.hpp"
#include "kernels/facet.hpp"
#include "kernels/math.hpp"

namespace emc::contact {

/// Positions of the contact nodes (contact-node index, coordinate).
using Positions = Kokkos::View<double* [3], ExecSpace>;

/// The positions x = X + u of the contact nodes computed where they are read (x(l, c)), for a
/// kernel that reads a few of them: X(l) the reference (or rigid) position; for l < nd, u's
/// component c at src(l, c) of the owned values v (src >= 0) or at -1 - src of the imported
/// values r; no displacement for l >= nd (rigid). fill() writes the same bits into Positions.
struct NodePositions {
  Kokkos::View<const double* [3], ExecSpace> X;
  Kokkos::View<const LO* [3], ExecSpace> src;
  int nd = 0;
  Kokkos::View<const double**, Kokkos::LayoutLeft, ExecSpace> v, r;
  KOKKOS_INLINE_FUNCTION double operator()(const int l, const int c) const {
    const LO k = l < nd ? src(l, c) : 0;
    return X(l, c) + (l >= nd ? 0.0 : k >= 0 ? v(k, 0) : r(-1 - k, 0));
  }
  int size() const { return static_cast<int>(X.extent(0)); }
};

/// x(l, c) = p(l, c) for every contact node (a labelled kernel).
void fill(const NodePositions& p, Positions x);

/// A pair's master facets held by this rank, by ascending facet id.
struct LocalFacets {
  Kokkos::View<int* [3], ExecSpace> nodes;  ///< contact-node indices
  Kokkos::View<int*, ExecSpace> id;         ///< the facet's id in the pair
  std::unordered_map<int, int> index;       ///< facet id -> position (host)
  /// a rigid master's grid (grown by the pair's max penetration), built with the facets: they
  /// never move (null for a deformable master)
  std::shared_ptr<const FacetGrid> rigid_grid;
  int size() const { return static_cast<int>(id.extent(0)); }
  /// The grid of the facets at x (the pair's max penetration `margin`): a rigid master's own.
  FacetGrid grid(Kokkos::View<const double* [3], ExecSpace> x, double margin) const {
    return rigid_grid ? *rigid_grid : FacetGrid(nodes, x, margin);
  }
  int find(int facet) const {
    auto it = index.find(facet);
    return it == index.end() ? -1 : it->second;
  }
};

/// A pair's slave nodes owned by this rank and the slave-surface triangles around each (for its
/// normal), in contact-node indices: triangles tri(start(k)) .. tri(start(k + 1) - 1) of node k.
struct LocalSlaves {
  Kokkos::View<int*, ExecSpace> node;     ///< contact-node index of my k-th slave
  Kokkos::View<int*, ExecSpace> start;    ///< CSR offsets into tri
  Kokkos::View<int* [3], ExecSpace> tri;  ///< contact-node indices
  int size() const { return static_cast<int>(node.extent(0)); }
};

/// The outward unit normal of the slave surface at my k-th slave in configuration x: the
/// area-weighted mean of its triangles' normals.
template <class X>
KOKKOS_INLINE_FUNCTION void slave_normal(const LocalSlaves& ls, int k, const X& x, double n[3]) {
  n[0] = n[1] = n[2] = 0;
  for (int j = ls.start(k); j < ls.start(k + 1); ++j) {
    double xm[3][3];
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < 3; ++i) xm[a][i] = x(ls.tri(j, a), i);
    const kernels::Facet f = kernels::facet(xm);
    for (int i = 0; i < 3; ++i) n[i] += f.area2 * f.n[i];
  }
  const double len = kernels::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (int i = 0; i < 3; ++i) n[i] = len > 0 ? n[i] / len : 0.0;
}

/// What the selection moved: for perf/README.md's traffic figures.
struct NodeTraffic {
  long long selections = 0;      ///< calls of select
  long long imports = 0;         ///< position imports (none while no rank has remote nodes)
  long long bytes_imported = 0;  ///< received from other ranks over all imports
  int nodes = 0;                 ///< contact nodes at the last selection
  int remote = 0;                ///< of which owned by other ranks
};

class ContactNodes {
 public:
  ContactNodes(const fem::Discretization& disc, const std::vector<Pair>& pairs);

  /// The start of a step's sweeps, which its selections share: u_n and, per pair, the box of my
  /// slave nodes at u_n (lo, hi).
  struct Sweep {
    const Vector* u0 = nullptr;
    std::vector<std::array<double, 6>> slaves_at_u0;
  };
  Sweep sweep_from(const Vector& u0) const;
  /// docs/THEORY.md §8: selects the facets whose sweep from u0 to u1 meets the sweep of my slave
  /// nodes grown by the pair's max penetration and facet size, and the facets of the entries of
  /// `index` whose slave is one of my contact nodes (chains, until closed) (collective).
  void select(const Sweep& from, const Vector& u1, const ActiveIndex& index);
  void select(const Vector& u0, const Vector& u1, const ActiveIndex& index) {
    select(sweep_from(u0), u1, index);
  }
  /// select() for the sweep of the last selection (u0 and u1 unchanged since): the facets in
  /// its reach stay, the chains of `index` are closed anew (collective).
  void reselect(const ActiveIndex& index);

  /// x = X + u of my contact nodes; u an owned vector (collective: imports the remote ones).
  void positions(const Vector& u, Positions x) const;
  /// The same, computed where a kernel reads them (collective: imports the remote ones; the
  /// result reads u's values, so it follows u until u is reallocated).
  NodePositions lazy_positions(const Vector& u) const;
  Positions new_positions(const char* label) const;
  /// Host copy of the positions at u (collective).
  Positions::HostMirror host_positions(const Vector& u) const;

  int size() const { return static_cast<int>(gid_.size()); }
  /// Contact-node index of global node n (-1 if not one of mine); its global node id.
  int local(int n) const {
    const auto it = std::lower_bound(gid_.begin(), gid_.end(), n);
    return it == gid_.end() || *it != n ? -1 : static_cast<int>(it - gid_.begin());
  }
  int global(int l) const { return gid_[l]; }
  const LocalFacets& facets(int pair) const { return facets_[pair]; }
  const LocalSlaves& slaves(int pair) const { return slaves_[pair]; }
  /// The slave nodes of the pair that this rank owns (global ids, ascending).
  const std::vector<int>& my_slaves(int pair) const { return my_slaves_[pair]; }
  const NodeTraffic& traffic() const { return traffic_; }
  /// Changes when the contact nodes (hence the rows of Positions) change.
  int builds() const { return builds_; }

 private:
  const fem::Discretization& disc_;
  const std::vector<Pair>& pairs_;
  std::vector<std::vector<int>> my_slaves_;
  std::vector<std::vector<int>> held_;  ///< per pair: deformable facets my overlap map holds
  std::vector<int> slave_side_;         ///< my slaves and their slave-surface neighbours, ascending
  /// per pair: my slaves' reference positions and owned dofs (their boxes over the step)
  std::vector<Kokkos::View<const double* [3], ExecSpace>> slave_X_;
  std::vector<Kokkos::View<const LO* [3], ExecSpace>> slave_dofs_;
  std::vector<int> gid_;  ///< contact node -> global node (deformable, then rigid)
  /// per pair: my slaves and their slave-surface triangles in slave_side_ indices (fixed)
  std::vector<LocalSlaves> slave_sides_;
  int deformable_ = 0;                      ///< the first deformable_ contact nodes carry dofs
  std::vector<std::vector<int>> selected_;  ///< per pair: the facets of the last build
  std::vector<LocalFacets> facets_;
  std::vector<LocalSlaves> slaves_;
  Teuchos::RCP<const Map> map_;
  Teuchos::RCP<const Import> import_;       ///< of the remote contact nodes' dofs only
  bool imports_ = false;                    ///< some rank has remote contact nodes
  Kokkos::View<LO* [3], ExecSpace> src_;    ///< per dof: owned row, or -1 - its row in map_
  Kokkos::View<double* [3], ExecSpace> X_;  ///< reference (or rigid) positions
  mutable NodeTraffic traffic_;
  int builds_ = 0;

  std::vector<std::vector<int>> in_reach_;  ///< per pair: the facets in reach at the last select

  void slave_box_data(const std::vector<int>& mine);
  std::vector<std::vector<double>> slave_boxes(const Sweep& from, const Vector& u1) const;
  std::vector<std::vector<int>> facets_in_reach(const Sweep& from, const Vector& u1) const;
  void select_closed(std::vector<std::vector<int>> need);
  void close_chains(std::vector<std::vector<int>>& need, const ActiveIndex& index) const;
  void build(const std::vector<std::vector<int>>& need);
  void build_slaves(std::size_t pair, Kokkos::View<const int*, ExecSpace> side_local);
  static LocalSlaves slave_tris(const Pair& p, const std::vector<int>& mine,
                                const std::vector<int>& side);
};

}  // namespace emc::contact
