#pragma once
// The kernel library's data types (Kokkos only: no Tpetra, Teuchos or MPI), ArborX style: data
// live in Views of a memory space, and every driver takes the execution space instance that runs
// it (the space must be able to access the memory space). Layouts are explicit: rows of three
// (points, facets) and four (tets) are row-major (LayoutRight) on every backend, so that a host
// array of structs wraps into a View without a copy and copies to a device View as one block.
#include <Kokkos_Core.hpp>
#include <type_traits>

namespace emc::kernels {

/// n points (3 coordinates each) in a memory space.
template <class MemorySpace>
using Points = Kokkos::View<const double* [3], Kokkos::LayoutRight, MemorySpace>;
/// n triangles (3 node ids into Points each).
template <class MemorySpace>
using Triangles = Kokkos::View<const int* [3], Kokkos::LayoutRight, MemorySpace>;
/// n tetrahedra (4 node ids into Points each).
template <class MemorySpace>
using Tetrahedra = Kokkos::View<const int* [4], Kokkos::LayoutRight, MemorySpace>;
/// n vectors of 3 (forces, displacements), writable.
template <class MemorySpace>
using Vectors3 = Kokkos::View<double* [3], Kokkos::LayoutRight, MemorySpace>;

/// T in a parameter that takes no part in deducing a function template's arguments (C++20's
/// std::type_identity_t): a View converts to it (const data, another memory trait).
template <class T>
struct Identity {
  using type = T;
};
template <class T>
using NonDeduced = typename Identity<T>::type;

/// The execution space that runs a memory space's kernels when the caller names none.
template <class MemorySpace>
using DefaultExecutionSpace = typename MemorySpace::execution_space;

/// A temporary View for kernels on ExecutionSpace in MemorySpace: an algorithm that dispatches
/// on a View's device (Kokkos::BinSort) then runs on ExecutionSpace.
template <class T, class ExecutionSpace, class MemorySpace>
using Scratch = Kokkos::View<T, Kokkos::Device<ExecutionSpace, MemorySpace>>;

/// A labelled range over [0, n) on an execution space instance.
template <class ExecutionSpace>
Kokkos::RangePolicy<ExecutionSpace> range(const ExecutionSpace& space, std::size_t n) {
  return Kokkos::RangePolicy<ExecutionSpace>(space, 0, n);
}

/// Fails to compile unless ExecutionSpace's kernels may read MemorySpace.
template <class ExecutionSpace, class MemorySpace>
constexpr void check_access() {
  static_assert(Kokkos::is_execution_space<ExecutionSpace>::value, "not a Kokkos execution space");
  static_assert(Kokkos::SpaceAccessibility<ExecutionSpace, MemorySpace>::accessible,
                "the execution space cannot access the memory space");
}

}  // namespace emc::kernels
