#pragma once
// Ending a run after an error on any number of ranks without a hang. Most errors are
// collective (every rank throws at the same point: bad input, a failed step, SIGTERM): rank 0
// prints the message and every rank returns. An error on one rank only (rank 0 cannot write
// its output) leaves the other ranks waiting in a collective forever: that rank prints its
// message and aborts the job (MPI_Abort, so mpiexec ends every rank with the same exit code).
#include <mpi.h>

#include <string>

namespace emc::app {

class ErrorExit {
 public:
  /// Collective: call on every rank at start-up (after MPI_Init).
  ErrorExit();
  ~ErrorExit();
  ErrorExit(const ErrorExit&) = delete;
  ErrorExit& operator=(const ErrorExit&) = delete;

  /// Reports `message` ("error: " + message on one line) and returns `code` if every rank
  /// reaches this call within `wait_seconds` (rank 0 prints); otherwise prints it on this rank
  /// and aborts the job with `code`.
  int fail(const std::string& message, int code, double wait_seconds = 5.0) const;

 private:
  MPI_Comm comm_ = MPI_COMM_NULL;  ///< of the error agreement, a duplicate of MPI_COMM_WORLD
  int rank_ = 0, size_ = 1;
};

}  // namespace emc::app
