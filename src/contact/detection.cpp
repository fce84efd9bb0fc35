#include "emcontact/contact/detection.hpp"

#include <cmath>

#include "kernels/facet.hpp"

namespace emc::contact {

namespace {

double dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// A candidate facet of entered_facet, with what orders candidates.
struct Entry {
  Hit hit;
  bool crossing = false;  ///< g_N >= -round at t_n: the facet's plane is crossed in the step
  double s = 0;           ///< the fraction of the step at which it is crossed
  double outside = 0;     ///< barycentric, of the crossing point
  bool extended = false;  ///< the crossing point lies in the edge extension only

  bool before(const Entry& o) const {
    if (crossing != o.crossing) return crossing;
    if (extended != o.extended) return !extended;
    if (s != o.s) return s < o.s;
    if (outside != o.outside) return outside < o.outside;
    return hit.facet < o.hit.facet;
  }
};

}  // namespace

EntryRule entry_rule(const Pair& p) {
  EntryRule r;
  r.dmax = p.dmax;
  r.round = 1e-12 * p.dmax;
  return r;
}

// docs/THEORY.md §6.3: activation by the facet entered over the step.
Hit entered_facet(const FacetGrid& grid1, const Pair& p, const std::vector<double>& x0,
                  const std::vector<double>& x1, int s, const double ns[3], const EntryRule& rule) {
  const double* y1 = &x1[3 * s];
  Entry best;
  bool any = false, covered = false;
  grid1.for_each_candidate(y1, [&](const Hit& h1, double out1) {
    const kernels::FacetMetric& m = grid1.metric(h1.facet);
    if (!(dot3(m.f.n, ns) < -rule.facing) || out1 > rule.edge) return;
    if (out1 <= rule.strict && h1.gap >= -rule.round && h1.gap <= rule.edge * std::sqrt(m.f.area2))
      covered = true;
    if (!(h1.gap < -rule.round && h1.gap > -rule.dmax)) return;
    double xm0[3][3], xi0[2], g0;
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < 3; ++i) xm0[a][i] = x0[3 * p.facets[h1.facet][a] + i];
    if (!kernels::facet_cpp(&x0[3 * s], xm0, xi0, g0) || !(h1.gap < g0)) return;  // approaching
    Entry e;
    e.hit = h1;
    e.crossing = g0 >= -rule.round;
    e.s = e.crossing ? g0 / (g0 - h1.gap) : 0.0;
    // where the node crosses the facet's plane (flat facets, linear motion over the step)
    const double xic[2] = {xi0[0] + e.s * (h1.xi[0] - xi0[0]), xi0[1] + e.s * (h1.xi[1] - xi0[1])};
    const double outc = e.crossing ? kernels::facet_outside(xic) : out1;
    if (outc > rule.edge) return;
    e.outside = outc > 0 ? outc : 0.0;
    e.extended = outc > rule.strict || out1 > rule.strict;
    if (e.extended && !e.crossing) return;  // the extension is for entries over the edge only
    if (!any || e.before(best)) best = e;
    any = true;
  });
  if (!any || (best.extended && covered)) return Hit{};
  best.hit.inside = true;
  return best.hit;
}

Hit next_facet(const FacetGrid& grid, const double y[3], const double ns[3],
               const EntryRule& rule) {
  Hit best;
  grid.for_each_candidate(y, [&](const Hit& h, double out) {
    if (out > rule.strict || !(dot3(grid.metric(h.facet).f.n, ns) < -rule.facing)) return;
    if (best.facet < 0 || std::fabs(h.gap) < std::fabs(best.gap)) best = h;
  });
  best.inside = best.facet >= 0;
  return best;
}

Penetration penetrating_nodes(const Pair& p, const std::vector<int>& nodes,
                              const std::vector<double>& x, double tol) {
  Penetration out;
  if (nodes.empty()) return out;
  const FacetGrid grid(p.facets, x, p.dmax);
  for (int s : nodes) {
    const Hit h = grid.locate(&x[3 * s]);
    if (h.facet < 0 || !(h.gap < -tol && h.gap > -p.dmax)) continue;
    ++out.count;
    if (h.gap < out.deepest) {
      out.deepest = h.gap;
      out.node = s;
    }
  }
  return out;
}

}  // namespace emc::contact
