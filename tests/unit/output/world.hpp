#pragma once
// MPI_COMM_WORLD helpers of the output module's parallel tests.
#include <mpi.h>

#include <string>

namespace emc::output::testing {

inline int world_rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

inline int world_size() {
  int n = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &n);
  return n;
}

/// Rank 0's string (a temporary directory's path) on every rank.
inline std::string from_rank0(std::string s) {
  int n = static_cast<int>(s.size());
  MPI_Bcast(&n, 1, MPI_INT, 0, MPI_COMM_WORLD);
  s.resize(n);
  MPI_Bcast(s.data(), n, MPI_CHAR, 0, MPI_COMM_WORLD);
  return s;
}

}  // namespace emc::output::testing
