#include "emcontact/time/interrupt.hpp"

#include <Teuchos_CommHelpers.hpp>

namespace emc::time {
namespace {

int g_agreed = SIGTERM;

}  // namespace

const char* signal_name(int signal) {
  switch (signal) {
    case SIGTERM:
      return "SIGTERM";
    case SIGINT:
      return "SIGINT";
    case SIGHUP:
      return "SIGHUP";
    default:
      return "a signal";
  }
}

int stop_signal() {
  return g_agreed;
}

volatile std::sig_atomic_t& stop_flag() {
  static volatile std::sig_atomic_t flag = 0;
  return flag;
}

bool stop_requested(const Comm& comm) {
  // the largest signal number of any rank: every rank names the same signal
  int mine = stop_flag(), any = 0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, 1, &mine, &any);
  if (any != 0) g_agreed = any;
  return any != 0;
}

}  // namespace emc::time
