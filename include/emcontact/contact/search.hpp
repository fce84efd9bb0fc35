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
