#include "emcontact/contact/contact.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "emcontact/contact/active_kernels.hpp"
#include "emcontact/contact/detection.hpp"
#include "emcontact/contact/law.hpp"
#include "emcontact/contact/search.hpp"
#include "emcontact/error.hpp"
#include "emcontact/parallel.hpp"
#include "kernels/facet.hpp"

namespace emc::contact {

Contact::Contact(const fem::Discretization& disc, std::vector<Pair> pairs)
    : disc_(disc), pairs_(std::move(pairs)), nodes_(disc, pairs_) {
  std::map<Kind, std::shared_ptr<const Law>> by_kind;
  for (const auto& p : pairs_) {
    auto& law = by_kind[p.kind];
    if (!law) {
      law = make_law(p.kind);
      distinct_laws_.push_back(law.get());
    }
    laws_.push_back(law);
  }
  // the laws act in a fixed order (full stick first: a closing stick master moves before the
  // frictionless slaves on it are projected, §7.2)
  std::sort(distinct_laws_.begin(), distinct_laws_.end(),
            [](const Law* a, const Law* b) { return a->kind() < b->kind(); });
  for (const auto& p : pairs_)
    for (const auto& f : p.facets)
      for (int n : f)
        if (n < disc.model().num_nodes()) master_nodes_.push_back(n);
  std::sort(master_nodes_.begin(), master_nodes_.end());
  master_nodes_.erase(std::unique(master_nodes_.begin(), master_nodes_.end()), master_nodes_.end());
}

Contact::~Contact() = default;

int Contact::global_count(int local) const {
  int g = 0;
  Teuchos::reduceAll(*disc_.comm(), Teuchos::REDUCE_SUM, 1, &local, &g);
  return g;
}

Positions Contact::positions(const Vector& u) const {
  Positions x = nodes_.new_positions("emc::contact_x");
  nodes_.positions(u, x);
  return x;
}

Refs Contact::refs(const std::vector<Active>& active) const {
  Refs r("emc::active_refs", active.size());
  auto h = Kokkos::create_mirror_view(r);
  const auto& map = *disc_.owned_map();
  for (std::size_t k = 0; k < active.size(); ++k) {
    const Active& a = active[k];
    const Pair& pr = pairs_[a.pair];
    ActiveRef& e = h(k);
    e.s = nodes_.local(a.slave);
    for (int i = 0; i < 3; ++i) {
      e.m[i] = nodes_.local(pr.facets[a.facet][i]);
      e.dof[i] = map.getLocalElement(fem::dof_gid(a.slave, i));
    }
    if (e.s < 0 || e.m[0] < 0 || e.m[1] < 0 || e.m[2] < 0)
      throw Error("internal: an active entry's nodes are not among the rank's contact nodes");
    e.xi[0] = a.xi[0];
    e.xi[1] = a.xi[1];
    e.edge = pr.edge;
    e.closes = closes(a);
    e.frictionless = slides(pr, a);
    e.mu = pr.mu;
    for (int i = 0; i < 3; ++i) e.dir[i] = a.dir[i];
  }
  Kokkos::deep_copy(r, h);
  return r;
}

std::vector<double> Contact::normal_forces(const Vector& g, Positions x0, Positions x1,
                                           const std::vector<Active>& active) const {
  Values fN("emc::normal_forces", active.size());
  contact::normal_forces(refs(active), x0, x1, g.getLocalViewDevice(Tpetra::Access::ReadOnly), fN);
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), fN);
  return std::vector<double>(h.data(), h.data() + h.extent(0));
}

void Contact::gap_range(Positions x1, const std::vector<Active>& active, double& lo,
                        double& hi) const {
  double l, h;
  contact::gap_range(refs(active), x1, l, h);
  Teuchos::reduceAll(*disc_.comm(), Teuchos::REDUCE_MIN, 1, &l, &lo);
  Teuchos::reduceAll(*disc_.comm(), Teuchos::REDUCE_MAX, 1, &h, &hi);
}

std::vector<std::array<double, 2>> Contact::facet_point_distances(
    Positions x, const std::vector<Active>& active) const {
  Kokkos::View<double* [2], ExecSpace> d("emc::facet_point_distances", active.size());
  contact::facet_point_distances(refs(active), x, d);
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), d);
  std::vector<std::array<double, 2>> out(active.size());
  for (std::size_t k = 0; k < active.size(); ++k) out[k] = {h(k, 0), h(k, 1)};
  return out;
}

// docs/THEORY.md §7.2: an active node behind its facet keeps its gap (closing it would push it
// out: energy from nowhere); every other node of a closing pair is closed in the next step.
void Contact::mark_kept_gaps(std::vector<Active>& active, Positions x1) const {
  Kokkos::View<int*, ExecSpace> behind("emc::behind", active.size());
  behind_facets(refs(active), x1, behind);
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), behind);
  for (std::size_t k = 0; k < active.size(); ++k)
    if (pairs_[active[k].pair].close_gap) active[k].keep_gap = h(k) != 0;
}

namespace {

/// The entries of `send` (packed with their slip) of every rank, by slave; `mine` kept apart.
ActiveIndex index_of(const Comm& comm, const std::vector<Active>& mine,
                     const std::vector<Active>& send) {
  std::vector<double> packed;
  for (const auto& a : send) {
    pack(a, packed);
    packed.push_back(double(a.slip));  // docs/THEORY.md §11: stick or slip travels with the entry
  }
  const auto all = allgather(comm, packed);
  ActiveIndex index;
  std::vector<int> own;
  for (const auto& a : mine) own.push_back(a.slave);
  std::sort(own.begin(), own.end());
  constexpr std::size_t stride = kPackedActive + 1;
  for (std::size_t k = 0; k + stride <= all.size(); k += stride) {
    Active a = unpack(&all[k]);
    a.slip = all[k + kPackedActive] != 0;
    index.by_slave.emplace(a.slave, a);
    if (!std::binary_search(own.begin(), own.end(), a.slave)) index.ghosts.push_back(a);
  }
  for (const auto& a : mine) {  // (slave, pair, facet, xi, slip): what travels
    Active b;
    b.slave = a.slave;
    b.pair = a.pair;
    b.facet = a.facet;
    b.xi[0] = a.xi[0];
    b.xi[1] = a.xi[1];
    b.slip = a.slip;
    index.by_slave.emplace(b.slave, b);
  }
  std::sort(index.ghosts.begin(), index.ghosts.end());
  return index;
}

}  // namespace

ActiveIndex Contact::gather(const std::vector<Active>& mine) const {
  std::vector<Active> links;
  for (const auto& a : mine)
    if (master_node(a.slave)) links.push_back(a);
  return index_of(*disc_.comm(), mine, links);
}

ActiveIndex Contact::gather_all(const std::vector<Active>& mine) const {
  return index_of(*disc_.comm(), mine, mine);
}

// docs/THEORY.md §3.5: rows of P compose along chains, P = P_1 P_2 ...
void Contact::expand_node(int node, int c, double w, const ActiveIndex& index,
                          const Positions::HostMirror& xh, std::vector<int>& path,
                          linalg::PRow& r) const {
  const auto& m = disc_.model();
  if (node >= m.num_nodes() || m.is_fixed(node)) return;  // rigid or fixed: no column
  auto it = index.by_slave.find(node);
  const bool on_path = std::find(path.begin(), path.end(), node) != path.end();
  if (it == index.by_slave.end() || on_path) {
    if (on_path) ++index.cycles;
    r.cols.push_back(fem::dof_gid(node, c));
    r.weights.push_back(w);
    return;
  }
  const Active& a = it->second;
  const auto& f = pairs_[a.pair].facets[a.facet];
  double N[3];
  kernels::facet_shape(a.xi, N);
  path.push_back(node);
  for (int i = 0; i < 3; ++i) expand_node(f[i], c, w * N[i], index, xh, path, r);
  path.pop_back();
  if (slides(pairs_[a.pair], a) && xh.extent(0) > 0) {  // + T dq at n+1/2 (§5)
    double xm[3][3];
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) xm[j][i] = xh(nodes_.local(f[j]), i);
    const kernels::Facet fh = kernels::facet(xm);
    r.cols.push_back(fem::dof_gid(node, 0));
    r.weights.push_back(w * fh.t1[c]);
    r.cols.push_back(fem::dof_gid(node, 1));
    r.weights.push_back(w * fh.t2[c]);
  }
}

// A_ii of owned dof i, read from its row (on the host; dummy_betas is the kernel for many).
double diagonal_entry(const Matrix& A, GO i) {
  const LO row = A.getRowMap()->getLocalElement(i);
  const LO col = A.getColMap()->getLocalElement(i);
  typename Matrix::local_inds_host_view_type cols;
  typename Matrix::values_host_view_type vals;
  A.getLocalRowView(row, cols, vals);
  for (std::size_t j = 0; j < cols.extent(0); ++j)
    if (cols(j) == col) return vals(j);
  return 0.0;
}

std::vector<std::pair<GO, double>> Contact::dummy_values(const Matrix& A,
                                                         const std::vector<GO>& dummies) const {
  const std::size_t n = dummies.size() / 3;  // a slave's three dofs in a row
  if (n == 0) return {};
  Kokkos::View<GO*, ExecSpace> dof(Kokkos::ViewAllocateWithoutInitializing("emc::dummies"), 3 * n);
  Kokkos::deep_copy(dof, Kokkos::View<const GO*, Kokkos::HostSpace>(dummies.data(), 3 * n));
  Kokkos::View<double*, ExecSpace> beta(Kokkos::ViewAllocateWithoutInitializing("emc::beta"), n);
  dummy_betas(A, dof, beta);
  const auto bh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), beta);
  std::vector<std::pair<GO, double>> out;
  for (std::size_t k = 0; k < n; ++k)
    for (int c = 0; c < 3; ++c) out.emplace_back(dummies[3 * k + c], bh(k));
  return out;
}

}  // namespace emc::contact
