#!/usr/bin/env bash
# Fresh machine -> packages, build, and the whole ctest suite (what CI runs). The kernel library
# (kernels/, docs/kernels.md) is also built standalone against Kokkos 3.4.01 with Serial and
# OpenMP (scripts/build_kokkos.sh, from Debian's source package) in build/_deps/kernels-openmp;
# the ctest of build/ runs its tests too (kokkos_openmp.*, on Serial and 2 OpenMP threads; its
# benchmarks are built in build/ already, on Serial).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
bash scripts/build.sh
bash scripts/build_kokkos.sh build/_deps/kokkos-openmp
cmake -S kernels -B build/_deps/kernels-openmp -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DKokkos_ROOT="$PWD/build/_deps/kokkos-openmp" -DEMC_KERNELS_TEST_PREFIX=kokkos_openmp. \
  -DEMC_KERNELS_TEST_THREADS=2 -DEMC_KERNELS_BENCH=OFF
cmake --build build/_deps/kernels-openmp -j "$(nproc)"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cd build && ctest --output-on-failure -j 2
