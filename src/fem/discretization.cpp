#include "emcontact/fem/discretization.hpp"

#include <Kokkos_DualView.hpp>
#include <algorithm>

#include "emcontact/error.hpp"
#include "emcontact/parallel.hpp"
#include "emcontact/views.hpp"
#include "kernels/svk.hpp"
#include "kernels/tet4.hpp"

namespace emc::fem {

using Teuchos::RCP;
using Teuchos::rcp;

Discretization::Discretization(const Model& model, RCP<const Comm> comm)
    : Discretization(model, partition(model, comm), comm) {}

Discretization::Discretization(const Model& model, Partition part, RCP<const Comm> comm)
    : model_(model), comm_(comm), part_(std::move(part)) {
  build_maps();
  on_every_rank(*comm_, [&] { build_element_data(); });  // a refused tet stops every rank
  build_moved_mass();
  build_graph();
  finish_group(svk_);
  finish_group(hyper_);
}

void Discretization::build_maps() {
  const auto invalid = Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid();
  std::vector<GO> owned, overlap;
  owned.reserve(3 * part_.owned_nodes.size());
  for (int n : part_.owned_nodes)
    for (int c = 0; c < 3; ++c) owned.push_back(dof_gid(n, c));
  overlap = owned;  // owned dofs first, in the same order (FECrsGraph requires it)
  for (int n : part_.shared_nodes)
    for (int c = 0; c < 3; ++c) overlap.push_back(dof_gid(n, c));
  owned_ = rcp(new Map(invalid, Teuchos::ArrayView<const GO>(owned), 0, comm_));
  overlap_ = rcp(new Map(invalid, Teuchos::ArrayView<const GO>(overlap), 0, comm_));
  std::vector<GO> tets;
  tets.reserve(part_.my_tets.size());
  for (int e : part_.my_tets) tets.push_back(model_.tet_id(e));
  elements_ = rcp(new Map(invalid, Teuchos::ArrayView<const GO>(tets), 0, comm_));
  importer_ = rcp(new Import(owned_, overlap_));
  exporter_ = rcp(new Export(overlap_, owned_));
}

Teuchos::RCP<Vector> Discretization::reference_positions() const {
  auto X = rcp(new Vector(owned_));
  auto x = X->getLocalViewHost(Tpetra::Access::OverwriteAll);
  for (size_t i = 0; i < x.extent(0); ++i) {
    const GO g = owned_->getGlobalElement(static_cast<LO>(i));
    x(i, 0) = model_.x(static_cast<int>(g / 3))[g % 3];
  }
  return X;
}

namespace {

/// The group of my elements `local` (indices into part.my_tets), each with the kernel material
/// material(body); throws on a tet of non-positive volume.
template <class Material, class Of>
void fill_group(const Model& model, const Partition& part, const Map& overlap,
                std::vector<int> local, const Of& material, ElementGroup<Material>& g) {
  const int ne = static_cast<int>(local.size());
  g.tets = kernels::TetElements<MemSpace, Material>(ne);
  const kernels::TetElementsMirror<MemSpace, Material> h(g.tets);
  for (int k = 0; k < ne; ++k) {
    const int e = part.my_tets[local[k]];
    double x[4][3], gr[4][3] = {};  // zero where tet_gradients leaves it (a flat tet, refused)
    h.massless(k) = massless_mask(model, e);
    for (int a = 0; a < 4; ++a) {
      const int n = model.tets[4 * e + a];
      h.nodes(k, a) = overlap.getLocalElement(dof_gid(n, 0)) / 3;
      const double* Xn = model.x(n);
      for (int i = 0; i < 3; ++i) x[a][i] = h.X(k, a, i) = Xn[i];
    }
    h.Ve(k) = kernels::tet_gradients(x, gr);
    if (!(h.Ve(k) > 0))
      throw InputError("mesh: element " + std::to_string(model.tet_id(e) + 1) + " has volume " +
                       std::to_string(h.Ve(k)) + "; every tetrahedron must have positive volume");
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) h.G(k, a, i) = gr[a][i];
    const Body& b = model.bodies[model.body_of_tet[e]];
    h.material(k) = material(b);
    h.rho(k) = b.density;
  }
  h.copy_to(g.tets);
  g.local = std::move(local);
  g.local_view = to_view("emc::group_local", g.local);
}

}  // namespace

void Discretization::build_element_data() {
  std::vector<int> svk, hyper;
  for (std::size_t k = 0; k < part_.my_tets.size(); ++k) {
    const Body& b = model_.bodies[model_.body_of_tet[part_.my_tets[k]]];
    (b.model == MaterialModel::svk ? svk : hyper).push_back(static_cast<int>(k));
  }
  fill_group(
      model_, part_, *overlap_, std::move(svk),
      [](const Body& b) { return svk_material(b.material()); }, svk_);
  fill_group(
      model_, part_, *overlap_, std::move(hyper),
      [](const Body& b) { return hyper_material(b.material()); }, hyper_);
}

template <class Material>
void Discretization::finish_group(ElementGroup<Material>& g) {
  const int ne = g.size();
  const auto lid = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), g.tets.nodes);
  g.columns = decltype(g.columns)("emc::tet_columns", ne);
  auto col = Kokkos::create_mirror_view(g.columns);
  auto colmap = graph_->getColMap();
  for (int k = 0; k < ne; ++k)
    for (int a = 0; a < 4; ++a) {
      const GO node = overlap_->getGlobalElement(3 * lid(k, a)) / 3;
      for (int c = 0; c < 3; ++c) col(k, 3 * a + c) = colmap->getLocalElement(dof_gid(node, c));
    }
  Kokkos::deep_copy(g.columns, col);
  g.colouring = kernels::TetColouring<MemSpace>(
      ExecSpace(), g.tets.nodes, static_cast<int>(overlap_->getNodeNumElements() / 3),
      assembly_chunk);
}

void Discretization::build_graph() {
  const int ne = static_cast<int>(part_.my_tets.size());
  const int nn = static_cast<int>(overlap_->getNodeNumElements() / 3);
  // node adjacency from my elements: sorted unique (row, col) node pairs
  std::vector<std::pair<int, int>> pairs;
  pairs.reserve(16 * static_cast<std::size_t>(ne));
  for_each_group([&](const auto& g) {
    const auto lid = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), g.tets.nodes);
    for (int k = 0; k < g.size(); ++k)
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) pairs.emplace_back(lid(k, a), lid(k, b));
  });
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  std::vector<std::size_t> start(nn + 1, 0);
  for (const auto& p : pairs) ++start[p.first + 1];
  for (int n = 0; n < nn; ++n) start[n + 1] += start[n];

  // docs/THEORY.md §6.8: the moved mass's columns of my owned rows, beyond the element graph's
  const auto moved_columns = [&](int n) -> const std::vector<int>* {
    if (!moved_) return nullptr;
    const auto it = moved_->columns.find(static_cast<int>(overlap_->getGlobalElement(3 * n) / 3));
    return it == moved_->columns.end() ? nullptr : &it->second;
  };
  Kokkos::DualView<std::size_t*, Node::device_type> count("emc::row_count", 3 * nn);
  for (int n = 0; n < nn; ++n) {
    const auto* extra = moved_columns(n);
    const std::size_t cols = start[n + 1] - start[n] + (extra ? extra->size() : 0);
    for (int c = 0; c < 3; ++c) count.h_view(3 * n + c) = 3 * cols;
  }
  count.modify_host();
  count.sync_device();
  graph_ = rcp(new FEGraph(owned_, overlap_, count));
  graph_->beginAssembly();
  std::vector<GO> cols;
  for (int n = 0; n < nn; ++n) {
    cols.clear();
    for (std::size_t k = start[n]; k < start[n + 1]; ++k) {
      const GO node = overlap_->getGlobalElement(3 * pairs[k].second) / 3;
      for (int c = 0; c < 3; ++c) cols.push_back(dof_gid(node, c));
    }
    if (const auto* extra = moved_columns(n))
      for (int m : *extra)
        for (int c = 0; c < 3; ++c) cols.push_back(dof_gid(m, c));
    std::sort(cols.begin(), cols.end());
    cols.erase(std::unique(cols.begin(), cols.end()), cols.end());
    const GO node = overlap_->getGlobalElement(3 * n) / 3;
    for (int c = 0; c < 3; ++c)
      graph_->insertGlobalIndices(dof_gid(node, c), Teuchos::ArrayView<const GO>(cols));
  }
  graph_->endAssembly();
}

void Discretization::to_overlap(const Vector& owned, Vector& overlap) const {
  overlap.doImport(owned, *importer_, Tpetra::INSERT);
}

RCP<Vector> Discretization::new_overlap_vector() const {
  return rcp(new Vector(overlap_));
}

}  // namespace emc::fem
