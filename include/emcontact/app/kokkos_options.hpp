#pragma once
// Kokkos' own command-line options (--kokkos-threads=N and the like) are parsed by
// Kokkos::initialize, which throws an uncaught exception on a malformed value: they are
// checked here first, before MPI and Kokkos start.

namespace emc::app {

/// Throws InputError naming the first integer option of Kokkos' with a value Kokkos would not
/// take (not a decimal integer, out of int's range, below its least value).
void check_kokkos_options(int argc, char** argv);

}  // namespace emc::app
