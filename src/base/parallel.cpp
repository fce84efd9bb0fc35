#include "emcontact/parallel.hpp"

#include <Teuchos_DefaultMpiComm.hpp>

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
