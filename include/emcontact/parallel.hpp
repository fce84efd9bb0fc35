#pragma once
// Small collective helpers shared by the modules.
#include <mpi.h>

#include <Teuchos_CommHelpers.hpp>
#include <algorithm>
#include <functional>
#include <string>
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

namespace emc {

/// This rank of `comm`; 0 for MPI_COMM_SELF without asking MPI.
int rank_of(MPI_Comm comm);
/// The number of ranks of `comm`; 1 for MPI_COMM_SELF without asking MPI (a serial program that
/// never starts MPI writes its files with MPI_COMM_SELF).
int ranks_of(MPI_Comm comm);
/// True on every rank when `ok` on every rank (collective).
bool all_ok(MPI_Comm comm, bool ok);
/// `root`'s string on every rank (collective).
std::string broadcast(MPI_Comm comm, const std::string& s, int root = 0);
/// The error text of the lowest rank that has one, on every rank ("" if none; collective).
std::string first_error(MPI_Comm comm, const std::string& error);

/// Collective over `comm`: runs `work` on rank 0 only; if it throws, every rank throws
/// emc::Error with its message (so that the other ranks do not wait for rank 0 forever).
void on_root(MPI_Comm comm, const std::function<void()>& work);

/// Collective over `comm`: runs `work` on every rank; if it throws on any, every rank throws
/// emc::Error with the lowest failing rank's message (a refusal found on one rank only, or on
/// each rank for its own part, stops every rank with one line and no hang). One rank: `work`
/// alone, its exception as thrown.
void on_every_rank(MPI_Comm comm, const std::function<void()>& work);

/// The same over a Teuchos communicator (the modules' `Comm`).
inline void on_every_rank(const Comm& comm, const std::function<void()>& work) {
  on_every_rank(raw_comm(comm), work);
}
inline void on_root(const Comm& comm, const std::function<void()>& work) {
  on_root(raw_comm(comm), work);
}

}  // namespace emc
