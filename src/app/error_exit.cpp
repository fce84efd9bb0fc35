#include "emcontact/app/error_exit.hpp"

#include <chrono>
#include <cstdio>
#include <thread>

#include "emcontact/os/signals.hpp"

namespace emc::app {

ErrorExit::ErrorExit() {
  // a communicator of its own: the barrier below must not match a collective that other
  // ranks are blocked in
  MPI_Comm_dup(MPI_COMM_WORLD, &comm_);
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
}

ErrorExit::~ErrorExit() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized && comm_ != MPI_COMM_NULL) MPI_Comm_free(&comm_);
}

int ErrorExit::fail(const std::string& message, int code, double wait_seconds) const {
  const std::string line = "error: " + message + "\n";
  os::signals_ending(code);
  if (size_ == 1) {
    std::fputs(line.c_str(), stderr);
    return code;
  }
  MPI_Request req;
  MPI_Ibarrier(comm_, &req);
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(wait_seconds);
  int done = 0;
  while (!done && std::chrono::steady_clock::now() < until) {
    MPI_Test(&req, &done, MPI_STATUS_IGNORE);
    if (!done) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (done) {  // collective: every rank has the error, rank 0 says it
    if (rank_ == 0) std::fputs(line.c_str(), stderr);
    return code;
  }
  // the other ranks are elsewhere (most likely blocked in a collective): end them all
  std::fputs(line.c_str(), stderr);
  std::fflush(stderr);
  MPI_Abort(MPI_COMM_WORLD, code);
  return code;
}

}  // namespace emc::app
