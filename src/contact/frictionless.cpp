// Frictionless contact (ALGORITHM.md §5): du_s = N du_m + T dq at n+1/2 with the exact right
// factor Pt and the variation X of P^T; after every Newton update the slave is projected back
// (update steps 2-3), moving on to a neighbouring facet beyond the hysteresis tol_f.
#include <Teuchos_TimeMonitor.hpp>
#include <memory>

#include "emcontact/contact/contact.hpp"
#include "emcontact/contact/detection.hpp"
#include "emcontact/contact/law.hpp"

namespace emc::contact {

namespace {

class Frictionless final : public Law {
 public:
  Kind kind() const override { return Kind::frictionless; }
  double activation_weight() const override { return 0.5; }
  bool clamps(const Pair&) const override { return true; }
  bool iterate_dependent() const override { return true; }
  void rows(const LawState& s, const std::vector<Active>& active, const Vector* g, const Matrix* A,
            LawRows& out) const override;
  void start(const LawState& s, std::vector<Active>& active, Vector& u1) const override {
    after_update(s, active, u1);
  }
  void after_update(const LawState& s, std::vector<Active>& active, Vector& u1) const override;
  bool releases(const Active& a, double fN) const override { return fN < 0 || a.off; }
};

std::vector<Active> mine(const Contact& contact, const std::vector<Active>& active,
                         std::vector<std::size_t>* where = nullptr) {
  std::vector<Active> out;
  for (std::size_t k = 0; k < active.size(); ++k)
    if (contact.pairs()[active[k].pair].kind == Kind::frictionless) {
      out.push_back(active[k]);
      if (where) where->push_back(k);
    }
  return out;
}

/// Scatters the blocks of one slave into P, Pt and X through the chains (§3): master dof
/// j = 3 i + c is expanded by expand_node (the dof itself if free, nothing if rigid or fixed,
/// the node's own row of P if it is an active slave; X's rows and columns go through it too).
void scatter(const LawState& s, const Active& a, const kernels::FrictionlessBlocks& b,
             LawRows& out) {
  const auto& f = s.contact.pairs()[a.pair].facets[a.facet];
  linalg::PRow mq[9];
  for (int j = 0; j < 9; ++j) {
    std::vector<int> path = {a.slave};
    s.contact.expand_node(f[j / 3], j % 3, 1.0, s.index, s.xh, path, mq[j]);
  }
  const GO q[2] = {fem::dof_gid(a.slave, 0), fem::dof_gid(a.slave, 1)};
  for (int r = 0; r < 3; ++r) {
    linalg::PRow p{fem::dof_gid(a.slave, r), {}, {}}, pt = p;
    for (int j = 0; j < 9; ++j)
      for (std::size_t l = 0; l < mq[j].cols.size(); ++l) {
        p.cols.push_back(mq[j].cols[l]);
        p.weights.push_back(b.Pm[r][j] * mq[j].weights[l]);
        pt.cols.push_back(mq[j].cols[l]);
        pt.weights.push_back(b.Ptm[r][j] * mq[j].weights[l]);
      }
    for (int k = 0; k < 2; ++k) {
      p.cols.push_back(q[k]);
      p.weights.push_back(b.Pq[r][k]);
      pt.cols.push_back(q[k]);
      pt.weights.push_back(b.Ptq[r][k]);
    }
    out.rows.push_back(std::move(p));
    out.pt_rows.push_back(std::move(pt));
  }
  for (int j = 0; j < 9; ++j)
    for (std::size_t l = 0; l < mq[j].cols.size(); ++l) {
      const GO dj = mq[j].cols[l];
      const double wj = mq[j].weights[l];
      for (int k = 0; k < 2; ++k) {
        out.X.push_back({q[k], dj, wj * b.Xsq[k][j]});
        out.X.push_back({dj, q[k], wj * b.Xmq[j][k]});
      }
      for (int i = 0; i < 9; ++i)
        if (b.Xmm[j][i] != 0)
          for (std::size_t e = 0; e < mq[i].cols.size(); ++e)
            out.X.push_back({dj, mq[i].cols[e], wj * mq[i].weights[e] * b.Xmm[j][i]});
    }
}

// ALGORITHM.md §5: P rows du_s = N du_m + T dq, the exact right factor Pt and the variation X
// of P^T; the slave's q dofs are its x and y dofs (dxi, deta), its z dof is the dummy.
void Frictionless::rows(const LawState& s, const std::vector<Active>& active, const Vector* g,
                        const Matrix* A, LawRows& out) const {
  const auto entries = mine(s.contact, active);
  if (entries.empty() || !g || !A) return;
  const int n = static_cast<int>(entries.size());
  Kokkos::View<kernels::FrictionlessBlocks*, ExecSpace> blocks("emc::frictionless_blocks", n);
  contact::frictionless_blocks(s.contact.refs(entries), s.x0, s.x1,
                               g->getLocalViewDevice(Tpetra::Access::ReadOnly), blocks);
  auto bh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), blocks);
  static auto timer = Teuchos::TimeMonitor::getNewTimer("emcontact: contact: chains and rows");
  Teuchos::TimeMonitor tm(*timer);  // the host pass (§3 chains, the scatter into P's rows)
  Vector diag(A->getRowMap());
  A->getLocalDiagCopy(diag);
  auto dv = diag.getLocalViewHost(Tpetra::Access::ReadOnly);
  const auto& map = *s.contact.disc().owned_map();
  for (int k = 0; k < n; ++k) {
    const Active& a = entries[k];
    scatter(s, a, bh(k), out);
    double beta = 0;
    for (int c = 0; c < 3; ++c) beta += dv(map.getLocalElement(fem::dof_gid(a.slave, c)), 0) / 3;
    out.beta.emplace_back(fem::dof_gid(a.slave, 2), beta);  // eq. 59
  }
}

/// §5 step 2 beyond the hysteresis: the neighbouring facet with a valid CPP at n+1/2, if any.
Hit next_facet_of(const Contact& contact, const Active& a, const Positions::HostMirror& xh) {
  const auto xh_device = Kokkos::create_mirror_view_and_copy(ExecSpace(), xh);
  const Pair& pr = contact.pairs()[a.pair];
  const auto& nodes = contact.nodes();
  const LocalFacets& lf = nodes.facets(a.pair);
  const FacetGrid grid(lf.nodes, xh_device, pr.dmax);
  const int sl = nodes.local(a.slave);
  const auto& my = nodes.my_slaves(a.pair);
  const int k = static_cast<int>(std::lower_bound(my.begin(), my.end(), a.slave) - my.begin());
  LocalSlaves ls = nodes.slaves(a.pair);
  double n_s[3];
  slave_normal(ls, k, xh, n_s);
  const double y[3] = {xh(sl, 0), xh(sl, 1), xh(sl, 2)};
  Hit h = next_facet(grid, y, n_s, entry_rule(pr));
  if (h.facet >= 0)
    h.facet = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), lf.id)(h.facet);
  return h;
}

// ALGORITHM.md §5 update steps 2-3 (eq. 60-64) for my frictionless slaves.
void Frictionless::after_update(const LawState& s, std::vector<Active>& active, Vector& u1) const {
  const double tol_f = 1e-3;
  std::vector<std::size_t> where;
  auto entries = mine(s.contact, active, &where);
  const int n = static_cast<int>(entries.size());
  const Positions x1 = s.contact.positions(u1);
  if (n == 0) return;
  const auto& m = s.contact.disc_model();
  Values3 xs1("emc::frictionless_xs1", n);
  Kokkos::View<double* [2], ExecSpace> xi("emc::frictionless_xi", n);
  Values outside("emc::frictionless_outside", n);
  auto xih = Kokkos::create_mirror_view(xi);
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < 2; ++i) xih(k, i) = entries[k].xi[i];
  Kokkos::deep_copy(xi, xih);
  frictionless_projections(s.contact.refs(entries), s.x0, x1, xs1, xi, outside);
  auto xsh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), xs1);
  Kokkos::deep_copy(xih, xi);
  auto oh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), outside);
  auto x0h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), s.x0);
  auto x1h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), x1);
  Positions::HostMirror xh;
  auto uv = u1.getLocalViewHost(Tpetra::Access::ReadWrite);
  const auto& map = *s.contact.disc().owned_map();
  const auto& nodes = s.contact.nodes();
  for (int k = 0; k < n; ++k) {
    Active& a = entries[k];
    double xi_k[2] = {xih(k, 0), xih(k, 1)}, xs[3] = {xsh(k, 0), xsh(k, 1), xsh(k, 2)};
    double out = oh(k);
    if (out > tol_f) {  // step 2: beyond the hysteresis, move to a neighbour with a valid CPP
      if (xh.extent(0) == 0) {
        xh = Positions::HostMirror("emc::xh", x1h.extent(0));
        for (std::size_t l = 0; l < xh.extent(0); ++l)
          for (int i = 0; i < 3; ++i) xh(l, i) = 0.5 * (x0h(l, i) + x1h(l, i));
      }
      const Hit h = next_facet_of(s.contact, a, xh);
      if (h.facet >= 0 && h.facet != a.facet) {
        a.facet = h.facet;
        const int sl = nodes.local(a.slave);
        const auto& f = s.contact.pairs()[a.pair].facets[a.facet];
        double xm0[3][3], xm1[3][3], y0[3];
        for (int i = 0; i < 3; ++i) {
          xs[i] = x1h(sl, i);
          y0[i] = x0h(sl, i);
          for (int j = 0; j < 3; ++j) {
            xm0[j][i] = x0h(nodes.local(f[j]), i);
            xm1[j][i] = x1h(nodes.local(f[j]), i);
          }
        }
        xi_k[0] = h.xi[0];
        xi_k[1] = h.xi[1];
        out = kernels::frictionless_project(y0, xs, xm0, xm1, xi_k, s.contact.closes(a));
      }
    }
    // kept with the extrapolated xi, up to the edge extension of activation (§6.3) so that a
    // node is not released where it would be caught again; beyond it released at the end of
    // the step
    a.off = out > entry_rule(s.contact.pairs()[a.pair]).edge;
    a.xi[0] = xi_k[0];
    a.xi[1] = xi_k[1];
    for (int c = 0; c < 3; ++c)
      uv(map.getLocalElement(fem::dof_gid(a.slave, c)), 0) = xs[c] - m.X[3 * a.slave + c];
    active[where[k]] = a;
  }
}

}  // namespace

std::shared_ptr<const Law> make_frictionless() {
  return std::make_shared<Frictionless>();
}

}  // namespace emc::contact
