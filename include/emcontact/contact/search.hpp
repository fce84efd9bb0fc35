#pragma once
// Contact search (docs/THEORY.md §2.5): the kernel library's grid of the master facets
// (kernels/search.hpp, Kokkos only) on the memory space of the solver's execution space. Its
// queries are device functions, so a FacetGrid copied by value into a kernel can be queried
// there, one thread per slave node; built and batch-queried on the solver's execution space.
#include <type_traits>

#include "emcontact/types.hpp"
#include "kernels/search.hpp"

namespace emc::contact {

using GridMemorySpace = ExecSpace::memory_space;
static_assert(std::is_same_v<kernels::DefaultExecutionSpace<GridMemorySpace>, ExecSpace>,
              "the grid's kernels run on the solver's execution space");

using kernels::CellBlock;
using kernels::GridShape;
using kernels::Hit;
using kernels::Prism;
using CellLists = kernels::CellLists<GridMemorySpace>;
using FacetGrid = kernels::FacetGrid<GridMemorySpace>;

}  // namespace emc::contact

// The grid's build and batch query on the solver's execution space are compiled once, in
// src/contact/search.cpp.
namespace emc::kernels {
extern template FacetGrid<contact::GridMemorySpace>::FacetGrid(
    const ExecSpace&, const FacetGrid<contact::GridMemorySpace>::FacetsView&,
    const FacetGrid<contact::GridMemorySpace>::PointsView&, double,
    const FacetGrid<contact::GridMemorySpace>::PointsView&);
extern template FacetGrid<contact::GridMemorySpace>::FacetGrid(
    const ExecSpace&, const std::vector<std::array<int, 3>>&, const std::vector<double>&, double);
extern template void FacetGrid<contact::GridMemorySpace>::locate_all(
    const ExecSpace&, const FacetGrid<contact::GridMemorySpace>::PointsView&,
    const FacetGrid<contact::GridMemorySpace>::HitsView&) const;
extern template void FacetGrid<contact::GridMemorySpace>::locate_all(const ExecSpace&,
                                                                     const double*, std::size_t,
                                                                     std::vector<Hit>&) const;
}  // namespace emc::kernels
