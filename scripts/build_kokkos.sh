#!/usr/bin/env bash
# Builds Kokkos 3.4.01 with the Serial and OpenMP backends from Debian's own `trilinos` source
# package (the Kokkos that trilinos-all-dev bundles, built there Serial only) and installs it
# into a prefix, for the standalone kernel library (kernels/, docs/kernels.md) and its tests on
# two threads. Nothing is installed system-wide and the machine's apt lists stay untouched: a
# private deb-src list, lists and cache live in the work directory.
#
#   bash scripts/build_kokkos.sh [PREFIX]     (default PREFIX=build/_deps/kokkos-openmp)
#
# Skipped when PREFIX already holds an installed Kokkos. Environment: EMC_KOKKOS_WORK (work
# directory, default build/_deps/kokkos-src; removed after a successful install), EMC_JOBS
# (compile jobs, default nproc). Needs network access to deb.debian.org and dpkg-dev's
# apt-get source; about 25 s on 2 cores (166 MB download, 12 MB extracted).
set -euo pipefail
cd "$(dirname "$0")/.."
PREFIX=$(realpath -m "${1:-build/_deps/kokkos-openmp}")
WORK=$(realpath -m "${EMC_KOKKOS_WORK:-build/_deps/kokkos-src}")
JOBS=${EMC_JOBS:-$(nproc)}

if [ -f "$PREFIX/lib/cmake/Kokkos/KokkosConfig.cmake" ]; then
  echo "build_kokkos: Kokkos already installed in $PREFIX"
  exit 0
fi

# 1. Debian's source package through a private deb-src list.
mkdir -p "$WORK/apt/lists/partial" "$WORK/apt/cache/archives/partial" "$WORK/apt/parts"
echo "deb-src [signed-by=/usr/share/keyrings/debian-archive-keyring.gpg]" \
  "http://deb.debian.org/debian bookworm main" > "$WORK/apt/sources.list"
apt=(apt-get -q -o "Dir::Etc::SourceList=$WORK/apt/sources.list"
  -o "Dir::Etc::SourceParts=$WORK/apt/parts" -o "Dir::State::Lists=$WORK/apt/lists"
  -o "Dir::Cache=$WORK/apt/cache" -o "APT::Sandbox::User=root")
cd "$WORK"
if ! ls trilinos_*.orig.tar.gz > /dev/null 2>&1; then
  "${apt[@]}" update > /dev/null
  "${apt[@]}" source --download-only trilinos > /dev/null
fi
# 2. Kokkos alone (Debian's patches of it only drop TriBITS test declarations: not needed).
rm -rf kokkos
tar xzf trilinos_*.orig.tar.gz --wildcards '*/packages/kokkos/*'
mv ./*/packages/kokkos kokkos
grep -q 'Kokkos_VERSION_MINOR 4' kokkos/CMakeLists.txt || {
  echo "build_kokkos: $WORK/kokkos is not Kokkos 3.4" >&2
  exit 1
}
# 3. Serial + OpenMP, static libraries, no tests.
cmake -S kokkos -B kbuild -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_STANDARD=17 \
  -DCMAKE_INSTALL_PREFIX="$PREFIX" -DKokkos_ENABLE_SERIAL=ON -DKokkos_ENABLE_OPENMP=ON \
  -DKokkos_ENABLE_TESTS=OFF > /dev/null
cmake --build kbuild -j "$JOBS" > /dev/null
cmake --install kbuild > /dev/null
cd / && rm -rf "$WORK"
echo "build_kokkos: Kokkos 3.4.01 (Serial, OpenMP) installed in $PREFIX"
