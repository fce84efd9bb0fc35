#include "emcontact/parallel.hpp"

#include <Teuchos_DefaultMpiComm.hpp>

namespace emc {

std::vector<double> allgather(const Comm& comm, const std::vector<double>& mine) {
  const auto& mpi = dynamic_cast<const Teuchos::MpiComm<int>&>(comm);
  const int np = comm.getSize();
  int n = static_cast<int>(mine.size());
  std::vector<int> counts(np), displs(np, 0);
  MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, *mpi.getRawMpiComm());
  for (int p = 1; p < np; ++p) displs[p] = displs[p - 1] + counts[p - 1];
  std::vector<double> all(displs[np - 1] + counts[np - 1]);
  MPI_Allgatherv(mine.data(), n, MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE,
                 *mpi.getRawMpiComm());
  return all;
}

}  // namespace emc
