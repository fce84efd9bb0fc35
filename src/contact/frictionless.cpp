// Frictionless contact (docs/THEORY.md §5): du_s = N du_m + T dq at n+1/2 with the exact right
// factor Pt and the variation X of P^T; after every Newton update the slave is projected back
// (update steps 2-3), moving on to a neighbouring facet beyond the hysteresis tol_f.
#include <Teuchos_TimeMonitor.hpp>
#include <algorithm>
#include <map>
#include <memory>

#include "emcontact/contact/contact.hpp"
#include "emcontact/contact/detection.hpp"
#include "emcontact/contact/law.hpp"
#include "emcontact/views.hpp"

namespace emc::contact {

namespace {

class Frictionless final : public Law {
 public:
  explicit Frictionless(Kind own) : own_(own) {}
  Kind kind() const override { return own_; }
  double activation_weight() const override { return 0.5; }
  bool clamps(const Pair&) const override { return true; }
  bool iterate_dependent() const override { return true; }
  void rows(const LawState& s, const std::vector<Active>& active, const Vector* g, const Matrix* A,
            LawRows& out) const override;
  void start(const LawState& s, std::vector<Active>& active, Vector& u1) const override {
    reversed_.clear();
    reversed_now_ = false;
    after_update(s, active, u1);
  }
  void after_update(const LawState& s, std::vector<Active>& active, Vector& u1) const override;
  bool releases(const Active& a, double fN) const override { return fN < 0 || a.off; }
  int after_failure(const LawState& s, std::vector<Active>& active) const override;
  bool stalls() const override { return reversed_now_; }
  bool slides() const override { return sliding_now_; }
  double slip_work(int slave) const override;

 private:
  Kind own_;  ///< the pairs' type: frictionless, or Coulomb's sliding entries (§11)
  /// Coulomb: the slaves whose slip turned against their direction at an iterate of the
  /// current solve (docs/THEORY.md §11.4), cleared at its start.
  mutable std::vector<int> reversed_;
  mutable bool reversed_now_ = false;  ///< at the last iterate
  mutable bool sliding_now_ = false;   ///< Coulomb entries at the last iterate
  /// Coulomb: (slave, -f_T . s) of my sliding entries at the last iterate, sorted by slave
  mutable std::vector<std::pair<int, double>> work_;
};

std::vector<Active> mine(const Contact& contact, Kind own, const std::vector<Active>& active,
                         std::vector<std::size_t>* where = nullptr) {
  std::vector<Active> out;
  for (std::size_t k = 0; k < active.size(); ++k)
    if (contact.pairs()[active[k].pair].kind == own &&
        slides(contact.pairs()[active[k].pair], active[k])) {
      out.push_back(active[k]);
      if (where) where->push_back(k);
    }
  return out;
}

/// Scatters the blocks of one slave into P, Pt and X through the chains (§3): master dof
/// j = 3 i + c is expanded by expand_node (the dof itself if free, nothing if rigid or fixed,
/// the node's own row of P if it is an active slave; X's rows and columns go through it too).
void scatter(const LawState& s, const Active& a, const kernels::FrictionlessBlocks& b,
             const kernels::CoulombSlip* fr, LawRows& out) {
  const auto& f = s.contact.pairs()[a.pair].facets[a.facet];
  linalg::PRow mq[9];
  for (int j = 0; j < 9; ++j) {
    std::vector<int> path = {a.slave};
    s.contact.expand_node(f[j / 3], j % 3, 1.0, s.index, s.xh, path, mq[j]);
  }
  const GO q[2] = {fem::dof_gid(a.slave, 0), fem::dof_gid(a.slave, 1)};
  for (int r = 0; r < 3; ++r) {
    const GO row = fem::dof_gid(a.slave, r);
    linalg::PRow p{row, {}, {}}, pt{row, {}, {}};
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
    if (fr) {  // docs/THEORY.md §11.3: the left factor's slip columns carry f_N's variation
      linalg::PRow pl = p;
      for (int k = 0; k < 2; ++k) pl.weights[pl.weights.size() - 2 + k] = fr->Plq[r][k];
      out.pl_rows.push_back(std::move(pl));
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
      if (fr)
        for (int k = 0; k < 2; ++k) out.X.push_back({q[k], dj, wj * fr->Xsq[k][j]});
    }
  if (!fr) return;
  // docs/THEORY.md §11: the friction pair, f_T on the slave and -N_i f_T on its deformable master
  // nodes (subtracted from g), and its derivative on the slip columns
  for (int k = 0; k < 2; ++k)
    for (int l = 0; l < 2; ++l) out.X.push_back({q[k], q[l], fr->Xqq[k][l]});
  const int nodes = s.contact.disc_model().num_nodes();
  for (int c = 0; c < 3; ++c) {
    out.load.emplace_back(fem::dof_gid(a.slave, c), fr->fT[c]);
    for (int i = 0; i < 3; ++i)
      if (f[i] < nodes) out.load.emplace_back(fem::dof_gid(f[i], c), -fr->N[i] * fr->fT[c]);
  }
}

// docs/THEORY.md §5.2, §5.4: P rows du_s = N du_m + T dq, the exact right factor Pt and the
// variation X of P^T; the slave's q dofs are its x and y dofs (dxi, deta), its z dof is the
// dummy.
void Frictionless::rows(const LawState& s, const std::vector<Active>& active, const Vector* g,
                        const Matrix* A, LawRows& out) const {
  reversed_now_ = sliding_now_ = false;
  work_.clear();
  const auto entries = mine(s.contact, own_, active);
  if (entries.empty() || !g || !A) return;
  sliding_now_ = own_ == Kind::coulomb;
  const int n = static_cast<int>(entries.size());
  Kokkos::View<kernels::FrictionlessBlocks*, ExecSpace> blocks("emc::frictionless_blocks", n);
  const Refs refs = s.contact.refs(entries);
  contact::frictionless_blocks(refs, s.x0, s.x1, g->getLocalViewDevice(Tpetra::Access::ReadOnly),
                               blocks);
  auto bh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), blocks);
  // eq. 59: beta, the mean of the slave's diagonal entries of A; Coulomb's slip weight c (§11.1)
  Values beta("emc::frictionless_beta", n);
  auto betah = Kokkos::create_mirror_view(beta);
  for (int k = 0; k < n; ++k) {
    betah(k) = 0;
    for (int c = 0; c < 3; ++c)
      betah(k) += diagonal_entry(*A, fem::dof_gid(entries[k].slave, c)) / 3;
  }
  Kokkos::deep_copy(beta, betah);
  Kokkos::View<kernels::CoulombSlip*, ExecSpace> slips("emc::coulomb_slips",
                                                       own_ == Kind::coulomb ? n : 0);
  if (own_ == Kind::coulomb)
    coulomb_slips(refs, s.x0, s.x1, g->getLocalViewDevice(Tpetra::Access::ReadOnly), beta, blocks,
                  slips);
  auto fh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), slips);
  Values r("emc::position_roundoff", n);
  position_roundoff(refs, s.x1, r);
  auto rh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), r);
  static auto timer = Teuchos::TimeMonitor::getNewTimer("emcontact: contact: chains and rows");
  Teuchos::TimeMonitor tm(*timer);  // the host pass (§3 chains, the scatter into P's rows)
  for (int k = 0; k < n; ++k) {
    const Active& a = entries[k];
    const kernels::CoulombSlip* fr = own_ == Kind::coulomb ? &fh(k) : nullptr;
    scatter(s, a, bh(k), fr, out);
    if (fr) work_.emplace_back(a.slave, fr->work);
    if (fr) {  // docs/THEORY.md §11.4: an iterate sliding against the entry's direction
      const double along = fr->dir[0] * a.dir[0] + fr->dir[1] * a.dir[1] + fr->dir[2] * a.dir[2];
      if (along < 0 && s.contact.pairs()[a.pair].mu > 0) {
        reversed_now_ = true;
        if (std::find(reversed_.begin(), reversed_.end(), a.slave) == reversed_.end())
          reversed_.push_back(a.slave);
      }
    }
    out.beta.emplace_back(fem::dof_gid(a.slave, 2), betah(k));  // eq. 59
    out.roundoff += betah(k) * betah(k) * rh(k) * rh(k);
  }
  std::sort(work_.begin(), work_.end());
}

double Frictionless::slip_work(int slave) const {
  const auto it = std::lower_bound(work_.begin(), work_.end(), std::make_pair(slave, -1e300));
  return it != work_.end() && it->first == slave ? it->second : 0.0;
}

/// §5 step 2 for my entries beyond the hysteresis (leaving, by pair): facet, xi, xs1 and
/// outside move to a neighbouring facet with a valid CPP at n+1/2, if there is one.
void switch_facets(const LawState& s, std::vector<Active>& entries, Refs refs, Positions x1,
                   const std::map<int, std::vector<int>>& leaving, Values3 xs1,
                   Kokkos::View<double* [2], ExecSpace> xi, Values outside) {
  const auto& nodes = s.contact.nodes();
  Positions xh = nodes.new_positions("emc::xh");
  midpoint(s.x0, x1, xh);
  for (const auto& [p, ks] : leaving) {
    const Pair& pr = s.contact.pairs()[p];
    const LocalFacets& lf = nodes.facets(p);
    const auto& my = nodes.my_slaves(p);
    std::vector<int> slave_k, current;
    for (int k : ks) {
      slave_k.push_back(
          static_cast<int>(std::lower_bound(my.begin(), my.end(), entries[k].slave) - my.begin()));
      current.push_back(lf.find(entries[k].facet));
    }
    Kokkos::View<int*, ExecSpace> next("emc::next_facet", ks.size());
    frictionless_switch(lf.grid(xh, pr.dmax), nodes.slaves(p), lf.nodes, refs,
                        to_view("emc::leaving", ks), to_view("emc::slave_k", slave_k),
                        to_view("emc::current", current), s.x0, x1, xh, entry_rule(pr), xs1, xi,
                        outside, next);
    auto nh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), next);
    auto ids = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), lf.id);
    for (std::size_t j = 0; j < ks.size(); ++j)
      if (nh(j) >= 0) entries[ks[j]].facet = ids(nh(j));
  }
}

// docs/THEORY.md §5.3 update steps 2-3 (eq. 60-64) for my frictionless slaves.
void Frictionless::after_update(const LawState& s, std::vector<Active>& active, Vector& u1) const {
  const double tol_f = 1e-3;
  std::vector<std::size_t> where;
  auto entries = mine(s.contact, own_, active, &where);
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
  const Refs refs = s.contact.refs(entries);
  frictionless_projections(refs, s.x0, x1, xs1, xi, outside);
  auto oh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), outside);
  std::map<int, std::vector<int>> leaving;  // step 2: beyond the hysteresis, by pair
  for (int k = 0; k < n; ++k)
    if (oh(k) > tol_f) leaving[entries[k].pair].push_back(k);
  if (!leaving.empty()) {
    switch_facets(s, entries, refs, x1, leaving, xs1, xi, outside);
    Kokkos::deep_copy(oh, outside);
  }
  auto xsh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), xs1);
  Kokkos::deep_copy(xih, xi);
  auto uv = u1.getLocalViewHost(Tpetra::Access::ReadWrite);
  const auto& map = *s.contact.disc().owned_map();
  for (int k = 0; k < n; ++k) {
    Active& a = entries[k];
    const double out = oh(k);
    const double xi_k[2] = {xih(k, 0), xih(k, 1)}, xs[3] = {xsh(k, 0), xsh(k, 1), xsh(k, 2)};
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

// docs/THEORY.md §11.4: a solve that failed while sliding entries' slip turned against their
// direction had no sliding solution for them: those entries (on any rank) return to stick
// (counted as in Coulomb::settle) and the others keep sliding; a solve that failed without such
// entries makes the entries that did not slide at t_n stick.
int Frictionless::after_failure(const LawState& s, std::vector<Active>& active) const {
  int changed = 0;
  const bool any_reversed = s.contact.global_count(static_cast<int>(reversed_.size())) > 0;
  for (auto& a : active)
    if (a.slip && ((!any_reversed && !a.slid) ||
                   std::find(reversed_.begin(), reversed_.end(), a.slave) != reversed_.end())) {
      a.slip = false;
      ++a.returns;
      ++changed;
    }
  reversed_.clear();
  return changed;
}

}  // namespace

std::shared_ptr<const Law> make_frictionless(Kind own) {
  return std::make_shared<Frictionless>(own);
}

}  // namespace emc::contact
