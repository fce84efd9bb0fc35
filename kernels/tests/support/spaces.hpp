#pragma once
// The execution spaces the tests and benchmarks run on (ArborX style: every backend Kokkos
// enables), and the reference each is compared with: Serial where it is enabled, else the
// default host space.
#include <Kokkos_Core.hpp>

namespace emc::kernels::test {

template <class... T>
struct List {};
template <class A, class B>
struct Cat;
template <class... A, class... B>
struct Cat<List<A...>, List<B...>> {
  using type = List<A..., B...>;
};
#ifdef KOKKOS_ENABLE_SERIAL
using SerialList = List<Kokkos::Serial>;
using Reference = Kokkos::Serial;
#else
using SerialList = List<>;
using Reference = Kokkos::DefaultHostExecutionSpace;
#endif
#ifdef KOKKOS_ENABLE_OPENMP
using OpenMPList = List<Kokkos::OpenMP>;
#else
using OpenMPList = List<>;
#endif
#ifdef KOKKOS_ENABLE_THREADS
using ThreadsList = List<Kokkos::Threads>;
#else
using ThreadsList = List<>;
#endif
#ifdef KOKKOS_ENABLE_CUDA
using CudaList = List<Kokkos::Cuda>;
#else
using CudaList = List<>;
#endif

/// Every enabled execution space.
using Spaces =
    typename Cat<typename Cat<typename Cat<SerialList, OpenMPList>::type, ThreadsList>::type,
                 CudaList>::type;

/// Whether E's results are compared with the reference's bit for bit: on the host (the same
/// compiler and floating-point contraction), not on a device (whose compiler may fuse a * b + c).
template <class E>
constexpr bool bitwise() {
  return Kokkos::SpaceAccessibility<Kokkos::HostSpace, typename E::memory_space>::accessible;
}

/// A host copy of a View (of any memory space).
template <class V>
auto on_host(const V& v) {
  return Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), v);
}

}  // namespace emc::kernels::test
