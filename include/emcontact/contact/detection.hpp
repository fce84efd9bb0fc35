#pragma once
// Which master facet an inactive slave node enters over a step (docs/THEORY.md §6.3), and the
// slave nodes that already penetrate their master at t = 0 (refused before any step). The rules
// are device functions on a FacetGrid, facet connectivity facets(f, a) and positions x(n, i).
#include <Kokkos_Core.hpp>
#include <array>
#include <string>
#include <vector>

#include "emcontact/contact/active.hpp"
#include "emcontact/contact/pairs.hpp"
#include "emcontact/contact/search.hpp"
#include "kernels/facet.hpp"
#include "kernels/math.hpp"

namespace emc::contact {

/// Tolerances of the activation rule (docs/THEORY.md §6.3).
struct EntryRule {
  double edge = 1e-2;    ///< a facet takes a node whose CPP lies outside it by up to this
                         ///< (barycentric), its xi then clamped to the facet
  double strict = 1e-9;  ///< "inside a facet" without that extension (barycentric)
  double facing = 0.2;   ///< a facet faces a slave node when n_facet . n_slave < -facing,
                         ///< and is at its side when |n_facet . n_slave| <= facing
  double round = 0;      ///< |g_N| below this is touching, not penetrating (round-off)
  double dmax = 0;       ///< deeper than this is behind a thin master, not penetrating
};

/// The rule for a pair: round-off 1e-12 of its activation depth, depth bound `max penetration`.
EntryRule entry_rule(const Pair& p);

namespace detail {

KOKKOS_INLINE_FUNCTION double dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// A candidate facet of entered_facet, with what orders candidates.
struct Entry {
  Hit hit;
  bool crossing = false;  ///< g_N >= -round at t_n: the facet's plane is crossed in the step
  double s = 0;           ///< the fraction of the step at which it is crossed
  double outside = 0;     ///< barycentric, of the crossing point
  bool extended = false;  ///< the crossing point lies in the edge extension only
  bool side = false;      ///< the facet does not face the node (crossed strictly inside)
  bool beside = false;    ///< its plane is crossed beside it, the node ends strictly inside it
  bool through = false;   ///< crossed strictly inside, the node ends beyond its edge extension

  KOKKOS_INLINE_FUNCTION bool before(const Entry& o) const {
    if (crossing != o.crossing) return crossing;
    if (through != o.through) return !through;
    if (beside != o.beside) return !beside;
    if (side != o.side) return !side;
    if (extended != o.extended) return !extended;
    if (s != o.s) return s < o.s;
    if (outside != o.outside) return outside < o.outside;
    return hit.facet < o.hit.facet;
  }
};

/// docs/THEORY.md §6.3, nodes entering from beside: a node behind the plane of facet `behind`
/// (CPP inside it, not crossed) lies outside the master when it lies in front of another facet
/// that takes it (within rule.edge) and that is nearer, or on whose back the facet `behind`
/// lies (a convex edge between them: the master is behind both planes there).
template <class Facets, class X>
KOKKOS_INLINE_FUNCTION bool outside_master(const FacetGrid& grid1, const Facets& facets,
                                           const X& x1, const double y1[3], const Hit& behind,
                                           const EntryRule& rule) {
  double c[3] = {0, 0, 0};
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i < 3; ++i) c[i] += x1(facets(behind.facet, a), i) / 3;
  bool outside = false;
  grid1.for_each_candidate(y1, [&](const Hit& h, double out) {
    if (h.facet == behind.facet || out > rule.edge || h.gap < -rule.round) return;
    const kernels::FacetMetric m = grid1.metric(h.facet);
    // the height of `behind`'s centroid over h's plane (through the node's CPP y1 - g n)
    const double hc =
        (c[0] - y1[0]) * m.f.n[0] + (c[1] - y1[1]) * m.f.n[1] + (c[2] - y1[2]) * m.f.n[2] + h.gap;
    if (h.gap < -behind.gap || hc <= rule.round) outside = true;
  });
  return outside;
}

}  // namespace detail

/// The facet that slave node s enters over the step from x0 (t_n) to x1 (t_{n+1}), with its
/// CPP and gap at t_{n+1} (hit.xi unclamped), or facet = -1. grid1 holds the facets (facets(f, a)
/// node indices into x0 and x1) at x1 (margin >= rule.dmax); ns is the slave surface's outward
/// normal at s at t_{n+1}. Candidates face the node, take it (and the point where it crosses
/// their plane) within rule.edge, hold it at -dmax < g_N < -round at n+1 and see it approach
/// (g_N decreasing). A facet crossed over the step (g_N >= -round at t_n) wins over one the node
/// was already behind; then a facet crossed inside over one crossed in the edge extension only;
/// then the earliest crossing, the least outside, the lowest id. A facet at the node's side
/// (|n_f . ns| <= facing) is a candidate when crossed strictly inside, after the facing ones. A
/// facet that takes the node only through the edge extension, or a side facet, is refused when
/// the node lies on another facing facet (inside it, 0 <= g_N <= edge times its size): the node
/// passes over that facet's edge. A node that crosses a facet's plane beside it (the point lies
/// beyond the edge extension: it came over a neighbour, moving along the surface) and ends
/// strictly inside it is a candidate after those crossed inside. A node that crosses a facet's
/// plane strictly inside it entered the master there: that facet is a candidate wherever the
/// node ends (through it, beyond its edge extension), after the facets the node ends in. A node
/// behind a facet it did not cross, or crossed beside, is refused when it lies outside the
/// master (detail::outside_master).
template <class Facets, class X>
KOKKOS_INLINE_FUNCTION Hit entered_facet(const FacetGrid& grid1, const Facets& facets, const X& x0,
                                         const X& x1, int s, const double ns[3],
                                         const EntryRule& rule) {
  const double y1[3] = {x1(s, 0), x1(s, 1), x1(s, 2)}, y0[3] = {x0(s, 0), x0(s, 1), x0(s, 2)};
  detail::Entry best;
  bool any = false, covered = false;
  grid1.for_each_candidate(y1, [&](const Hit& h1, double out1) {
    const kernels::FacetMetric m = grid1.metric(h1.facet);
    const double facing = detail::dot3(m.f.n, ns);
    if (!(facing < rule.facing)) return;
    const bool side = !(facing < -rule.facing);
    if (!side && out1 <= rule.strict && h1.gap >= -rule.round &&
        h1.gap <= rule.edge * kernels::sqrt(m.f.area2))
      covered = true;
    if (!(h1.gap < -rule.round && h1.gap > -rule.dmax)) return;
    double xm0[3][3], xi0[2], g0;
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < 3; ++i) xm0[a][i] = x0(facets(h1.facet, a), i);
    if (!kernels::facet_cpp(y0, xm0, xi0, g0) || !(h1.gap < g0)) return;  // approaching
    detail::Entry e;
    e.hit = h1;
    e.crossing = g0 >= -rule.round;
    e.s = e.crossing ? g0 / (g0 - h1.gap) : 0.0;
    // where the node crosses the facet's plane (flat facets, linear motion over the step)
    const double xic[2] = {xi0[0] + e.s * (h1.xi[0] - xi0[0]), xi0[1] + e.s * (h1.xi[1] - xi0[1])};
    double outc = e.crossing ? kernels::facet_outside(xic) : out1;
    // docs/THEORY.md §6.3, crossing beside a facet: crossed over a neighbour (moving along the
    // surface) and ending strictly inside it, the node entered the master: caught here where it
    // lies inside the master
    e.beside = e.crossing && outc > rule.edge && out1 <= rule.strict;
    if (e.beside) outc = out1;
    if (outc > rule.edge) return;
    // docs/THEORY.md §6.3, through a facet: crossed strictly inside, the node entered the master
    // there, wherever it ends (out over a master edge, or into another facet's region)
    e.through = out1 > rule.edge;
    if (e.through && !(e.crossing && outc <= rule.strict)) return;
    e.outside = outc > 0 ? outc : 0.0;
    e.extended = outc > rule.strict || out1 > rule.strict;
    if (e.extended && !e.crossing) return;  // the extension is for entries over the edge only
    e.side = side;
    if (side && (e.extended || e.beside || !e.crossing)) return;  // side: crossed strictly inside
    if (!any || e.before(best)) best = e;
    any = true;
  });
  if (!any || ((best.extended || best.side || best.beside) && covered)) return Hit{};
  if ((!best.crossing || best.beside) &&
      detail::outside_master(grid1, facets, x1, y1, best.hit, rule))
    return Hit{};
  best.hit.inside = true;
  return best.hit;
}

/// docs/THEORY.md §6.3, a node that crosses a facet deeper than the max penetration: the facet
/// (-1 if none), the node's gap behind it at t_{n+1} and the drop of that gap over the step.
struct Crossing {
  int facet = -1;
  double gap = 0;      ///< g_N at t_{n+1}, <= -rule.dmax
  double closing = 0;  ///< g_N at t_n minus g_N at t_{n+1}
};

namespace detail {

/// g_N of the point y0 + s (y1 - y0) on facet xm0 + s (xm1 - xm0) (linear motion over the
/// step), with its CPP xi; a degenerate facet gives 0 and xi outside.
KOKKOS_INLINE_FUNCTION double gap_at(double s, const double y0[3], const double y1[3],
                                     const double xm0[3][3], const double xm1[3][3], double xi[2]) {
  double y[3], xm[3][3], gap = 0;
  for (int i = 0; i < 3; ++i) {
    y[i] = y0[i] + s * (y1[i] - y0[i]);
    for (int a = 0; a < 3; ++a) xm[a][i] = xm0[a][i] + s * (xm1[a][i] - xm0[a][i]);
  }
  if (!kernels::facet_cpp(y, xm, xi, gap)) xi[0] = xi[1] = -1;
  return gap;
}

}  // namespace detail

/// docs/THEORY.md §6.3: the facet that slave node s crossed over the step from x0 (t_n) to x1
/// (t_{n+1}) and ends behind deeper than rule.dmax, where activation cannot catch it: in front
/// of the facet at t_n (g_N >= -round-off), g_N <= -dmax at t_{n+1}, and the point where it
/// crosses the facet's plane (all nodes moving linearly over the step; found by bisection of
/// g_N(s)) strictly inside the facet. It went through a thin master, or ended inside one
/// deeper than its max penetration. swept: the grid of the facets' sweeps over the step
/// (FacetGrid with `from` = x0). The deepest such facet, or facet = -1.
template <class Facets, class X>
KOKKOS_INLINE_FUNCTION Crossing crossed_too_deep(const FacetGrid& swept, const Facets& facets,
                                                 const X& x0, const X& x1, int s,
                                                 const EntryRule& rule) {
  const double y1[3] = {x1(s, 0), x1(s, 1), x1(s, 2)}, y0[3] = {x0(s, 0), x0(s, 1), x0(s, 2)};
  Crossing best;
  swept.for_each_on_segment(y0, y1, [&](int f) {
    double xm0[3][3], xm1[3][3], xi[2], g0, g1;
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < 3; ++i) {
        xm0[a][i] = x0(facets(f, a), i);
        xm1[a][i] = x1(facets(f, a), i);
      }
    if (!kernels::facet_cpp(y1, xm1, xi, g1) || !(g1 <= -rule.dmax)) return;
    const kernels::FacetMetric m0 = kernels::facet_metric(xm0);
    if (!kernels::facet_cpp(y0, xm0, m0, xi, g0)) return;
    const double round = gap_roundoff(kernels::sqrt(m0.f.area2), y0);
    const double front = -(round > rule.round ? round : rule.round);
    if (!(g0 >= front) || (best.facet >= 0 && !(g1 < best.gap))) return;
    double lo = 0, hi = 1;  // g_N(lo) >= front > g_N(hi)
    for (int k = 0; k < 64 && hi - lo > 1e-16; ++k) {
      const double mid = 0.5 * (lo + hi);
      if (detail::gap_at(mid, y0, y1, xm0, xm1, xi) >= front)
        lo = mid;
      else
        hi = mid;
    }
    detail::gap_at(hi, y0, y1, xm0, xm1, xi);
    if (kernels::facet_outside(xi) > rule.strict) return;
    best.facet = f;
    best.gap = g1;
    best.closing = g0 - g1;
  });
  return best;
}

/// The same on a pair's global facets and positions (3 per geometry node), with the grid of
/// the facets' sweeps built here.
Crossing crossed_too_deep(const Pair& p, const std::vector<double>& x0,
                          const std::vector<double>& x1, int s, const EntryRule& rule);

/// The same on a pair's global facets and positions (3 per geometry node).
Hit entered_facet(const FacetGrid& grid1, const Pair& p, const std::vector<double>& x0,
                  const std::vector<double>& x1, int s, const double ns[3], const EntryRule& rule);

/// The facet a frictionless slave at y (mid-point configuration of grid) moves on to when it
/// leaves its facet (§5 step 2): among the facets facing it (normal ns) whose CPP is inside,
/// the smallest |g_N|, lowest id on ties; facet = -1 if none.
KOKKOS_INLINE_FUNCTION Hit next_facet(const FacetGrid& grid, const double y[3], const double ns[3],
                                      const EntryRule& rule) {
  Hit best;
  grid.for_each_candidate(y, [&](const Hit& h, double out) {
    if (out > rule.strict || !(detail::dot3(grid.metric(h.facet).f.n, ns) < -rule.facing)) return;
    if (best.facet < 0 || kernels::fabs(h.gap) < kernels::fabs(best.gap)) best = h;
  });
  best.inside = best.facet >= 0;
  return best;
}

/// Slave nodes (of `nodes`) that penetrate the pair's master in configuration x: the closest
/// facet whose CPP is inside (smallest |g_N|) has -dmax < g_N < -tol.
struct Penetration {
  int count = 0;
  double deepest = 0;  ///< the most negative g_N (<= 0)
  int node = -1;       ///< the node at that depth
};
Penetration penetrating_nodes(const Pair& p, const std::vector<int>& nodes,
                              const std::vector<double>& x, double tol);

}  // namespace emc::contact
