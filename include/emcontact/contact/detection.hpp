#pragma once
// Which master facet an inactive slave node enters over a step (docs/THEORY.md §6.3), and the
// slave nodes that already penetrate their master at t = 0 (refused before any step).
#include <string>
#include <vector>

#include "emcontact/contact/pairs.hpp"
#include "emcontact/contact/search.hpp"

namespace emc::contact {

/// Tolerances of the activation rule (docs/THEORY.md §6.3).
struct EntryRule {
  double edge = 1e-2;    ///< a facet takes a node whose CPP lies outside it by up to this
                         ///< (barycentric), its xi then clamped to the facet
  double strict = 1e-9;  ///< "inside a facet" without that extension (barycentric)
  double facing = 0.2;   ///< a facet faces a slave node when n_facet . n_slave < -facing
  double round = 0;      ///< |g_N| below this is touching, not penetrating (round-off)
  double dmax = 0;       ///< deeper than this is behind a thin master, not penetrating
};

/// The rule for a pair: round-off 1e-12 of its activation depth, depth bound `max penetration`.
EntryRule entry_rule(const Pair& p);

/// The facet that slave node s enters over the step from x0 (t_n) to x1 (t_{n+1}), with its
/// CPP and gap at t_{n+1} (hit.xi unclamped), or facet = -1. grid1 holds the pair's facets at
/// x1 (margin >= rule.dmax); ns is the slave surface's outward normal at s at t_{n+1}.
/// Candidates face the node, take it (and the point where it crosses their plane) within
/// rule.edge, hold it at -dmax < g_N < -round at n+1 and see it approach (g_N decreasing). A
/// facet crossed over the step (g_N >= -round at t_n) wins over one the node was already
/// behind; then a facet crossed inside over one crossed in the edge extension only; then the
/// earliest crossing, the least outside, the lowest id. A facet that takes the node only
/// through the edge extension is refused when the node lies on another facing facet (inside
/// it, 0 <= g_N <= edge times its size): the node passes over that facet's edge.
Hit entered_facet(const FacetGrid& grid1, const Pair& p, const std::vector<double>& x0,
                  const std::vector<double>& x1, int s, const double ns[3], const EntryRule& rule);

/// The facet a frictionless slave at y (mid-point configuration of grid) moves on to when it
/// leaves its facet (§5 step 2): among the facets facing it (normal ns) whose CPP is inside,
/// the smallest |g_N|, lowest id on ties; facet = -1 if none.
Hit next_facet(const FacetGrid& grid, const double y[3], const double ns[3], const EntryRule& rule);

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
