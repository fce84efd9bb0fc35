#!/usr/bin/env bash
# Installs every Debian 12 package emcontact needs to build, test and plot (run as root).
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
$SUDO apt-get update -q
# libptscotch-dev must be named: Trilinos' CMake configs link it but no package depends on it.
# libmumps-dev (MUMPS's MPI build, Solver/Linear/type = mumps; it brings libmumps-headers-dev)
# comes with trilinos-all-dev but is named because emcontact calls it directly.
# libsuitesparse-dev: UMFPACK, Solver/Linear/type = umfpack (one rank).
# libopenblas0-serial: Debian's alternatives then give every BLAS and LAPACK user (MUMPS's dense
# kernels above all) OpenBLAS, single-threaded, instead of the reference BLAS (the hollow
# cylinders 98 s against 112 s, perf/README.md "MUMPS").
# clang-format and clang-tidy (Debian's, 14): the `format` test and scripts/run_clang_tidy.sh.
# python3-paraview (pvpython; it pulls paraview), xvfb and xauth (xvfb-run: Debian's ParaView
# renders through X only) are for tools/render_fields.py and the render_ball_impact test;
# python3-paraview and xauth are only recommends (of paraview, of xvfb), hence named.
$SUDO apt-get install -y -q --no-install-recommends \
  g++ cmake ninja-build git clang-format clang-tidy \
  trilinos-all-dev libptscotch-dev libmumps-dev libsuitesparse-dev libopenblas0-serial libopenmpi-dev openmpi-bin \
  libhdf5-openmpi-dev \
  libgmsh-dev gmsh libgtest-dev libbenchmark-dev \
  python3-matplotlib python3-numpy python3-h5py \
  python3-paraview xvfb xauth
