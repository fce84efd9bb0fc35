// The contact search (docs/THEORY.md §2.5) on the solver's execution space: the kernel
// library's grid build and batch query (kernels/search_build.hpp), compiled here once.
#include "emcontact/contact/search.hpp"

namespace emc::kernels {
template FacetGrid<contact::GridMemorySpace>::FacetGrid(
    const ExecSpace&, const FacetGrid<contact::GridMemorySpace>::FacetsView&,
    const FacetGrid<contact::GridMemorySpace>::PointsView&, double,
    const FacetGrid<contact::GridMemorySpace>::PointsView&);
template FacetGrid<contact::GridMemorySpace>::FacetGrid(const ExecSpace&,
                                                        const std::vector<std::array<int, 3>>&,
                                                        const std::vector<double>&, double);
template void FacetGrid<contact::GridMemorySpace>::locate_all(
    const ExecSpace&, const FacetGrid<contact::GridMemorySpace>::PointsView&,
    const FacetGrid<contact::GridMemorySpace>::HitsView&) const;
template void FacetGrid<contact::GridMemorySpace>::locate_all(const ExecSpace&, const double*,
                                                              std::size_t, std::vector<Hit>&) const;
}  // namespace emc::kernels
