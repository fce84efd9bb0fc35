#!/usr/bin/env bash
# Fresh machine -> packages, build, the default ctest suite, the unit tests under ASan + UBSan,
# clang-tidy on the changed files (what CI runs; docs/developer-guide.md, "Tests"). The kernel
# library (kernels/, docs/kernels.md) is also built standalone against Kokkos 3.4.01 with Serial
# and OpenMP (scripts/build_kokkos.sh, from Debian's source package) in
# build/_deps/kernels-openmp; the ctest of build/ runs its tests too (kokkos_openmp.*, on Serial
# and 2 OpenMP threads). EMC_SANITIZE=0 or EMC_TIDY=0 leave out those two steps (e.g. on a
# developer's machine).
set -euo pipefail
cd "$(dirname "$0")/.."
step() {  # NAME CMD...: runs CMD and prints how long it took
  local t0=$SECONDS
  echo "== $1"
  shift
  "$@"
  echo "== $((SECONDS - t0)) s"
}
step "packages" bash scripts/install_deps.sh
step "build" bash scripts/build.sh
step "Kokkos 3.4.01 Serial + OpenMP" bash scripts/build_kokkos.sh build/_deps/kokkos-openmp
step "kernel library on OpenMP" bash -c 'cmake -S kernels -B build/_deps/kernels-openmp -G Ninja \
  -DCMAKE_BUILD_TYPE=Release -DKokkos_ROOT="$PWD/build/_deps/kokkos-openmp" \
  -DEMC_KERNELS_TEST_PREFIX=kokkos_openmp. -DEMC_KERNELS_TEST_THREADS=2 -DEMC_KERNELS_BENCH=OFF \
  && cmake --build build/_deps/kernels-openmp -j "$(nproc)"'
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
step "default suite" bash -c 'cd build && ctest --output-on-failure -j 2'
if [ "${EMC_SANITIZE:-1}" = 1 ]; then
  step "unit tests under ASan + UBSan" bash scripts/sanitize.sh --unit
fi
if [ "${EMC_TIDY:-1}" = 1 ]; then
  step "clang-tidy on the changed files" bash scripts/run_clang_tidy.sh --changed
fi
