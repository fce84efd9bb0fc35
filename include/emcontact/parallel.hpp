#pragma once
// Small collective helpers shared by the modules.
#include <mpi.h>

#include <Teuchos_CommHelpers.hpp>
#include <algorithm>
#include <vector>

#include "emcontact/types.hpp"

namespace emc {

/// The MPI communicator of `comm`; MPI_COMM_SELF for a serial Teuchos communicator (one rank).
MPI_Comm raw_comm(const Comm& comm);

/// Every rank's doubles, concatenated in rank order, on every rank (MPI_Allgatherv).
std::vector<double> allgather(const Comm& comm, const std::vector<double>& mine);
/// Every rank's ints, concatenated in rank order, on every rank (MPI_Allgatherv).
std::vector<int> allgather(const Comm& comm, const std::vector<int>& mine);

/// Rank 0's vector (trivially copyable elements) on every rank, in chunks below INT_MAX bytes.
template <class T>
void broadcast_vector(const Comm& comm, std::vector<T>& v) {
  long long n = static_cast<long long>(v.size());
  Teuchos::broadcast(comm, 0, 1, &n);
  v.resize(n);
  const long long bytes = n * static_cast<long long>(sizeof(T));
  char* p = reinterpret_cast<char*>(v.data());
  for (long long off = 0; off < bytes; off += (1 << 30)) {
    const int len = static_cast<int>(std::min<long long>(1 << 30, bytes - off));
    Teuchos::broadcast(comm, 0, len, p + off);
  }
}

}  // namespace emc

namespace emc {

/// Sends sends[r] to rank r and returns what every rank sent to me, in rank order
/// (MPI_Alltoall of the counts, then MPI_Alltoallv).
std::vector<int> exchange_ints(const Comm& comm, const std::vector<std::vector<int>>& sends);

}  // namespace emc
