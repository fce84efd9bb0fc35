#pragma once
// What the kernel library's benchmarks share: a benchmark registered once per enabled execution
// space, and the Kokkos configuration recorded in the output's context.
#include <benchmark/benchmark.h>

#include <Kokkos_Core.hpp>
#include <string>

#include "support/spaces.hpp"

namespace emc::kernels::test {

/// Calls R::template on<E>() for every execution space E of the list.
template <class R, class... E>
void for_each_space(List<E...>) {
  (R::template on<E>(), ...);
}

/// The Kokkos version and, with OpenMP, its threads, in the benchmark output's context.
inline void add_kokkos_context() {
  benchmark::AddCustomContext("kokkos_version", std::to_string(KOKKOS_VERSION));
#ifdef KOKKOS_ENABLE_OPENMP
  benchmark::AddCustomContext("openmp_threads", std::to_string(Kokkos::OpenMP().concurrency()));
#endif
}

}  // namespace emc::kernels::test
