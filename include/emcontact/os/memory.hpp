#pragma once
// The memory of a run: the C library's allocator settings for a long implicit run (freed memory
// is kept for the next allocation of the same size instead of being returned to the system and
// faulted in again); the memory a model needs, checked against what this process can get before
// the meshes are built; and the one-line message of a run that ran out of memory anyway.
#include <exception>
#include <string>
#include <vector>

#include "emcontact/types.hpp"

namespace emc::os {

/// With glibc, and unless GLIBC_TUNABLES is set (the user's own malloc settings win): no
/// allocation is served by its own mmap, and the heap's free top is never trimmed. Every Newton
/// iterate allocates and frees the same vectors and matrices; glibc would map the large ones
/// afresh (zeroed pages, one fault per page) and trim the heap after each free. Returns whether
/// the settings were made. Call before anything allocates much (before MPI starts).
bool keep_freed_memory();

/// What a run allocates once its meshes are built (the matrices, vectors and preconditioner
/// of the default iterative solvers, the solver packages' set-up): a base and bytes per
/// tetrahedron shared by the ranks, fitted to the tumbling box on one rank at 6042, 44736 and
/// 205753 tets. Mapped: its address space (VmSize) grew from then on by 131, 226 and 577 MB
/// (115 MB + 2290 bytes per tet; GMRES's Krylov basis of 300 vectors is mapped whole and
/// touched only as far as the iterations go). Resident: its resident size grew by 18, 49 and
/// 236 MB (11 MB + 1090 bytes per tet). Rounded up.
constexpr double kMappedBaseBytes = 120e6;
constexpr double kMappedBytesPerTet = 2300;
constexpr double kResidentBaseBytes = 20e6;
constexpr double kResidentBytesPerTet = 1200;
/// Bytes per tetrahedron a rank holds whatever the rank count, rounded up: rank 0's whole mesh
/// during the set-up (about 60), the other ranks' broadcast nodes and surfaces then, and on
/// every rank what is not divided among the ranks (ghosts, interface rows, surfaces: R = 50 in
/// perf/README.md's fit).
constexpr double kReplicatedBytesPerTet = 100;

/// Bytes one of `ranks` ranks needs beyond its start-up for a model of `tets` tetrahedra:
/// resident memory, or if `mapped` address space.
double bytes_needed(double tets, int ranks, bool mapped);

/// Throws InputError "<what>, which would need about X GiB per rank ... more than the Y GiB
/// this rank can still get (<source>); allowed: a coarser mesh ..." if the resident bytes
/// needed exceed /proc/meminfo's MemAvailable shared by the `ranks_on_node` ranks of this
/// machine, or the mapped bytes needed exceed RLIMIT_AS (ulimit -v) less this process's mapped
/// size (VmSize). `what` names the model ("file: Bodies: the meshes would hold about 737847
/// tetrahedra in all (box: 737847)").
void check_memory(double tets, int ranks, int ranks_on_node, const std::string& what);

/// Keeps the model's size (and the memory available now) for out_of_memory_message.
void note_model_size(long long tets, long long nodes, int ranks, int ranks_on_node);

/// True for std::bad_alloc and Kokkos' allocation failure (a std::runtime_error in Kokkos 3.4).
bool is_out_of_memory(const std::exception& e);

/// One line for a run that ran out of memory: the model noted (tets, nodes, ranks), the memory
/// it needs and what was available, and what to change.
std::string out_of_memory_message(const std::exception& e);

/// This process's peak resident set so far (getrusage's ru_maxrss), in bytes.
double peak_resident_bytes();

/// The summary line of the ranks' peak resident sets (bytes, rank 0 first), in MiB (2^20
/// bytes): "emcontact: peak resident memory per rank: 466 379 379 370 MiB (rank 0 first)" for
/// up to 8 ranks; for more, "emcontact: peak resident memory per rank: min 370, median 379, max
/// 466, rank 0 466 MiB (64 ranks)".
std::string peak_memory_line(const std::vector<double>& bytes_per_rank);

/// Gathers every rank's peak_resident_bytes to rank 0 (collective); its summary line on rank 0,
/// "" elsewhere.
std::string gather_peak_memory(const Comm& comm);

}  // namespace emc::os
