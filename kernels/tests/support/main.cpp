// The kernel library's test main: Kokkos initialized for every test, the enabled execution
// spaces printed, and, where EMC_KERNELS_EXPECT_THREADS is set (ctest sets it), a failure
// unless the OpenMP backend runs that many threads (a typed test on one thread would compare
// nothing threaded).
#include <gtest/gtest.h>

#include <Kokkos_Core.hpp>
#include <cstdio>
#include <cstdlib>

int main(int argc, char** argv) {
  Kokkos::ScopeGuard kokkos(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  std::printf("Kokkos %d.%d.%d, default execution space %s\n", KOKKOS_VERSION / 10000,
              KOKKOS_VERSION / 100 % 100, KOKKOS_VERSION % 100,
              Kokkos::DefaultExecutionSpace::name());
#ifdef KOKKOS_ENABLE_OPENMP
  const int threads = Kokkos::OpenMP().concurrency();
  std::printf("OpenMP: %d threads\n", threads);
  const char* expect = std::getenv("EMC_KERNELS_EXPECT_THREADS");
  if (expect && *expect && threads != std::atoi(expect)) {
    std::fprintf(stderr, "OpenMP runs %d threads, EMC_KERNELS_EXPECT_THREADS=%s\n", threads,
                 expect);
    return 1;
  }
#endif
  return RUN_ALL_TESTS();
}
