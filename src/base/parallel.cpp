#include "emcontact/parallel.hpp"

#include <Teuchos_DefaultMpiComm.hpp>
#include <climits>
#include <exception>

#include "emcontact/error.hpp"

namespace emc {

MPI_Comm raw_comm(const Comm& comm) {
  const auto* mpi = dynamic_cast<const Teuchos::MpiComm<int>*>(&comm);
  return mpi != nullptr ? (*mpi->getRawMpiComm())() : MPI_COMM_SELF;
}

namespace {

template <class T>
std::vector<T> allgather_as(const Comm& comm, const std::vector<T>& mine, MPI_Datatype type) {
  const int np = comm.getSize();
  int n = static_cast<int>(mine.size());
  std::vector<int> counts(np), displs(np, 0);
  MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, raw_comm(comm));
  for (int p = 1; p < np; ++p) displs[p] = displs[p - 1] + counts[p - 1];
  std::vector<T> all(displs[np - 1] + counts[np - 1]);
  MPI_Allgatherv(mine.data(), n, type, all.data(), counts.data(), displs.data(), type,
                 raw_comm(comm));
  return all;
}

}  // namespace

std::vector<double> allgather(const Comm& comm, const std::vector<double>& mine) {
  return allgather_as(comm, mine, MPI_DOUBLE);
}

std::vector<int> allgather(const Comm& comm, const std::vector<int>& mine) {
  return allgather_as(comm, mine, MPI_INT);
}

}  // namespace emc

namespace emc {

std::vector<int> exchange_ints(const Comm& comm, const std::vector<std::vector<int>>& sends) {
  const int np = comm.getSize();
  std::vector<int> scount(np), rcount(np), sdispl(np, 0), rdispl(np, 0), flat;
  for (int p = 0; p < np; ++p) {
    scount[p] = static_cast<int>(sends[p].size());
    sdispl[p] = static_cast<int>(flat.size());
    flat.insert(flat.end(), sends[p].begin(), sends[p].end());
  }
  MPI_Alltoall(scount.data(), 1, MPI_INT, rcount.data(), 1, MPI_INT, raw_comm(comm));
  for (int p = 1; p < np; ++p) rdispl[p] = rdispl[p - 1] + rcount[p - 1];
  std::vector<int> got(rdispl[np - 1] + rcount[np - 1]);
  MPI_Alltoallv(flat.data(), scount.data(), sdispl.data(), MPI_INT, got.data(), rcount.data(),
                rdispl.data(), MPI_INT, raw_comm(comm));
  return got;
}

}  // namespace emc

namespace emc {

int rank_of(MPI_Comm comm) {
  int r = 0;
  if (comm != MPI_COMM_SELF) MPI_Comm_rank(comm, &r);
  return r;
}

bool all_ok(MPI_Comm comm, bool ok) {
  int mine = ok ? 1 : 0, all = 0;
  MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_LAND, comm);
  return all == 1;
}

std::string broadcast(MPI_Comm comm, const std::string& s, int root) {
  long long n = static_cast<long long>(s.size());
  MPI_Bcast(&n, 1, MPI_LONG_LONG, root, comm);
  std::string out = rank_of(comm) == root ? s : std::string(static_cast<std::size_t>(n), '\0');
  if (n > 0) MPI_Bcast(out.data(), static_cast<int>(n), MPI_CHAR, root, comm);
  return out;
}

std::string first_error(MPI_Comm comm, const std::string& error) {
  int mine = error.empty() ? INT_MAX : rank_of(comm), first = INT_MAX;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm);
  return first == INT_MAX ? std::string() : broadcast(comm, error, first);
}

int ranks_of(MPI_Comm comm) {
  int n = 1;
  if (comm != MPI_COMM_SELF) MPI_Comm_size(comm, &n);  // a serial program never starts MPI
  return n;
}

void on_root(MPI_Comm comm, const std::function<void()>& work) {
  if (ranks_of(comm) == 1) return work();
  std::string error;
  if (rank_of(comm) == 0) {
    try {
      work();
    } catch (const std::exception& e) {
      error = e.what();
      if (error.empty()) error = "rank 0 failed";
    }
  }
  error = first_error(comm, error);
  if (!error.empty()) throw Error(error);
}

void on_every_rank(MPI_Comm comm, const std::function<void()>& work) {
  if (ranks_of(comm) == 1) return work();
  std::string error;
  try {
    work();
  } catch (const std::exception& e) {
    error = e.what();
    if (error.empty()) error = "rank " + std::to_string(rank_of(comm)) + " failed";
  }
  error = first_error(comm, error);
  if (!error.empty()) throw Error(error);
}

}  // namespace emc
