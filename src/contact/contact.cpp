#include "emcontact/contact/contact.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <set>

#include "emcontact/contact/detection.hpp"
#include "emcontact/contact/search.hpp"
#include "emcontact/error.hpp"
#include "emcontact/parallel.hpp"
#include "kernels/facet.hpp"
#include "kernels/frictionless.hpp"

namespace emc::contact {

using Teuchos::rcp;

Contact::Contact(const fem::Discretization& disc, std::vector<Pair> pairs)
    : disc_(disc), pairs_(std::move(pairs)) {
  const int rank = disc_.comm()->getRank();
  for (const auto& p : pairs_) {
    my_slaves_.emplace_back();
    for (int s : p.slaves)
      if (disc_.part().node_owner[s] == rank) my_slaves_.back().push_back(s);
  }
  if (pairs_.empty()) return;
  const GO n = 3LL * disc_.model().num_nodes();
  all_ = rcp(new Map(n, 0, disc_.comm(), Tpetra::LocallyReplicated));
  to_all_ = rcp(new Import(disc_.owned_map(), all_));
}

std::vector<double> Contact::replicate(const Vector& u) const {
  Vector all(all_);
  all.doImport(u, *to_all_, Tpetra::INSERT);
  auto h = all.getLocalViewHost(Tpetra::Access::ReadOnly);
  return std::vector<double>(h.data(), h.data() + h.extent(0));
}

int Contact::global_count(int local) const {
  int g = 0;
  Teuchos::reduceAll(*disc_.comm(), Teuchos::REDUCE_SUM, 1, &local, &g);
  return g;
}

/// g_N of node s on the plane of facet f in configuration x (+infinity if degenerate).
static double gap_at(const std::vector<double>& x, int s, const std::array<int, 3>& f) {
  double xm[3][3], xi[2], gap;
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 3; ++i) xm[k][i] = x[3 * f[k] + i];
  return kernels::facet_cpp(&x[3 * s], xm, xi, gap) ? gap : 1e300;
}

void Contact::facet_coords(const Active& a, const std::vector<double>& x, double xm[3][3]) const {
  const auto& f = pairs_[a.pair].facets[a.facet];
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 3; ++i) xm[k][i] = x[3 * f[k] + i];
}

// docs/THEORY.md §6.3: activation by the facet entered over the step; xi (clamped to the
// facet) from the CPP at t_n for full stick (§4), of the trial mid-point at n+1/2 for
// frictionless (§5).
std::vector<Active> Contact::detect(const std::vector<double>& x0, const std::vector<double>& x1,
                                    const std::vector<Active>& active) const {
  std::set<int> busy;
  for (const auto& a : active) busy.insert(a.slave);
  std::vector<Active> found;
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    const Pair& pr = pairs_[p];
    const auto& mine = my_slaves_[p];
    if (mine.empty()) continue;
    const FacetGrid grid1(pr.facets, x1, pr.dmax);
    const EntryRule rule = entry_rule(pr);
    const int ns = static_cast<int>(mine.size());
    std::vector<Active> hit(ns);
    Kokkos::parallel_for(
        "emcontact::contact::detect", Kokkos::RangePolicy<Kokkos::DefaultHostExecutionSpace>(0, ns),
        [&, p](const int k) {
          const int s = mine[k];
          if (busy.count(s)) return;
          double n_s[3];
          slave_normal(pr, s, x1, n_s);
          const Hit h1 = entered_facet(grid1, pr, x0, x1, s, n_s, rule);
          if (h1.facet < 0) return;
          // xf: the facet where xi is taken, at t_n (stick) or at n+1/2
          // (frictionless)
          double xf[3][3], y[3];
          const bool mid = pr.kind == Kind::frictionless;
          auto at = [&](int n, int i) {
            return mid ? 0.5 * (x0[3 * n + i] + x1[3 * n + i]) : x0[3 * n + i];
          };
          for (int i = 0; i < 3; ++i) {
            y[i] = at(s, i);
            for (int a = 0; a < 3; ++a) xf[a][i] = at(pr.facets[h1.facet][a], i);
          }
          const kernels::FacetMetric m = kernels::facet_metric(xf);
          double xi[2], gap;
          if (!kernels::facet_cpp(y, xf, m, xi, gap)) return;
          // docs/THEORY.md §7.2: a closing stick node keeps its CPP in the
          // edge extension (closing to a clamped xi drags it along the facet)
          if (!(pr.close_gap && pr.kind == Kind::full_stick)) kernels::facet_clamp(m, xi);
          hit[k] = Active{s, static_cast<int>(p), h1.facet, {xi[0], xi[1]}, false};
          // docs/THEORY.md §7.2: a node already behind the facet at t_n keeps
          // its gap (closing it would push it out: energy from nowhere)
          hit[k].keep_gap = gap_at(x0, s, pr.facets[h1.facet]) < -gap_roundoff(pr, &x0[3 * s]);
        });
    for (const auto& a : hit)
      if (a.slave >= 0) {
        found.push_back(a);
        busy.insert(a.slave);  // a node in two pairs is taken by the first
      }
  }
  return found;
}

// docs/THEORY.md §6.6: no slave node may start inside its master.
void Contact::check_initial_penetration(const std::vector<double>& x,
                                        const std::string& file) const {
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    const Pair& pr = pairs_[p];
    const Penetration mine = penetrating_nodes(pr, my_slaves_[p], x, 1e-9 * pr.edge);
    const int count = global_count(mine.count);
    if (count == 0) continue;
    double deepest = 0;
    Teuchos::reduceAll(*disc_.comm(), Teuchos::REDUCE_MIN, 1, &mine.deepest, &deepest);
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "%s: Contact/%s: %d slave node%s penetrate%s the master at t = 0 (deepest "
                  "%.3g, %.3g of the facet size); the bodies must not overlap at the start, "
                  "and a master's facet normals must face the slave (a rigid plane's 'axis' "
                  "points toward the slave)",
                  file.c_str(), pr.name.c_str(), count, count == 1 ? "" : "s",
                  count == 1 ? "s" : "", -deepest, -deepest / pr.edge);
    throw InputError(buf);
  }
  for (const Pair& pr : pairs_)
    if (pr.rigid_master) check_facing(pr, x, file);
}

// docs/THEORY.md §6.6: a rigid surface whose facets turn their back to the slave body (its
// centroid behind the facet it projects into, at any depth) can never be touched.
void Contact::check_facing(const Pair& pr, const std::vector<double>& x,
                           const std::string& file) const {
  double c[3] = {0, 0, 0};
  for (int s : pr.slaves)
    for (int i = 0; i < 3; ++i) c[i] += x[3 * s + i] / pr.slaves.size();
  double nearest = 1e300, gap_nearest = 0;
  for (const auto& f : pr.facets) {
    double xm[3][3], xi[2], gap;
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 3; ++i) xm[k][i] = x[3 * f[k] + i];
    if (!kernels::facet_cpp(c, xm, xi, gap) || kernels::facet_outside(xi) > 0) continue;
    if (std::fabs(gap) < nearest) {
      nearest = std::fabs(gap);
      gap_nearest = gap;
    }
  }
  if (!(nearest < 1e300) || gap_nearest >= 0) return;
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "%s: Contact/%s: the slave body lies behind the rigid master at t = 0 (its "
                "centroid %.3g behind the facet it projects into); a master's facet normals must "
                "face the slave (a rigid plane's 'axis' points toward the slave)",
                file.c_str(), pr.name.c_str(), -gap_nearest);
  throw InputError(buf);
}

std::vector<double> Contact::normal_forces(const Vector& g, const std::vector<double>& x0,
                                           const std::vector<double>& x1,
                                           const std::vector<Active>& active) const {
  auto gv = g.getLocalViewHost(Tpetra::Access::ReadOnly);
  const auto& map = *disc_.owned_map();
  std::vector<double> fN(active.size());
  for (std::size_t k = 0; k < active.size(); ++k) {
    const Active& a = active[k];
    double xm0[3][3], xm1[3][3], xh[3][3];
    facet_coords(a, x0, xm0);
    facet_coords(a, x1, xm1);
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) xh[j][i] = 0.5 * (xm0[j][i] + xm1[j][i]);
    const kernels::Facet f = kernels::facet(xh);
    double s = 0;
    for (int i = 0; i < 3; ++i) s += gv(map.getLocalElement(fem::dof_gid(a.slave, i)), 0) * f.n[i];
    fN[k] = s;
  }
  return fN;
}

ActiveIndex Contact::gather(const std::vector<Active>& mine) const {
  std::vector<double> send;
  for (const auto& a : mine)
    send.insert(send.end(), {double(a.slave), double(a.pair), double(a.facet), a.xi[0], a.xi[1]});
  const auto all = allgather(*disc_.comm(), send);
  ActiveIndex index;
  for (std::size_t k = 0; k + 4 < all.size(); k += 5) {
    Active a;
    a.slave = static_cast<int>(all[k]);
    a.pair = static_cast<int>(all[k + 1]);
    a.facet = static_cast<int>(all[k + 2]);
    a.xi[0] = all[k + 3];
    a.xi[1] = all[k + 4];
    index.by_slave.emplace(a.slave, a);
  }
  return index;
}

// ALGORITHM.md §3: rows of P compose along chains, P = P_1 P_2 ...
void Contact::expand_node(int node, int c, double w, const ActiveIndex& index,
                          const std::vector<double>& x0, const std::vector<double>& x1,
                          std::vector<int>& path, linalg::PRow& r) const {
  const auto& m = disc_.model();
  if (node >= m.num_nodes() || m.fixed[node]) return;  // rigid or fixed: no column
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
  for (int i = 0; i < 3; ++i) expand_node(f[i], c, w * N[i], index, x0, x1, path, r);
  path.pop_back();
  if (pairs_[a.pair].kind == Kind::frictionless && !x1.empty()) {  // + T dq at n+1/2 (§5)
    double xm0[3][3], xm1[3][3], xh[3][3];
    facet_coords(a, x0, xm0);
    facet_coords(a, x1, xm1);
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) xh[j][i] = 0.5 * (xm0[j][i] + xm1[j][i]);
    const kernels::Facet fh = kernels::facet(xh);
    r.cols.push_back(fem::dof_gid(node, 0));
    r.weights.push_back(w * fh.t1[c]);
    r.cols.push_back(fem::dof_gid(node, 1));
    r.weights.push_back(w * fh.t2[c]);
  }
}

// ALGORITHM.md §3-§4: du_s = N du_m; the slave's own column of P is zero (three dummies).
void Contact::constraint_rows(const std::vector<Active>& active, const ActiveIndex& index,
                              const std::vector<double>& x0, const std::vector<double>& x1,
                              std::vector<linalg::PRow>& rows, std::vector<GO>& dummies) const {
  for (const auto& a : active) {
    if (pairs_[a.pair].kind != Kind::full_stick) continue;
    const auto& f = pairs_[a.pair].facets[a.facet];
    double N[3];
    kernels::facet_shape(a.xi, N);
    for (int c = 0; c < 3; ++c) {
      linalg::PRow r;
      r.row = fem::dof_gid(a.slave, c);
      std::vector<int> path = {a.slave};
      for (int k = 0; k < 3; ++k) expand_node(f[k], c, N[k], index, x0, x1, path, r);
      rows.push_back(std::move(r));
      dummies.push_back(fem::dof_gid(a.slave, c));
    }
  }
}

// ALGORITHM.md §5: P rows du_s = N du_m + T dq, the exact right factor Pt and the variation X
// of P^T; the slave's q dofs are its x and y dofs (dxi, deta), its z dof is the dummy.
void Contact::frictionless_rows(const std::vector<Active>& active, const ActiveIndex& index,
                                const std::vector<double>& x0, const std::vector<double>& x1,
                                const Vector& g, const Matrix& A, std::vector<linalg::PRow>& rows,
                                std::vector<linalg::PRow>& pt_rows, std::vector<linalg::Entry>& X,
                                std::vector<std::pair<GO, double>>& dummy_beta) const {
  const auto& m = disc_.model();
  auto gv = g.getLocalViewHost(Tpetra::Access::ReadOnly);
  Vector diag(A.getRowMap());
  A.getLocalDiagCopy(diag);
  auto dv = diag.getLocalViewHost(Tpetra::Access::ReadOnly);
  const auto& map = *disc_.owned_map();
  for (const auto& a : active) {
    if (pairs_[a.pair].kind != Kind::frictionless) continue;
    const auto& f = pairs_[a.pair].facets[a.facet];
    double xm0[3][3], xm1[3][3], gs[3], beta = 0;
    facet_coords(a, x0, xm0);
    facet_coords(a, x1, xm1);
    for (int c = 0; c < 3; ++c) {
      const LO l = map.getLocalElement(fem::dof_gid(a.slave, c));
      gs[c] = gv(l, 0);
      beta += dv(l, 0) / 3;
    }
    kernels::FrictionlessBlocks b;
    kernels::frictionless_blocks(&x0[3 * a.slave], &x1[3 * a.slave], xm0, xm1, a.xi, gs, b,
                                 closes(a));
    // master dof j = 3 i + c: a column of P and a row and column of X in terms of q, through
    // expand_node: the dof itself if free, nothing if rigid or fixed, and for a master node
    // that is an active slave itself its own row of P (a chain, §3; X's rows and columns are
    // carried through that row like P's)
    linalg::PRow mq[9];
    for (int j = 0; j < 9; ++j) {
      std::vector<int> path = {a.slave};
      expand_node(f[j / 3], j % 3, 1.0, index, x0, x1, path, mq[j]);
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
      rows.push_back(std::move(p));
      pt_rows.push_back(std::move(pt));
    }
    for (int j = 0; j < 9; ++j)
      for (std::size_t l = 0; l < mq[j].cols.size(); ++l) {
        const GO dj = mq[j].cols[l];
        const double wj = mq[j].weights[l];
        for (int k = 0; k < 2; ++k) {
          X.push_back({q[k], dj, wj * b.Xsq[k][j]});
          X.push_back({dj, q[k], wj * b.Xmq[j][k]});
        }
        for (int i = 0; i < 9; ++i)
          if (b.Xmm[j][i] != 0)
            for (std::size_t e = 0; e < mq[i].cols.size(); ++e)
              X.push_back({dj, mq[i].cols[e], wj * mq[i].weights[e] * b.Xmm[j][i]});
      }
    dummy_beta.emplace_back(fem::dof_gid(a.slave, 2), beta);  // eq. 59
  }
}

// ALGORITHM.md §5 update steps 2-3 (eq. 60-64) for my frictionless slaves.
void Contact::frictionless_project(std::vector<Active>& active, const std::vector<double>& x0,
                                   const std::vector<double>& x1, Vector& u1) const {
  const double tol_f = 1e-3;
  const auto& m = disc_.model();
  auto uv = u1.getLocalViewHost(Tpetra::Access::ReadWrite);
  const auto& map = *disc_.owned_map();
  std::vector<double> xh;
  std::vector<std::unique_ptr<FacetGrid>> grids(pairs_.size());
  for (auto& a : active) {
    if (pairs_[a.pair].kind != Kind::frictionless) continue;
    double xm0[3][3], xm1[3][3], xi[2] = {a.xi[0], a.xi[1]}, xs1[3];
    for (int i = 0; i < 3; ++i) xs1[i] = x1[3 * a.slave + i];
    facet_coords(a, x0, xm0);
    facet_coords(a, x1, xm1);
    const bool close = closes(a);
    double out = kernels::frictionless_project(&x0[3 * a.slave], xs1, xm0, xm1, xi, close);
    if (out > tol_f) {  // step 2: beyond the hysteresis, move to a neighbour with a valid CPP
      if (xh.empty()) {
        xh.resize(x0.size());
        for (std::size_t k = 0; k < x0.size(); ++k) xh[k] = 0.5 * (x0[k] + x1[k]);
      }
      const Pair& pr = pairs_[a.pair];
      if (!grids[a.pair]) grids[a.pair] = std::make_unique<FacetGrid>(pr.facets, xh, pr.dmax);
      double y[3];
      for (int i = 0; i < 3; ++i) y[i] = xh[3 * a.slave + i];
      double n_s[3];
      slave_normal(pr, a.slave, xh, n_s);
      const Hit h = next_facet(*grids[a.pair], y, n_s, entry_rule(pr));
      if (h.facet >= 0 && h.facet != a.facet) {
        a.facet = h.facet;
        for (int i = 0; i < 3; ++i) xs1[i] = x1[3 * a.slave + i];
        xi[0] = h.xi[0];
        xi[1] = h.xi[1];
        facet_coords(a, x0, xm0);
        facet_coords(a, x1, xm1);
        out = kernels::frictionless_project(&x0[3 * a.slave], xs1, xm0, xm1, xi, close);
      }
    }
    // kept with the extrapolated xi, up to the edge extension of activation (§6.3) so that a
    // node is not released where it would be caught again; beyond it released at the end of
    // the step
    a.off = out > entry_rule(pairs_[a.pair]).edge;
    a.xi[0] = xi[0];
    a.xi[1] = xi[1];
    for (int c = 0; c < 3; ++c)
      uv(map.getLocalElement(fem::dof_gid(a.slave, c)), 0) = xs1[c] - m.X[3 * a.slave + c];
  }
}

std::vector<std::pair<GO, double>> Contact::dummy_values(const Matrix& A,
                                                         const std::vector<GO>& dummies) const {
  Vector d(A.getRowMap());
  A.getLocalDiagCopy(d);
  auto h = d.getLocalViewHost(Tpetra::Access::ReadOnly);
  const auto& map = *A.getRowMap();
  std::vector<std::pair<GO, double>> out;
  for (std::size_t k = 0; k + 2 < dummies.size(); k += 3) {  // a slave's three dofs in a row
    double tr = 0;
    for (int c = 0; c < 3; ++c) tr += h(map.getLocalElement(dummies[k + c]), 0);
    for (int c = 0; c < 3; ++c) out.emplace_back(dummies[k + c], tr / 3);
  }
  return out;
}

// docs/THEORY.md §7.2: an active node behind its facet keeps its gap (closing it would push it
// out: energy from nowhere); every other node of a closing pair is closed in the next step.
void Contact::mark_kept_gaps(std::vector<Active>& active, const std::vector<double>& x1) const {
  for (auto& a : active) {
    const Pair& pr = pairs_[a.pair];
    if (pr.close_gap)
      a.keep_gap = gap_at(x1, a.slave, pr.facets[a.facet]) < -gap_roundoff(pr, &x1[3 * a.slave]);
  }
}

void Contact::gap_range(const std::vector<double>& x1, const std::vector<Active>& active,
                        double& lo, double& hi) const {
  double l = 1e300, h = -1e300;
  for (const auto& a : active) {
    double xm[3][3], xi[2], gap;
    facet_coords(a, x1, xm);
    if (!kernels::facet_cpp(&x1[3 * a.slave], xm, xi, gap)) continue;  // degenerate facet
    l = std::min(l, gap);
    h = std::max(h, gap);
  }
  Teuchos::reduceAll(*disc_.comm(), Teuchos::REDUCE_MIN, 1, &l, &lo);
  Teuchos::reduceAll(*disc_.comm(), Teuchos::REDUCE_MAX, 1, &h, &hi);
}

}  // namespace emc::contact
