// The mass matrix: the consistent mass of docs/THEORY.md §1.3 applied to a vector, element by
// element (matrix-free: M is constant), and the moved mass of docs/THEORY.md §6.8 (massless slave
// nodes): each massless node's affine fit over massive nodes of its body, and the mass of the
// elements with massless nodes, M' = sum_e T_e^T M_e T_e, as a matrix on the owned rows.
#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <numeric>
#include <vector>

#include "emcontact/error.hpp"
#include "emcontact/fem/discretization.hpp"
#include "emcontact/views.hpp"
#include "kernels/mass_tet4.hpp"
#include "kernels/tet4.hpp"

namespace emc::fem {
namespace {

/// docs/THEORY.md §6.8: an affine fit is taken from the massive nodes within r edges of the
/// massless node, r the smallest of 1 .. kFirstRings whose fit has a Lebesgue constant
/// sum_j |w_j| of at most kLebesgue (an extrapolation over two layers of nodes behind a flat face
/// has 3), else the one of them with the smallest constant; where none of them spans 3D, the
/// first larger r up to kMaxRing that does.
constexpr int kFirstRings = 3;
constexpr int kMaxRing = 8;
constexpr double kLebesgue = 4.0;

/// Node adjacency (sharing a tet), CSR over all nodes.
void adjacency(const Model& m, std::vector<int>& start, std::vector<int>& adj) {
  std::vector<std::vector<int>> nb(m.num_nodes());
  for (int e = 0; e < m.num_tets(); ++e)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        if (a != b) nb[m.tets[4 * e + a]].push_back(m.tets[4 * e + b]);
  start.assign(1, 0);
  adj.clear();
  for (auto& v : nb) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
    adj.insert(adj.end(), v.begin(), v.end());
    start.push_back(static_cast<int>(adj.size()));
  }
}

/// Solves the symmetric positive definite 4x4 system G z = b by Cholesky; false when a pivot is
/// below 1e-10 of G's first diagonal entry (the points do not span 3D).
bool solve4(const double G[4][4], const double b[4], double z[4]) {
  double L[4][4] = {};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j <= i; ++j) {
      double s = G[i][j];
      for (int k = 0; k < j; ++k) s -= L[i][k] * L[j][k];
      if (i == j) {
        if (!(s > 1e-10 * G[0][0])) return false;
        L[i][i] = std::sqrt(s);
      } else {
        L[i][j] = s / L[j][j];
      }
    }
  double y[4];
  for (int i = 0; i < 4; ++i) {
    double s = b[i];
    for (int k = 0; k < i; ++k) s -= L[i][k] * y[k];
    y[i] = s / L[i][i];
  }
  for (int i = 3; i >= 0; --i) {
    double s = y[i];
    for (int k = i + 1; k < 4; ++k) s -= L[k][i] * z[k];
    z[i] = s / L[i][i];
  }
  return true;
}

/// The minimum-norm weights with sum_j w_j (1, X_j) = (1, X_c) over the points `pts` (the value
/// at X_c of their least-squares affine fit), refined once against round-off; returns
/// sum_j |w_j|, or infinity when the points do not span 3D.
double affine_fit(const Model& m, int c, const std::vector<int>& pts, std::vector<double>& w) {
  const double inf = std::numeric_limits<double>::infinity();
  const std::size_t k = pts.size();
  if (k < 4) return inf;
  const double* xc = m.x(c);
  double R = 0;
  for (int j : pts) {
    const double* xj = m.x(j);
    R = std::max(R, std::hypot(xj[0] - xc[0], xj[1] - xc[1], xj[2] - xc[2]));
  }
  std::vector<std::array<double, 4>> a(k);
  double G[4][4] = {};
  for (std::size_t j = 0; j < k; ++j) {
    a[j][0] = 1;
    const double* xj = m.x(pts[j]);
    for (int i = 0; i < 3; ++i) a[j][i + 1] = (xj[i] - xc[i]) / R;
    for (int p = 0; p < 4; ++p)
      for (int q = 0; q < 4; ++q) G[p][q] += a[j][p] * a[j][q];
  }
  double b[4] = {1, 0, 0, 0}, z[4];
  if (!solve4(G, b, z)) return inf;
  w.assign(k, 0.0);
  for (std::size_t j = 0; j < k; ++j)
    w[j] = a[j][0] * z[0] + a[j][1] * z[1] + a[j][2] * z[2] + a[j][3] * z[3];
  double r[4] = {1, 0, 0, 0}, dz[4];  // one step of refinement: r = b - sum_j w_j a_j
  for (std::size_t j = 0; j < k; ++j)
    for (int p = 0; p < 4; ++p) r[p] -= w[j] * a[j][p];
  if (solve4(G, r, dz))
    for (std::size_t j = 0; j < k; ++j)
      w[j] += a[j][0] * dz[0] + a[j][1] * dz[1] + a[j][2] * dz[2] + a[j][3] * dz[3];
  double lebesgue = 0;
  for (double x : w) lebesgue += std::fabs(x);
  return lebesgue;
}

/// Breadth-first rings of nodes around a node (through any nodes): next() returns the massive
/// nodes one edge further out than the last ring (empty once the body is exhausted).
class Rings {
 public:
  Rings(const Model& m, const std::vector<int>& start, const std::vector<int>& adj, int c)
      : m_(m), start_(start), adj_(adj), front_{c}, seen_{c} {}
  std::vector<int> next() {
    std::vector<int> reach;
    for (int n : front_)
      for (int k = start_[n]; k < start_[n + 1]; ++k) reach.push_back(adj_[k]);
    std::sort(reach.begin(), reach.end());
    reach.erase(std::unique(reach.begin(), reach.end()), reach.end());
    std::vector<int> fresh, merged, massive;
    std::set_difference(reach.begin(), reach.end(), seen_.begin(), seen_.end(),
                        std::back_inserter(fresh));
    std::merge(seen_.begin(), seen_.end(), fresh.begin(), fresh.end(), std::back_inserter(merged));
    seen_ = std::move(merged);
    for (int n : fresh)
      if (!m_.is_massless(n)) massive.push_back(n);
    front_ = std::move(fresh);
    return massive;
  }
  bool exhausted() const { return front_.empty(); }

 private:
  const Model& m_;
  const std::vector<int>& start_;
  const std::vector<int>& adj_;
  std::vector<int> front_, seen_;
};

}  // namespace

int MasslessFit::find(int n) const {
  const auto it = std::lower_bound(node.begin(), node.end(), n);
  return it != node.end() && *it == n ? static_cast<int>(it - node.begin()) : -1;
}

int fit_massless_nodes(Model& m) {
  MasslessFit fit;
  fit.start.push_back(0);
  if (m.massless.empty()) {
    m.massless_fit = fit;
    return -1;
  }
  std::vector<int> start, adj;
  adjacency(m, start, adj);
  for (int c = 0; c < m.num_nodes(); ++c) {
    if (!m.is_massless(c)) continue;
    Rings rings(m, start, adj, c);
    std::vector<int> pts, best_pts;
    std::vector<double> w, best_w;
    double best = std::numeric_limits<double>::infinity();
    for (int r = 1; r <= kMaxRing && !rings.exhausted(); ++r) {
      const auto ring = rings.next();
      if (ring.empty()) continue;
      pts.insert(pts.end(), ring.begin(), ring.end());
      const double lebesgue = affine_fit(m, c, pts, w);
      if (lebesgue < best) {
        best = lebesgue;
        best_pts = pts;
        best_w = w;
      }
      if (best <= kLebesgue || (r >= kFirstRings && std::isfinite(best))) break;
    }
    if (!std::isfinite(best)) return c;
    std::vector<std::size_t> order(best_pts.size());
    for (std::size_t j = 0; j < order.size(); ++j) order[j] = j;
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return best_pts[a] < best_pts[b]; });
    fit.node.push_back(c);
    for (std::size_t j : order) {
      fit.support.push_back(best_pts[j]);
      fit.weight.push_back(best_w[j]);
    }
    fit.start.push_back(static_cast<int>(fit.support.size()));
  }
  m.massless_fit = std::move(fit);
  return -1;
}

void moved_element_mass(const Model& m, int e, std::vector<int>& nodes, std::vector<double>& M) {
  const MasslessFit& fit = m.massless_fit;
  nodes.clear();
  int row[4];
  for (int a = 0; a < 4; ++a) {
    const int n = m.tets[4 * e + a];
    row[a] = fit.find(n);
    if (row[a] < 0)
      nodes.push_back(n);
    else
      nodes.insert(nodes.end(), fit.support.begin() + fit.start[row[a]],
                   fit.support.begin() + fit.start[row[a] + 1]);
  }
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  const int K = static_cast<int>(nodes.size());
  const auto col = [&](int n) {
    return static_cast<int>(std::lower_bound(nodes.begin(), nodes.end(), n) - nodes.begin());
  };
  std::vector<double> W(4 * static_cast<std::size_t>(K), 0.0);
  for (int a = 0; a < 4; ++a) {
    if (row[a] < 0) {
      W[a * K + col(m.tets[4 * e + a])] = 1.0;
      continue;
    }
    for (int k = fit.start[row[a]]; k < fit.start[row[a] + 1]; ++k)
      W[a * K + col(fit.support[k])] += fit.weight[k];
  }
  double x[4][3];
  for (int a = 0; a < 4; ++a)
    for (int i = 0; i < 3; ++i) x[a][i] = m.x(m.tets[4 * e + a])[i];
  M.assign(static_cast<std::size_t>(K) * K, 0.0);
  kernels::moved_mass(m.bodies[m.body_of_tet[e]].density, kernels::tet_volume(x), W.data(), K,
                      M.data());
}

std::vector<double> mass_row_sums(const Model& m) {
  std::vector<double> rows(m.num_nodes(), 0.0);
  std::vector<int> nodes;
  std::vector<double> M;
  for (int e = 0; e < m.owned_tets; ++e) {
    if (massless_mask(m, e)) {
      moved_element_mass(m, e, nodes, M);
      const std::size_t K = nodes.size();
      for (std::size_t j = 0; j < K; ++j)
        for (std::size_t k = 0; k < K; ++k) rows[nodes[j]] += M[j * K + k];
      continue;
    }
    double x[4][3];
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) x[a][i] = m.x(m.tets[4 * e + a])[i];
    const double quarter = 0.25 * m.bodies[m.body_of_tet[e]].density * kernels::tet_volume(x);
    for (int a = 0; a < 4; ++a) rows[m.tets[4 * e + a]] += quarter;
  }
  return rows;
}

// docs/THEORY.md §6.8: M' of the elements with massless nodes, summed over them in ascending
// element order (the same sums on any number of ranks), on the rows of my owned nodes.
void Discretization::build_moved_mass() {
  if (model_.massless.empty()) return;
  const int me = comm_->getRank();
  std::map<int, std::map<int, double>> rows;  // node rows -> node columns -> M'
  std::vector<int> nodes;
  std::vector<double> M;
  std::vector<int> order(model_.num_tets());  // the held tets by id (own and ghosts interleave)
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return model_.tet_id(a) < model_.tet_id(b); });
  for (int e : order) {
    if (!massless_mask(model_, e)) continue;
    moved_element_mass(model_, e, nodes, M);
    const std::size_t K = nodes.size();
    for (std::size_t j = 0; j < K; ++j) {
      if (part_.owner(model_, nodes[j]) != me) continue;
      auto& row = rows[nodes[j]];
      for (std::size_t k = 0; k < K; ++k) row[nodes[k]] += M[j * K + k];
    }
  }
  moved_ = Teuchos::rcp(new MovedMass);
  Teuchos::Array<std::size_t> count(owned_->getNodeNumElements(), 0);
  for (const auto& r : rows) {
    moved_->columns[r.first] = {};
    for (const auto& c : r.second) moved_->columns[r.first].push_back(c.first);
    for (int i = 0; i < 3; ++i)
      count[owned_->getLocalElement(dof_gid(r.first, i))] = r.second.size();
  }
  moved_->M = Teuchos::rcp(new Matrix(owned_, count()));
  moved_->absM = Teuchos::rcp(new Matrix(owned_, count()));
  std::vector<GO> cols;
  std::vector<double> vals, abs_vals;
  for (const auto& r : rows)
    for (int i = 0; i < 3; ++i) {
      cols.clear();
      vals.clear();
      abs_vals.clear();
      for (const auto& c : r.second) {
        cols.push_back(dof_gid(c.first, i));
        vals.push_back(c.second);
        abs_vals.push_back(std::fabs(c.second));
      }
      const GO row = dof_gid(r.first, i);
      moved_->M->insertGlobalValues(row, Teuchos::ArrayView<const GO>(cols),
                                    Teuchos::ArrayView<const double>(vals));
      moved_->absM->insertGlobalValues(row, Teuchos::ArrayView<const GO>(cols),
                                       Teuchos::ArrayView<const double>(abs_vals));
    }
  moved_->M->fillComplete(owned_, owned_);
  moved_->absM->fillComplete(owned_, owned_);
  moved_->row_sums = Teuchos::rcp(new Vector(owned_));
  Vector ones(owned_);
  ones.putScalar(1.0);
  moved_->M->apply(ones, *moved_->row_sums);
}

// The moved mass's entries, times c, added to the owned rows of the Newton matrix's owned+shared
// values (before the FE matrix exports its shared rows); the positions are found once per graph.
void Discretization::add_moved_mass(const FEMatrix::local_matrix_device_type& lcl, double c) const {
  const auto lM = moved_->M->getLocalMatrixDevice();
  if (moved_->offsets.extent(0) != lM.values.extent(0)) {
    const auto hM = moved_->M->getLocalMatrixHost();
    auto off =
        Kokkos::View<int*, Kokkos::HostSpace>("emc::moved_mass_offsets", hM.values.extent(0));
    auto rows = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), lcl.graph.row_map);
    auto ents = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), lcl.graph.entries);
    const auto colmap = graph_->getColMap();
    const auto mcols = moved_->M->getColMap();
    for (LO i = 0; i < static_cast<LO>(hM.numRows()); ++i)
      for (auto k = hM.graph.row_map(i); k < hM.graph.row_map(i + 1); ++k) {
        const LO col = colmap->getLocalElement(mcols->getGlobalElement(hM.graph.entries(k)));
        const auto* b = ents.data() + rows(i);
        const auto* e = ents.data() + rows(i + 1);
        const auto* it = std::lower_bound(b, e, col);
        if (col < 0 || it == e || *it != col)
          throw Error("internal: a moved mass entry is missing from the FE graph");
        off(k) = static_cast<int>(it - ents.data());
      }
    moved_->offsets = Kokkos::create_mirror_view_and_copy(ExecSpace(), off);
  }
  kernels::add_at(ExecSpace(), "emcontact::fem::moved_mass", lcl.values, moved_->offsets, c,
                  lM.values);
}

void Discretization::moved_mass_residual(const Vector& u0, const Vector& V0, const Vector& u1,
                                         double dt, Vector& r, Vector* scale) const {
  const double c2 = 2.0 / (dt * dt), c1 = 2.0 / dt;
  Vector w(owned_);
  w.update(c2, u1, -c2, u0, 0.0);
  if (scale) {  // |M'| (|c2 (u1 - u0)| + |c1 V0| + 1e-2 c2 |u1|): what cancellation in M' w
    Vector a(owned_), b(owned_);  // can leave, and the rounding of u1 through the inertia (§1.6)
    a.abs(w);
    b.abs(V0);
    a.update(c1, b, 1.0);
    b.abs(u1);
    a.update(1e-2 * c2, b, 1.0);
    moved_->absM->apply(a, *scale, Teuchos::NO_TRANS, 1.0, 1.0);
  }
  w.update(-c1, V0, 1.0);
  moved_->M->apply(w, r, Teuchos::NO_TRANS, 1.0, 1.0);
}

// docs/THEORY.md §1.9 with the moved mass: p = M' V on my owned rows gives their kinetic energy,
// L, J about the origin and the mass moment (row sums of M' times x = X + u).
void Discretization::add_moved_monitors(const Vector& u, const Vector& V,
                                        kernels::Monitors& m) const {
  Vector p(owned_);
  moved_->M->apply(V, p);
  const auto hp = p.getLocalViewHost(Tpetra::Access::ReadOnly);
  const auto hu = u.getLocalViewHost(Tpetra::Access::ReadOnly);
  const auto hV = V.getLocalViewHost(Tpetra::Access::ReadOnly);
  const auto hr = moved_->row_sums->getLocalViewHost(Tpetra::Access::ReadOnly);
  const LO nodes = static_cast<LO>(owned_->getNodeNumElements() / 3);
  for (LO k = 0; k < nodes; ++k) {
    const GO node = owned_->getGlobalElement(3 * k) / 3;
    const double* X = model_.x(static_cast<int>(node));
    double x[3], pk[3];
    for (int i = 0; i < 3; ++i) {
      x[i] = X[i] + hu(3 * k + i, 0);
      pk[i] = hp(3 * k + i, 0);
      m.kinetic += 0.5 * hV(3 * k + i, 0) * pk[i];
      m.L[i] += pk[i];
      m.moment[i] += hr(3 * k + i, 0) * x[i];
    }
    m.J[0] += x[1] * pk[2] - x[2] * pk[1];
    m.J[1] += x[2] * pk[0] - x[0] * pk[2];
    m.J[2] += x[0] * pk[1] - x[1] * pk[0];
  }
}

void Discretization::apply_mass(const Vector& v, Vector& Mv) const {
  auto vo = new_overlap_vector();
  to_overlap(v, *vo);
  Vector mo(overlap_);
  {
    const auto v = read_column(*vo);
    const auto Mv = write_column(mo);
    for_each_group(
        [&](const auto& g) { kernels::mass_tet4_apply(ExecSpace(), g.tets, v, Mv, loops(g)); });
  }
  Mv.putScalar(0.0);
  Mv.doExport(mo, *exporter_, Tpetra::ADD);
  if (moved_) moved_->M->apply(v, Mv, Teuchos::NO_TRANS, 1.0, 1.0);
}

}  // namespace emc::fem
