// docs/THEORY.md §6.3: which master facet an inactive slave node enters over a step, and the
// crossings deeper than max penetration (the host entry points of detection.hpp).
#include "emcontact/contact/detection.hpp"

namespace emc::contact {

EntryRule entry_rule(const Pair& p) {
  EntryRule r;
  r.dmax = p.dmax;
  r.round = 1e-12 * p.dmax;
  return r;
}

Hit entered_facet(const FacetGrid& grid1, const Pair& p, const std::vector<double>& x0,
                  const std::vector<double>& x1, int s, const double ns[3], const EntryRule& rule) {
  using Unmanaged = Kokkos::MemoryTraits<Kokkos::Unmanaged>;
  const Kokkos::View<const int* [3], Kokkos::HostSpace, Unmanaged> facets(
      reinterpret_cast<const int*>(p.facets.data()), p.facets.size());
  const Kokkos::View<const double*[3], Kokkos::HostSpace, Unmanaged> v0(x0.data(), x0.size() / 3),
      v1(x1.data(), x1.size() / 3);
  return entered_facet(grid1, facets, v0, v1, s, ns, rule);
}

Crossing crossed_too_deep(const Pair& p, const std::vector<double>& x0,
                          const std::vector<double>& x1, int s, const EntryRule& rule) {
  using Unmanaged = Kokkos::MemoryTraits<Kokkos::Unmanaged>;
  const Kokkos::View<const int* [3], Kokkos::HostSpace, Unmanaged> facets(
      reinterpret_cast<const int*>(p.facets.data()), p.facets.size());
  const Kokkos::View<const double*[3], Kokkos::HostSpace, Unmanaged> v0(x0.data(), x0.size() / 3),
      v1(x1.data(), x1.size() / 3);
  const auto dev = [](auto v) {
    return Kokkos::create_mirror_view_and_copy(ExecSpace::memory_space(), v);
  };
  const FacetGrid swept(dev(facets), dev(v1), p.dmax, dev(v0));
  return crossed_too_deep(swept, facets, v0, v1, s, rule);
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
