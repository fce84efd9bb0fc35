// docs/THEORY.md §6.3 (activation by the facet entered over the step) and §6.6 (no slave node
// starts inside its master), on the rank's contact nodes.
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_TimeMonitor.hpp>
#include <algorithm>

#include "emcontact/contact/contact.hpp"
#include "emcontact/contact/detection.hpp"
#include "emcontact/contact/law.hpp"
#include "emcontact/contact/overlap.hpp"
#include "emcontact/error.hpp"
#include "emcontact/format.hpp"
#include "emcontact/parallel.hpp"
#include "kernels/math.hpp"

namespace emc::contact {

namespace {

/// docs/THEORY.md §6.3 for each of my slave nodes of pair p not busy: the facet it enters and
/// xi, clamped if `clamp`, from the configuration x0 + w (x1 - x0): found(k) = 1 and hit(k) (its
/// contact-node index, and the facet's local index) if it enters one, else found(k) = 0.
void entering_nodes(const FacetGrid& grid1, const LocalSlaves ls,
                    const Kokkos::View<int* [3], ExecSpace> facets, Positions x0, Positions x1,
                    Kokkos::View<int*, ExecSpace> busy, const EntryRule rule, const double w,
                    const bool clamp, const double edge, const int p,
                    Kokkos::View<Active*, ExecSpace> hit, Kokkos::View<int*, ExecSpace> found) {
  const FacetGrid grid = grid1;  // by value: Views only
  Kokkos::parallel_for(
      "emcontact::contact::detect",
      Kokkos::RangePolicy<ExecSpace, Kokkos::Schedule<Kokkos::Dynamic>>(0, ls.size()),
      KOKKOS_LAMBDA(const int k) {
        const int s = ls.node(k);
        found(k) = 0;
        const double y1[3] = {x1(s, 0), x1(s, 1), x1(s, 2)};
        if (busy(s) || !grid.any_box(y1)) return;  // no candidate: no normal needed
        double n_s[3];
        slave_normal(ls, k, x1, n_s);
        const Hit h1 = entered_facet(grid, facets, x0, x1, s, n_s, rule);
        if (h1.facet < 0) return;
        double xf[3][3], y[3];
        for (int i = 0; i < 3; ++i) {
          y[i] = w == 0 ? x0(s, i) : (1 - w) * x0(s, i) + w * x1(s, i);
          for (int a = 0; a < 3; ++a) {
            const int n = facets(h1.facet, a);
            xf[a][i] = w == 0 ? x0(n, i) : (1 - w) * x0(n, i) + w * x1(n, i);
          }
        }
        const kernels::FacetMetric m = kernels::facet_metric(xf);
        double xi[2], gap;
        if (!kernels::facet_cpp(y, xf, m, xi, gap)) return;
        if (clamp) kernels::facet_clamp(m, xi);
        Active a;
        a.slave = s;  // contact-node index here; global below
        a.pair = p;
        a.facet = h1.facet;
        a.xi[0] = xi[0];
        a.xi[1] = xi[1];
        // docs/THEORY.md §7.2: a node already behind the facet at t_n keeps its gap (closing
        // it would push it out: energy from nowhere)
        double xm0[3][3], y0[3], xi0[2], g0;
        for (int i = 0; i < 3; ++i) {
          y0[i] = x0(s, i);
          for (int b = 0; b < 3; ++b) xm0[b][i] = x0(facets(h1.facet, b), i);
        }
        a.keep_gap = kernels::facet_cpp(y0, xm0, xi0, g0) && g0 < -gap_roundoff(edge, y0);
        hit(k) = a;
        found(k) = 1;
      });
}

/// The entries hit(k) with pos(k) = 1, in order of k, with the facet's id in the pair (a scan
/// turns pos into their positions, -1 elsewhere: only the hits reach the host).
Kokkos::View<Active*, ExecSpace>::HostMirror compact_hits(
    const Kokkos::View<const Active*, ExecSpace> hit, const Kokkos::View<int*, ExecSpace> pos,
    const Kokkos::View<const int*, ExecSpace> id) {
  const int ns = static_cast<int>(hit.extent(0));
  int count = 0;
  Kokkos::parallel_scan(
      "emcontact::contact::detect_count", Kokkos::RangePolicy<ExecSpace>(0, ns),
      KOKKOS_LAMBDA(const int k, int& n, const bool final) {
        const int f = pos(k);
        if (final) pos(k) = f ? n : -1;
        n += f;
      },
      count);
  Kokkos::View<Active*, ExecSpace> found(
      Kokkos::ViewAllocateWithoutInitializing("emc::detect_found"), count);
  Kokkos::parallel_for(
      "emcontact::contact::detect_compact", Kokkos::RangePolicy<ExecSpace>(0, ns),
      KOKKOS_LAMBDA(const int k) {
        if (pos(k) < 0) return;
        Active a = hit(k);
        a.facet = id(a.facet);
        found(pos(k)) = a;
      });
  return Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), found);
}

}  // namespace

std::vector<Active> Contact::detect(Positions x0, Positions x1,
                                    const std::vector<Active>& active) const {
  static auto timer = Teuchos::TimeMonitor::getNewTimer("emcontact: contact: activation");
  Teuchos::TimeMonitor tm(*timer);
  Kokkos::View<int*, ExecSpace> busy("emc::busy", nodes_.size());
  auto bh = Kokkos::create_mirror_view(busy);
  for (const auto& a : active) bh(nodes_.local(a.slave)) = 1;
  Kokkos::deep_copy(busy, bh);
  std::vector<Active> found;
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    const auto hits = detect_pair(static_cast<int>(p), x0, x1, busy);
    for (const auto& a : hits) bh(nodes_.local(a.slave)) = 1;  // a node in two pairs: the first
    Kokkos::deep_copy(busy, bh);
    found.insert(found.end(), hits.begin(), hits.end());
  }
  return found;
}

// docs/THEORY.md §6.3: xi (clamped to the facet unless the law keeps it) is the CPP in the
// law's configuration: at t_n for full stick (§4), at the trial mid-point for frictionless (§5).
std::vector<Active> Contact::detect_pair(int p, Positions x0, Positions x1,
                                         Kokkos::View<int*, ExecSpace> busy) const {
  const Pair& pr = pairs_[p];
  const LocalSlaves ls = nodes_.slaves(p);
  const LocalFacets& lf = nodes_.facets(p);
  const int ns = ls.size();
  if (ns == 0 || lf.size() == 0) return {};
  const FacetGrid grid = lf.grid(x1, pr.dmax);
  Kokkos::View<Active*, ExecSpace> hit(Kokkos::ViewAllocateWithoutInitializing("emc::detect_hits"),
                                       ns);
  Kokkos::View<int*, ExecSpace> flag(Kokkos::ViewAllocateWithoutInitializing("emc::detect_flags"),
                                     ns);
  entering_nodes(grid, ls, lf.nodes, x0, x1, busy, entry_rule(pr), laws_[p]->activation_weight(),
                 laws_[p]->clamps(pr), pr.edge, p, hit, flag);
  const auto hh = compact_hits(hit, flag, lf.id);
  std::vector<Active> found(hh.data(), hh.data() + hh.extent(0));
  for (auto& a : found) a.slave = nodes_.global(a.slave);
  return found;
}

namespace {

/// The count of my slaves of a pair that crossed a facet too deep, and the deepest of them
/// (contact-node index).
struct Deep {
  int count = 0;
  double gap = 0, closing = 0;
  int node = -1;
};

/// The reduction of Deep over my slaves of a pair (a functor: device code is never in a
/// private member).
struct DeepCrossingsOf {
  using value_type = Deep;
  FacetGrid swept;
  Kokkos::View<int* [3], ExecSpace> facets;
  Positions x0, x1;
  LocalSlaves ls;
  Kokkos::View<int*, ExecSpace> busy;
  EntryRule rule;

  KOKKOS_INLINE_FUNCTION void operator()(const int k, Deep& r) const {
    const int s = ls.node(k);
    if (busy(s)) return;
    const Crossing c = crossed_too_deep(swept, facets, x0, x1, s, rule);
    if (c.facet < 0) return;
    ++r.count;
    if (r.node < 0 || c.gap < r.gap || (c.gap == r.gap && s < r.node)) {
      r.gap = c.gap;
      r.closing = c.closing;
      r.node = s;
    }
  }
  EMC_KERNELS_REDUCER_JOIN(Deep)
  template <class A, class B>
  KOKKOS_INLINE_FUNCTION static void join_into(A& a, const B& b) {
    a.count += b.count;
    if (b.node >= 0 && (a.node < 0 || b.gap < a.gap || (b.gap == a.gap && b.node < a.node))) {
      a.gap = b.gap;
      a.closing = b.closing;
      a.node = b.node;
    }
  }
  KOKKOS_INLINE_FUNCTION void init(Deep& a) const {
    a.count = 0;
    a.gap = a.closing = 0;
    a.node = -1;
  }
};

}  // namespace

// docs/THEORY.md §6.3: a node that crossed a facet deeper than the max penetration.
DeepCrossings Contact::crossed_too_deep(Positions x0, Positions x1,
                                        const std::vector<int>& active) const {
  static auto timer = Teuchos::TimeMonitor::getNewTimer("emcontact: contact: crossings");
  Teuchos::TimeMonitor tm(*timer);
  Kokkos::View<int*, ExecSpace> busy("emc::busy", nodes_.size());
  auto bh = Kokkos::create_mirror_view(busy);
  for (int n : active)
    if (nodes_.local(n) >= 0) bh(nodes_.local(n)) = 1;
  Kokkos::deep_copy(busy, bh);
  std::vector<double> mine;  // per pair with a crossing: count, gap, closing, pair, node
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    const LocalSlaves ls = nodes_.slaves(static_cast<int>(p));
    const LocalFacets& lf = nodes_.facets(static_cast<int>(p));
    if (ls.size() == 0 || lf.size() == 0) continue;
    const FacetGrid swept =
        lf.rigid_grid ? *lf.rigid_grid : FacetGrid(lf.nodes, x1, pairs_[p].dmax, x0);
    Deep d;
    Kokkos::parallel_reduce(
        "emcontact::contact::crossed_too_deep", Kokkos::RangePolicy<ExecSpace>(0, ls.size()),
        DeepCrossingsOf{swept, lf.nodes, x0, x1, ls, busy, entry_rule(pairs_[p])}, d);
    if (d.count > 0)
      mine.insert(mine.end(),
                  {double(d.count), d.gap, d.closing, double(p), double(nodes_.global(d.node))});
  }
  DeepCrossings out;
  const auto all = allgather(*disc_.comm(), mine);
  for (std::size_t k = 0; k + 5 <= all.size(); k += 5) {
    out.count += static_cast<int>(all[k]);
    if (out.pair < 0 || all[k + 1] < out.gap) {
      out.gap = all[k + 1];
      out.closing = all[k + 2];
      out.pair = static_cast<int>(all[k + 3]);
      out.node = static_cast<int>(all[k + 4]);
    }
  }
  return out;
}

// docs/THEORY.md §6.6: no slave node may start inside its master (reference configuration).
void Contact::check_initial_penetration(const std::string& file) const {
  const auto x = contact::positions(disc_.model(), {});
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    const Pair& pr = pairs_[p];
    const Penetration mine = penetrating_nodes(pr, nodes_.my_slaves(p), x, 1e-9 * pr.edge);
    const int count = global_count(mine.count);
    if (count == 0) continue;
    double deepest = 0;
    Teuchos::reduceAll(*disc_.comm(), Teuchos::REDUCE_MIN, 1, &mine.deepest, &deepest);
    throw InputError(
        format("%s: Contact/%s: %d slave node%s penetrate%s the master at t = 0 (deepest "
               "%.3g, %.3g of the facet size); the bodies must not overlap at the start, "
               "and a master's facet normals must face the slave (a rigid plane's 'axis' "
               "points toward the slave)",
               file.c_str(), pr.name.c_str(), count, count == 1 ? "" : "s", count == 1 ? "s" : "",
               -deepest, -deepest / pr.edge));
  }
  for (std::size_t p = 0; p < pairs_.size(); ++p) check_overlap(pairs_[p], x, file);
  for (const Pair& pr : pairs_)
    if (pr.rigid_master) check_facing(pr, x, file);
}

// docs/THEORY.md §6.6: a slave node inside the master body at any depth (a body embedded in
// another lies deeper than any facet's window), or a node of the master surface inside the
// slave body (the master embedded in the slave: no slave node is inside it).
void Contact::check_overlap(const Pair& pr, const std::vector<double>& x,
                            const std::string& file) const {
  // every rank tests every point against the tets it owns; a point's depth is the largest
  const auto report = [&](const std::vector<int>& points, int body, const char* nodes,
                          const char* name) {
    auto depth = depth_inside_body(disc_.model(), body, points, x, pr.edge);
    if (disc_.comm()->getSize() > 1 && !depth.empty()) {
      std::vector<double> mine = depth;
      Teuchos::reduceAll(*disc_.comm(), Teuchos::REDUCE_MAX, static_cast<int>(depth.size()),
                         mine.data(), depth.data());
    }
    const Overlap o = overlap_of(points, depth);
    if (o.count == 0) return;
    throw InputError(
        format("%s: Contact/%s: %d %s node%s lie%s inside the %s body at t = 0 (deepest "
               "%.3g, %.3g of the facet size); the bodies must not overlap at the start",
               file.c_str(), pr.name.c_str(), o.count, nodes, o.count == 1 ? "" : "s",
               o.count == 1 ? "s" : "", name, o.deepest, o.deepest / pr.edge));
  };
  report(pr.slaves, pr.master_body, "slave", "master");
  std::vector<int> master;  // the master surface's nodes
  for (const auto& f : pr.facets) master.insert(master.end(), f.begin(), f.end());
  std::sort(master.begin(), master.end());
  master.erase(std::unique(master.begin(), master.end()), master.end());
  report(master, pr.slave_body, "master", "slave");
}

// docs/THEORY.md §6.6: a rigid surface whose facets turn their back to the slave body (its
// centroid behind the facet it projects into, at any depth) can never be touched. A slave
// face lying on the surface has its centroid on the facet's plane up to round-off (1e-17 either
// way on a tilted plane): then the slave surface's outward normal tells, against the facet's.
void Contact::check_facing(const Pair& pr, const std::vector<double>& x,
                           const std::string& file) const {
  double c[3] = {0, 0, 0};
  for (int s : pr.slaves)
    for (int i = 0; i < 3; ++i) c[i] += x[3 * s + i] / pr.slaves.size();
  double nearest = 1e300, gap_nearest = 0, n[3] = {0, 0, 0};
  for (const auto& f : pr.facets) {
    double xm[3][3], xi[2], gap;
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 3; ++i) xm[k][i] = x[3 * f[k] + i];
    if (!kernels::facet_cpp(c, xm, xi, gap) || kernels::facet_outside(xi) > 1e-9) continue;
    if (std::fabs(gap) < nearest) {
      nearest = std::fabs(gap);
      gap_nearest = gap;
      const kernels::Facet fc = kernels::facet(xm);
      for (int i = 0; i < 3; ++i) n[i] = fc.n[i];
    }
  }
  if (!(nearest < 1e300)) return;
  // the node check's tolerance (1e-9 of the facet size), and the gap's round-off
  const double tol = std::max(1e-9 * pr.edge, gap_roundoff(pr.edge, c));
  if (gap_nearest < -tol)
    throw InputError(
        format("%s: Contact/%s: the slave body lies behind the rigid master at t = 0 (its "
               "centroid %.3g behind the facet it projects into); a master's facet normals "
               "must face the slave (a rigid plane's 'axis' points toward the slave)",
               file.c_str(), pr.name.c_str(), -gap_nearest));
  if (gap_nearest > tol) return;
  double ns[3] = {0, 0, 0};  // the slave surface's outward normal, area-weighted
  for (const auto& t : pr.slave_facets) {
    double xs[3][3];
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 3; ++i) xs[k][i] = x[3 * t[k] + i];
    const kernels::Facet fc = kernels::facet(xs);
    for (int i = 0; i < 3; ++i) ns[i] += fc.area2 * fc.n[i];
  }
  if (!(ns[0] * n[0] + ns[1] * n[1] + ns[2] * n[2] > 0)) return;
  throw InputError(
      format("%s: Contact/%s: the slave surface lies on the rigid master at t = 0 facing the "
             "same way (its outward normal along the facet's): the slave body lies behind it; "
             "a master's facet normals must face the slave (a rigid plane's 'axis' points "
             "toward the slave)",
             file.c_str(), pr.name.c_str()));
}

}  // namespace emc::contact
