#!/usr/bin/env bash
# Build the Trilinos packages emcontact needs, with Kokkos' OpenMP backend, from Debian's own
# `trilinos` source package (13.2.0, the same version and patches as trilinos-all-dev), into a prefix.
#
#   bash perf/build_trilinos_openmp.sh [PREFIX]          (default PREFIX=/opt/trilinos-openmp)
#
# Environment: EMC_TRILINOS_SRC (work dir for the sources and the build tree, default /var/tmp/emc-trilinos),
# EMC_JOBS (parallel compile jobs, default nproc). Needs root for apt (deb-src list + build deps).
# Debian's binary packages are Serial-only (see perf/README.md); this build enables OpenMP and
# instantiates only <double, int, long long, OpenMP>. MueLu is left out (its explicit instantiation
# alone takes hours on 2 cores); emcontact then builds without the MueLu preconditioner.
# Then build emcontact against it:
#   cmake -S . -B build-omp -G Ninja -DCMAKE_PREFIX_PATH=PREFIX && cmake --build build-omp
# and run with OMP_NUM_THREADS=N OMP_PROC_BIND=spread OMP_PLACES=threads.
set -euo pipefail
PREFIX=${1:-/opt/trilinos-openmp}
WORK=${EMC_TRILINOS_SRC:-/var/tmp/emc-trilinos}
JOBS=${EMC_JOBS:-$(nproc)}
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO=sudo

# 1. Debian's source package. A private deb-src list, so the machine's own lists stay untouched.
LIST=/etc/apt/sources.list.d/emc-trilinos-src.sources
if [ ! -f "$LIST" ]; then
  $SUDO tee "$LIST" >/dev/null <<'EOF'
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: bookworm
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
EOF
fi
$SUDO apt-get update -qq
$SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
  dpkg-dev cmake ninja-build g++ gfortran libopenmpi-dev openmpi-bin libblas-dev liblapack-dev >/dev/null
mkdir -p "$WORK"
cd "$WORK"
if [ ! -d src ]; then
  apt-get source --download-only trilinos
  dpkg-source -x trilinos_*.dsc src   # unpacks and applies Debian's patches
fi

# 2. Configure: Kokkos OpenMP, ETI for <double, int, long long> only, no tests or examples.
cmake -S src -B build -G Ninja \
  -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX="$PREFIX" \
  -DCMAKE_C_COMPILER=mpicc -DCMAKE_CXX_COMPILER=mpicxx -DCMAKE_Fortran_COMPILER=mpif90 \
  -DCMAKE_CXX_STANDARD=14 -DBUILD_SHARED_LIBS=ON \
  -DTPL_ENABLE_MPI=ON -DTPL_ENABLE_BLAS=ON -DTPL_ENABLE_LAPACK=ON \
  -DTrilinos_ENABLE_ALL_OPTIONAL_PACKAGES=OFF -DTrilinos_ENABLE_ALL_PACKAGES=OFF \
  -DTrilinos_ENABLE_TESTS=OFF -DTrilinos_ENABLE_EXAMPLES=OFF \
  -DTrilinos_ENABLE_Fortran=OFF \
  -DTrilinos_ENABLE_OpenMP=ON -DKokkos_ENABLE_OPENMP=ON -DKokkos_ENABLE_SERIAL=ON \
  -DTrilinos_ENABLE_Teuchos=ON -DTrilinos_ENABLE_Kokkos=ON -DTrilinos_ENABLE_KokkosKernels=ON \
  -DTrilinos_ENABLE_Tpetra=ON -DTrilinos_ENABLE_Belos=ON -DTrilinos_ENABLE_Ifpack2=ON \
  -DTrilinos_ENABLE_Amesos2=ON -DTrilinos_ENABLE_Epetra=OFF -DTrilinos_ENABLE_MueLu=OFF \
  -DTrilinos_ENABLE_Zoltan2=ON -DTrilinos_ENABLE_Xpetra=ON \
  -DTrilinos_ENABLE_EXPLICIT_INSTANTIATION=ON \
  -DTpetra_INST_SERIAL=OFF -DTpetra_INST_OPENMP=ON \
  -DTpetra_INST_INT_INT=OFF -DTpetra_INST_INT_LONG=OFF -DTpetra_INST_INT_LONG_LONG=ON \
  -DTpetra_INST_COMPLEX_DOUBLE=OFF -DTpetra_INST_COMPLEX_FLOAT=OFF -DTpetra_INST_FLOAT=OFF \
  -DTpetra_ENABLE_TSQR=OFF -DAmesos2_ENABLE_KLU2=ON \
  -DTrilinos_ENABLE_SECONDARY_TESTED_CODE=ON

# 3. Build and install.
cmake --build build -j "$JOBS"
cmake --install build
echo "Trilinos with Kokkos OpenMP installed in $PREFIX"
