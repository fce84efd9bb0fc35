// Frictionless contact (docs/THEORY.md §5): du_s = N du_m + T dq at n+1/2 with the exact right
// factor Pt and the variation X of P^T; after every Newton update the slave is projected back
// (update steps 2-3), moving on to a neighbouring facet beyond the hysteresis tol_f. The pieces
// here serve Coulomb's sliding entries too (law_parts.hpp).
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_TimeMonitor.hpp>
#include <algorithm>
#include <map>
#include <memory>

#include "emcontact/contact/contact.hpp"
#include "emcontact/contact/detection.hpp"
#include "emcontact/views.hpp"
#include "law_parts.hpp"

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
  void start(const LawState& s, std::vector<Active>&, Vector& u1) const override {
    project_sliding(s, Kind::frictionless, u1);
  }
  void after_update(const LawState& s, std::vector<Active>&, Vector& u1) const override {
    project_sliding(s, Kind::frictionless, u1);
  }
  bool releases(const Active& a, double fN) const override { return fN < 0 || a.off; }
  int after_failure(const LawState& s, std::vector<Active>& active) const override {
    return stick_reversed(s, Kind::frictionless, active);
  }
};

// docs/THEORY.md §5.2, §5.4: P rows du_s = N du_m + T dq, the exact right factor Pt and the
// variation X of P^T; the slave's q dofs are its x and y dofs (dxi, deta), its z dof is the
// dummy.
void Frictionless::rows(const LawState& s, const std::vector<Active>&, const Vector* g,
                        const Matrix* A, LawRows& out) const {
  const SlidingBlocks b = sliding_blocks(s, Kind::frictionless, g, A);
  static auto timer = Teuchos::TimeMonitor::getNewTimer("emcontact: contact: chains and rows");
  Teuchos::TimeMonitor tm(*timer);  // the host pass (§3 chains, the scatter into P's rows)
  for (int k = 0; k < b.size(); ++k) {
    scatter(s, b.entries[k], b.blocks_h(k), nullptr, out);
    add_beta(b, k, out);
  }
}

/// §5 step 2 for my rows sel(k) beyond the hysteresis (leaving, by pair): facet, xi, xs1 and
/// outside move to a neighbouring facet with a valid CPP at n+1/2, if there is one (the state's
/// facet and its nodes in refs with it). A host pass over the leaving rows only.
void switch_facets(const LawState& s, Ints sel, Refs refs, Positions x1,
                   const std::map<int, std::vector<int>>& leaving, Values3 xs1, Xis xi,
                   Values outside) {
  const auto& nodes = s.contact.nodes();
  Positions xh = nodes.new_positions("emc::xh");
  midpoint(s.x0, x1, xh);
  const auto sel_h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), sel);
  const auto slave_h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), s.state->slave);
  const auto facet_h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), s.state->facet);
  for (const auto& [p, ks] : leaving) {
    const Pair& pr = s.contact.pairs()[p];
    const LocalFacets& lf = nodes.facets(p);
    const auto& my = nodes.my_slaves(p);
    std::vector<int> slave_k, current;
    for (int k : ks) {
      slave_k.push_back(
          static_cast<int>(std::lower_bound(my.begin(), my.end(), slave_h(sel_h(k))) - my.begin()));
      current.push_back(lf.find(facet_h(sel_h(k))));
    }
    Kokkos::View<int*, ExecSpace> next("emc::next_facet", ks.size());
    const Ints leaving_k = to_view("emc::leaving", ks);
    frictionless_switch(lf.grid(xh, pr.dmax), nodes.slaves(p), lf.nodes, refs, leaving_k,
                        to_view("emc::slave_k", slave_k), to_view("emc::current", current), s.x0,
                        x1, xh, entry_rule(pr), xs1, xi, outside, next);
    const Ints facet = s.state->facet;
    const Refs state_refs = s.state->refs;
    const auto ids = lf.id;
    const auto facet_nodes = lf.nodes;
    Kokkos::parallel_for(
        "emcontact::contact::switch_facets",
        Kokkos::RangePolicy<ExecSpace>(0, static_cast<int>(ks.size())), KOKKOS_LAMBDA(const int j) {
          if (next(j) < 0) return;
          const int k = sel(leaving_k(j));
          facet(k) = ids(next(j));
          for (int i = 0; i < 3; ++i) state_refs(k).m[i] = facet_nodes(next(j), i);
        });
  }
}

}  // namespace

// §3: master dof j = 3 i + c is expanded by expand_node (the dof itself if free, nothing if
// rigid or fixed, the node's own row of P if it is an active slave; X's rows and columns go
// through it too).
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

// The blocks come from the state's rows on the execution space; the chains (§3) and the
// scatter into P's rows are a host pass (the elimination takes host rows).
SlidingBlocks sliding_blocks(const LawState& s, Kind own, const Vector* g, const Matrix* A) {
  SlidingBlocks b;
  ContactState& st = *s.state;
  const int kind = static_cast<int>(own);
  st.reversed_now[kind] = st.sliding_now[kind] = false;
  b.sel = st.sliding[kind];
  const int n = b.size();
  if (n == 0 || !g || !A) {
    b.sel = Ints("emcontact::contact::sliding_none", 0);
    return b;
  }
  b.blocks = Kokkos::View<kernels::FrictionlessBlocks*, ExecSpace>("emc::frictionless_blocks", n);
  b.refs = gather_refs(st, b.sel);
  contact::frictionless_blocks(b.refs, s.x0, s.x1, g->getLocalViewDevice(Tpetra::Access::ReadOnly),
                               b.blocks);
  b.blocks_h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), b.blocks);
  // eq. 59: beta, the mean of the slave's diagonal entries of A (a kernel over their rows)
  b.beta = Values("emc::frictionless_beta", n);
  mean_diagonals(*A, gather_slaves(st, b.sel), b.beta);
  b.beta_h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), b.beta);
  Values r("emc::position_roundoff", n);
  position_roundoff(b.refs, s.x1, r);
  b.roundoff_h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), r);
  const auto sel_h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), b.sel);
  const auto all = host_entries(st, 0, st.local);
  for (int k = 0; k < n; ++k) b.entries.push_back(all[sel_h(k)]);
  return b;
}

void add_beta(const SlidingBlocks& b, int k, LawRows& out) {
  const double beta = b.beta_h(k);
  out.beta.emplace_back(fem::dof_gid(b.entries[k].slave, 2), beta);  // eq. 59
  out.roundoff += beta * beta * b.roundoff_h(k) * b.roundoff_h(k);
}

// docs/THEORY.md §5.3 update steps 2-3 (eq. 60-64) for my sliding slaves, on the state.
void project_sliding(const LawState& s, Kind own, Vector& u1) {
  const double tol_f = 1e-3;
  const Ints sel = s.state->sliding[static_cast<int>(own)];
  const int n = static_cast<int>(sel.extent(0));
  const Positions x1 = s.contact.positions(u1);
  if (n == 0) return;
  Values3 xs1("emc::frictionless_xs1", n);
  Xis xi = gather_xi(*s.state, sel);
  Values outside("emc::frictionless_outside", n);
  const Refs refs = gather_refs(*s.state, sel);
  frictionless_projections(refs, s.x0, x1, xs1, xi, outside);
  if (count_beyond(outside, tol_f) > 0) {  // step 2: beyond the hysteresis, by pair
    const auto oh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), outside);
    const auto sel_h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), sel);
    const auto pair_h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), s.state->pair);
    std::map<int, std::vector<int>> leaving;
    for (int k = 0; k < n; ++k)
      if (oh(k) > tol_f) leaving[pair_h(sel_h(k))].push_back(k);
    switch_facets(s, sel, refs, x1, leaving, xs1, xi, outside);
  }
  store_projections(*s.state, sel, xi, outside, xs1,
                    u1.getLocalViewDevice(Tpetra::Access::ReadWrite));
}

// docs/THEORY.md §11.4: a solve that failed while sliding entries' slip turned against their
// direction had no sliding solution for them: those entries (on any rank) return to stick
// (counted as in Coulomb's return map) and the others keep sliding; a solve that failed without
// such entries makes the entries that did not slide at t_n stick. The reversal marks are the
// law's own rows' (of type own).
int stick_reversed(const LawState& s, Kind own, std::vector<Active>& active) {
  ContactState& st = *s.state;
  auto reversed = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), st.reversed);
  const auto marked = [&](std::size_t k) {
    return k < reversed.extent(0) && reversed(k) != 0 &&
           s.contact.pairs()[active[k].pair].kind == own;
  };
  int mine = 0;
  for (std::size_t k = 0; k < active.size(); ++k) mine += marked(k) ? 1 : 0;
  const bool any_reversed = s.contact.global_count(mine) > 0;
  int changed = 0;
  for (std::size_t k = 0; k < active.size(); ++k) {
    Active& a = active[k];
    if (a.slip && ((!any_reversed && !a.slid) || marked(k))) {
      a.slip = false;
      ++a.returns;
      ++changed;
    }
  }
  for (std::size_t k = 0; k < active.size(); ++k)
    if (marked(k)) reversed(k) = 0;
  Kokkos::deep_copy(st.reversed, reversed);
  return changed;
}

std::shared_ptr<const Law> make_frictionless() {
  return std::make_shared<Frictionless>();
}

}  // namespace emc::contact
