// docs/THEORY.md §8: the contact nodes of a rank and the import of their positions only.
#include "emcontact/contact/nodes.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_TimeMonitor.hpp>
#include <algorithm>
#include <array>
#include <iterator>

#include "emcontact/error.hpp"
#include "emcontact/parallel.hpp"
#include "kernels/math.hpp"

namespace emc::contact {

namespace {

constexpr double kHuge = 1e300;

void sort_unique(std::vector<int>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

/// f(facet) for each slave-surface facet around slave node s of pair p (its normal's facets).
template <class F>
void for_each_slave_tri(const Pair& p, int s, F f) {
  const auto k = std::lower_bound(p.slaves.begin(), p.slaves.end(), s) - p.slaves.begin();
  for (int t = p.tri_start[k]; t < p.tri_start[k + 1]; ++t) f(p.slave_facets[p.slave_tris[t]]);
}

bool boxes_meet(const double* a, const double* b) {
  for (int i = 0; i < 3; ++i)
    if (a[i] > b[3 + i] || b[i] > a[3 + i]) return false;
  return true;
}

void grow(double* box, const double x[3]) {
  for (int i = 0; i < 3; ++i) {
    box[i] = std::min(box[i], x[i]);
    box[3 + i] = std::max(box[3 + i], x[i]);
  }
}

/// The box of the points X(k) + u(dof(k)) over k: one reduction of the six bounds (a functor:
/// device code is never in a private member).
struct SlaveBox {
  struct value_type {
    double lo[3], hi[3];
  };
  Kokkos::View<const double* [3], ExecSpace> X;
  Kokkos::View<const LO* [3], ExecSpace> dof;
  Kokkos::View<const double**, Kokkos::LayoutLeft, ExecSpace> v;

  KOKKOS_INLINE_FUNCTION void operator()(const int k, value_type& b) const {
    for (int c = 0; c < 3; ++c) {
      const double a = X(k, c) + v(dof(k, c), 0);
      b.lo[c] = a < b.lo[c] ? a : b.lo[c];
      b.hi[c] = a > b.hi[c] ? a : b.hi[c];
    }
  }
  KOKKOS_INLINE_FUNCTION void init(value_type& b) const {
    for (int c = 0; c < 3; ++c) {
      b.lo[c] = kHuge;
      b.hi[c] = -kHuge;
    }
  }
  EMC_KERNELS_REDUCER_JOIN(value_type)
  template <class A, class B>
  KOKKOS_INLINE_FUNCTION static void join_into(A& a, const B& b) {
    for (int c = 0; c < 3; ++c) {
      a.lo[c] = b.lo[c] < a.lo[c] ? b.lo[c] : a.lo[c];
      a.hi[c] = b.hi[c] > a.hi[c] ? b.hi[c] : a.hi[c];
    }
  }
};

/// box (lo, hi) = the box of X(k) + u(dof(k)) over k (empty if there is no k).
void slave_box(const Kokkos::View<const double* [3], ExecSpace> X,
               const Kokkos::View<const LO* [3], ExecSpace> dof, const Vector& u, double* box) {
  const SlaveBox f{X, dof, u.getLocalViewDevice(Tpetra::Access::ReadOnly)};
  SlaveBox::value_type b;
  Kokkos::parallel_reduce("emcontact::contact::slave_box",
                          Kokkos::RangePolicy<ExecSpace>(0, X.extent(0)), f, b);
  for (int c = 0; c < 3; ++c) {
    box[c] = b.lo[c];
    box[3 + c] = b.hi[c];
  }
}

/// out(k) = map(in(k)).
void gather_ids(const Kokkos::View<const int*, ExecSpace> map,
                const Kokkos::View<const int*, ExecSpace> in,
                const Kokkos::View<int*, ExecSpace> out) {
  Kokkos::parallel_for(
      "emcontact::contact::to_local", Kokkos::RangePolicy<ExecSpace>(0, in.extent(0)),
      KOKKOS_LAMBDA(const int k) { out(k) = map(in(k)); });
}

}  // namespace

ContactNodes::ContactNodes(const fem::Discretization& disc, const std::vector<Pair>& pairs)
    : disc_(disc), pairs_(pairs), facets_(pairs.size()), slaves_(pairs.size()) {
  const int rank = disc_.comm()->getRank();
  const auto& overlap = *disc_.overlap_map();
  const auto holds = [&](int n) {
    return overlap.getLocalElement(fem::dof_gid(n, 0)) !=
           Tpetra::Details::OrdinalTraits<LO>::invalid();
  };
  for (const auto& p : pairs_) {
    my_slaves_.emplace_back();
    for (int s : p.slaves)
      if (disc_.part().owner(disc_.model(), s) == rank) my_slaves_.back().push_back(s);
    slave_box_data(my_slaves_.back());
    for (int s : my_slaves_.back()) {  // the slave and its slave-surface neighbours (its normal)
      slave_side_.push_back(s);
      for_each_slave_tri(
          p, s, [&](const auto& g) { slave_side_.insert(slave_side_.end(), g.begin(), g.end()); });
    }
    held_.emplace_back();
    if (p.rigid_master) continue;
    for (int f = 0; f < static_cast<int>(p.facets.size()); ++f) {
      const auto& t = p.facets[f];
      if (holds(t[0]) && holds(t[1]) && holds(t[2])) held_.back().push_back(f);
    }
  }
  sort_unique(slave_side_);
  for (std::size_t p = 0; p < pairs_.size(); ++p)
    slave_sides_.push_back(slave_tris(pairs_[p], my_slaves_[p], slave_side_));
}

// My slaves of pair p and the slave-surface triangles around each, in indices into `side`
// (ascending, holding them all).
LocalSlaves ContactNodes::slave_tris(const Pair& p, const std::vector<int>& mine,
                                     const std::vector<int>& side) {
  const auto at = [&](int n) {
    return static_cast<int>(std::lower_bound(side.begin(), side.end(), n) - side.begin());
  };
  LocalSlaves g;
  g.node = Kokkos::View<int*, ExecSpace>("emc::my_slaves", mine.size());
  g.start = Kokkos::View<int*, ExecSpace>("emc::local_slave_start", mine.size() + 1);
  auto nh = Kokkos::create_mirror_view(g.node);
  auto sh = Kokkos::create_mirror_view(g.start);
  std::vector<std::array<int, 3>> tris;
  for (std::size_t k = 0; k < mine.size(); ++k) {
    nh(k) = at(mine[k]);
    sh(k) = static_cast<int>(tris.size());
    for_each_slave_tri(p, mine[k], [&](const auto& t) {
      tris.push_back({at(t[0]), at(t[1]), at(t[2])});
    });
  }
  sh(mine.size()) = static_cast<int>(tris.size());
  g.tri = Kokkos::View<int* [3], ExecSpace>("emc::my_slave_tris", tris.size());
  auto th = Kokkos::create_mirror_view(g.tri);
  for (std::size_t t = 0; t < tris.size(); ++t)
    for (int a = 0; a < 3; ++a) th(t, a) = tris[t][a];
  Kokkos::deep_copy(g.node, nh);
  Kokkos::deep_copy(g.start, sh);
  Kokkos::deep_copy(g.tri, th);
  return g;
}

// The reference positions of my slaves and their owned dofs, for slave_boxes.
void ContactNodes::slave_box_data(const std::vector<int>& mine) {
  const auto& m = disc_.model();
  const auto& map = *disc_.owned_map();
  Kokkos::View<double* [3], ExecSpace> X("emc::slave_X", mine.size());
  Kokkos::View<LO* [3], ExecSpace> dof("emc::slave_dofs", mine.size());
  auto Xh = Kokkos::create_mirror_view(X);
  auto dh = Kokkos::create_mirror_view(dof);
  for (std::size_t k = 0; k < mine.size(); ++k) {
    const double* Xk = m.x(mine[k]);
    for (int c = 0; c < 3; ++c) {
      Xh(k, c) = Xk[c];
      dh(k, c) = map.getLocalElement(fem::dof_gid(mine[k], c));
    }
  }
  Kokkos::deep_copy(X, Xh);
  Kokkos::deep_copy(dof, dh);
  slave_X_.push_back(X);
  slave_dofs_.push_back(dof);
}

ContactNodes::Sweep ContactNodes::sweep_from(const Vector& u0) const {
  Sweep s;
  s.u0 = &u0;
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    std::array<double, 6> b = {kHuge, kHuge, kHuge, -kHuge, -kHuge, -kHuge};
    if (!my_slaves_[p].empty()) slave_box(slave_X_[p], slave_dofs_[p], u0, b.data());
    s.slaves_at_u0.push_back(b);
  }
  return s;
}

// The box of my slave nodes of each pair over the step (x at u0 and at u1: the union of the two
// boxes), grown by the pair's max penetration and mean facet size (the reach of Newton's
// iterates and of §5 step 2).
std::vector<std::vector<double>> ContactNodes::slave_boxes(const Sweep& from,
                                                           const Vector& u1) const {
  std::vector<std::vector<double>> boxes;
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    std::vector<double> b(from.slaves_at_u0[p].begin(), from.slaves_at_u0[p].end());
    if (!my_slaves_[p].empty()) {
      double b1[6];
      slave_box(slave_X_[p], slave_dofs_[p], u1, b1);
      grow(b.data(), b1);
      grow(b.data(), b1 + 3);
      const double reach = pairs_[p].dmax + pairs_[p].edge;
      for (int i = 0; i < 3; ++i) {
        b[i] -= reach;
        b[3 + i] += reach;
      }
    }
    boxes.push_back(std::move(b));
  }
  return boxes;
}

// Each rank tests the deformable facets its overlap map holds against every rank's slave boxes
// and sends their ids; rigid facets (never moving, known everywhere) are tested locally.
std::vector<std::vector<int>> ContactNodes::facets_in_reach(const Sweep& from,
                                                            const Vector& u1) const {
  const Vector& u0 = *from.u0;
  const auto& m = disc_.model();
  const int np = static_cast<int>(pairs_.size()), nr = disc_.comm()->getSize();
  const auto mine = slave_boxes(from, u1);
  std::vector<double> flat;
  for (const auto& b : mine) flat.insert(flat.end(), b.begin(), b.end());
  const auto all = allgather(*disc_.comm(), flat);  // [rank][pair][6]
  const bool deformable =
      std::any_of(pairs_.begin(), pairs_.end(), [](const Pair& p) { return !p.rigid_master; });
  Teuchos::RCP<Vector> o0, o1;  // the positions of the deformable facets my elements hold
  if (deformable) {
    o0 = disc_.new_overlap_vector();
    o1 = disc_.new_overlap_vector();
    disc_.to_overlap(u0, *o0);
    disc_.to_overlap(u1, *o1);
  }
  using HostView = decltype(u0.getLocalViewHost(Tpetra::Access::ReadOnly));
  HostView v0, v1;
  if (deformable) {
    v0 = o0->getLocalViewHost(Tpetra::Access::ReadOnly);
    v1 = o1->getLocalViewHost(Tpetra::Access::ReadOnly);
  }
  const auto& overlap = *disc_.overlap_map();
  std::vector<std::vector<int>> need(np), sends(nr);
  for (int p = 0; p < np; ++p) {
    const Pair& pr = pairs_[p];
    for (int f = 0; f < (pr.rigid_master ? static_cast<int>(pr.facets.size()) : 0); ++f) {
      double box[6] = {kHuge, kHuge, kHuge, -kHuge, -kHuge, -kHuge};
      for (int a : pr.facets[f]) grow(box, &m.rigid_X[3 * (a - m.num_nodes())]);
      if (boxes_meet(box, mine[p].data())) need[p].push_back(f);
    }
    for (int f : held_[p]) {
      double box[6] = {kHuge, kHuge, kHuge, -kHuge, -kHuge, -kHuge};
      for (int a : pr.facets[f]) {
        const double* Xa = m.x(a);
        for (const auto* v : {&v0, &v1}) {
          double x[3];
          for (int c = 0; c < 3; ++c)
            x[c] = Xa[c] + (*v)(overlap.getLocalElement(fem::dof_gid(a, c)), 0);
          grow(box, x);
        }
      }
      for (int r = 0; r < nr; ++r)
        if (boxes_meet(box, &all[6 * (r * np + p)])) sends[r].insert(sends[r].end(), {p, f});
    }
  }
  const auto got = exchange_ints(*disc_.comm(), sends);
  for (std::size_t k = 0; k + 1 < got.size(); k += 2) need[got[k]].push_back(got[k + 1]);
  return need;
}

// §3 chains: an active entry whose slave is one of my contact nodes adds its facet (its rows of
// P, and for frictionless its tangents at n+1/2, enter mine). My contact nodes are my slaves
// (sorted per pair) and the nodes of the facets in reach (a sorted list that grows with them).
void ContactNodes::close_chains(std::vector<std::vector<int>>& need,
                                const ActiveIndex& index) const {
  for (auto& v : need) sort_unique(v);
  if (index.by_slave.empty()) return;
  std::vector<int> facet_nodes;
  for (std::size_t p = 0; p < need.size(); ++p)
    for (int f : need[p])
      for (int a : pairs_[p].facets[f]) facet_nodes.push_back(a);
  sort_unique(facet_nodes);
  const auto is_node = [&](int s) {
    if (std::binary_search(facet_nodes.begin(), facet_nodes.end(), s)) return true;
    for (const auto& mine : my_slaves_)
      if (std::binary_search(mine.begin(), mine.end(), s)) return true;
    return false;
  };
  const auto insert = [](std::vector<int>& v, int x) {
    const auto it = std::lower_bound(v.begin(), v.end(), x);
    if (it != v.end() && *it == x) return false;
    v.insert(it, x);
    return true;
  };
  for (bool changed = true; changed;) {
    changed = false;
    for (const auto& [s, a] : index.by_slave)
      if (is_node(s) && insert(need[a.pair], a.facet)) {
        for (int n : pairs_[a.pair].facets[a.facet]) insert(facet_nodes, n);
        changed = true;
      }
  }
}

void ContactNodes::select(const Sweep& from, const Vector& u1, const ActiveIndex& index) {
  static auto timer = Teuchos::TimeMonitor::getNewTimer("emcontact: contact: node selection");
  Teuchos::TimeMonitor tm(*timer);
  in_reach_ = facets_in_reach(from, u1);
  auto need = in_reach_;
  close_chains(need, index);
  select_closed(std::move(need));
}

void ContactNodes::reselect(const ActiveIndex& index) {
  static auto timer = Teuchos::TimeMonitor::getNewTimer("emcontact: contact: node selection");
  Teuchos::TimeMonitor tm(*timer);
  if (in_reach_.size() != pairs_.size())
    throw Error("internal: ContactNodes::reselect before any select");
  auto need = in_reach_;
  close_chains(need, index);
  select_closed(std::move(need));
}

// Builds the contact nodes of the facets `need` unless every rank's are those of the last build.
void ContactNodes::select_closed(std::vector<std::vector<int>> need) {
  ++traffic_.selections;
  // the same facets on every rank: the nodes, their import and the local numbering stay
  int changed = need != selected_ ? 1 : 0, any = 0;
  Teuchos::reduceAll(*disc_.comm(), Teuchos::REDUCE_MAX, 1, &changed, &any);
  if (!any && import_) return;
  build(need);
  selected_ = std::move(need);
}

// The contact nodes: my slaves with their slave-surface neighbours, and the nodes of the
// facets in reach, in ascending global id (so the deformable ones, below num_nodes, first).
void ContactNodes::build(const std::vector<std::vector<int>>& need) {
  const auto& m = disc_.model();
  std::vector<int> facet_nodes;
  for (std::size_t p = 0; p < pairs_.size(); ++p)
    for (int f : need[p])
      for (int n : pairs_[p].facets[f]) facet_nodes.push_back(n);
  sort_unique(facet_nodes);
  gid_.clear();
  gid_.reserve(slave_side_.size() + facet_nodes.size());
  std::set_union(slave_side_.begin(), slave_side_.end(), facet_nodes.begin(), facet_nodes.end(),
                 std::back_inserter(gid_));
  deformable_ =
      static_cast<int>(std::lower_bound(gid_.begin(), gid_.end(), m.num_nodes()) - gid_.begin());
  // a dof of mine is read from the owned vector; only the others are imported (src_ < 0)
  const auto& owned = *disc_.owned_map();
  std::vector<GO> remote;
  X_ = Kokkos::View<double* [3], ExecSpace>("emc::contact_X", size());
  src_ = Kokkos::View<LO* [3], ExecSpace>("emc::contact_src", size());
  auto Xh = Kokkos::create_mirror_view(X_);
  auto sh = Kokkos::create_mirror_view(src_);
  for (int l = 0; l < size(); ++l)
    for (int c = 0; c < 3; ++c) {
      if (l >= deformable_) {
        Xh(l, c) = m.rigid_X[3 * (gid_[l] - m.num_nodes()) + c];
        continue;
      }
      Xh(l, c) = m.x(gid_[l])[c];
      const GO dof = fem::dof_gid(gid_[l], c);
      sh(l, c) = owned.getLocalElement(dof);
      if (sh(l, c) != Tpetra::Details::OrdinalTraits<LO>::invalid()) continue;
      sh(l, c) = -1 - static_cast<LO>(remote.size());
      remote.push_back(dof);
    }
  Kokkos::deep_copy(X_, Xh);
  Kokkos::deep_copy(src_, sh);
  const auto invalid = Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid();
  map_ = Teuchos::rcp(new Map(invalid, remote.data(), remote.size(), 0, disc_.comm()));
  import_ = Teuchos::rcp(new Import(disc_.owned_map(), map_));
  imports_ = map_->getGlobalNumElements() > 0;
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    LocalFacets& lf = facets_[p];
    const int nf = static_cast<int>(need[p].size());
    lf.nodes = Kokkos::View<int* [3], ExecSpace>("emc::local_facets", nf);
    lf.id = Kokkos::View<int*, ExecSpace>("emc::local_facet_ids", nf);
    auto nh = Kokkos::create_mirror_view(lf.nodes);
    auto ih = Kokkos::create_mirror_view(lf.id);
    lf.index.clear();
    for (int k = 0; k < nf; ++k) {
      ih(k) = need[p][k];
      lf.index[need[p][k]] = k;
      for (int a = 0; a < 3; ++a) nh(k, a) = local(pairs_[p].facets[need[p][k]][a]);
    }
    Kokkos::deep_copy(lf.nodes, nh);
    Kokkos::deep_copy(lf.id, ih);
    lf.rigid_grid.reset();
    if (pairs_[p].rigid_master)
      lf.rigid_grid = std::make_shared<const FacetGrid>(lf.nodes, X_, pairs_[p].dmax);
  }
  // slave_side_ is a subset of gid_, both ascending: one merge walk numbers it
  Kokkos::View<int*, ExecSpace> side_local(
      Kokkos::ViewAllocateWithoutInitializing("emc::side_local"), slave_side_.size());
  auto slh = Kokkos::create_mirror_view(side_local);
  for (std::size_t i = 0, l = 0; i < slave_side_.size(); ++i) {
    while (gid_[l] < slave_side_[i]) ++l;
    slh(i) = static_cast<int>(l);
  }
  Kokkos::deep_copy(side_local, slh);
  for (std::size_t p = 0; p < pairs_.size(); ++p) build_slaves(p, side_local);
  ++builds_;
  traffic_.nodes = size();
  traffic_.remote = static_cast<int>(remote.size() / 3);
}

// My slaves and their triangles in contact-node indices, through side_local (slave_side_ index
// -> contact-node index).
void ContactNodes::build_slaves(std::size_t p, Kokkos::View<const int*, ExecSpace> side_local) {
  const LocalSlaves& g = slave_sides_[p];
  LocalSlaves& ls = slaves_[p];
  ls.start = g.start;  // the same triangles around each slave
  ls.node = Kokkos::View<int*, ExecSpace>(
      Kokkos::ViewAllocateWithoutInitializing("emc::local_slaves"), g.node.extent(0));
  ls.tri = Kokkos::View<int* [3], ExecSpace>(
      Kokkos::ViewAllocateWithoutInitializing("emc::local_slave_tris"), g.tri.extent(0));
  gather_ids(side_local, g.node, ls.node);
  gather_ids(side_local, Kokkos::View<const int*, ExecSpace>(g.tri.data(), 3 * g.tri.extent(0)),
             Kokkos::View<int*, ExecSpace>(ls.tri.data(), 3 * ls.tri.extent(0)));
}

// Not initialized: every caller writes every entry (positions, midpoint).
Positions ContactNodes::new_positions(const char* label) const {
  return Positions(Kokkos::ViewAllocateWithoutInitializing(label), size());
}

// docs/THEORY.md §8: x(l) = X(l) + u(l) over the contact nodes l.
void fill(const NodePositions& p, Positions x) {
  Kokkos::parallel_for(
      "emcontact::contact::positions", Kokkos::RangePolicy<ExecSpace>(0, p.size()),
      KOKKOS_LAMBDA(const int l) {
        for (int c = 0; c < 3; ++c) x(l, c) = p(l, c);
      });
}

NodePositions ContactNodes::lazy_positions(const Vector& u) const {
  NodePositions p{X_, src_, deformable_, u.getLocalViewDevice(Tpetra::Access::ReadOnly), {}};
  if (!imports_) return p;  // no rank has remote contact nodes (one rank): nothing to import
  Vector um(map_);          // the remote dofs; collective
  um.doImport(u, *import_, Tpetra::INSERT);
  ++traffic_.imports;
  traffic_.bytes_imported += static_cast<long long>(map_->getNodeNumElements()) * sizeof(double);
  p.r = um.getLocalViewDevice(Tpetra::Access::ReadOnly);  // a View: it keeps the values alive
  return p;
}

void ContactNodes::positions(const Vector& u, Positions x) const {
  fill(lazy_positions(u), x);
}

Positions::HostMirror ContactNodes::host_positions(const Vector& u) const {
  Positions x = new_positions("emc::contact_x");
  positions(u, x);
  return Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), x);
}

}  // namespace emc::contact
