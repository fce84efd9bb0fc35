#include "emcontact/app/signals.hpp"

#include <unistd.h>

#include <csignal>

#include "emcontact/time/interrupt.hpp"

namespace emc::app {
namespace {

volatile std::sig_atomic_t g_rank = 0;
volatile std::sig_atomic_t g_in_loop = 0;

extern "C" void on_sigterm(int) {
  if (g_in_loop) {
    time::stop_flag() = 1;
    return;
  }
  static const char msg[] =
      "error: stopped by SIGTERM during setup (before the first step: nothing to restart "
      "from)\n";
  if (g_rank == 0) {
    const ssize_t n = write(STDERR_FILENO, msg, sizeof msg - 1);
    (void)n;
  }
  _exit(1);
}

}  // namespace

void install_sigterm_handler(int rank) {
  g_rank = rank;
  std::signal(SIGTERM, on_sigterm);
}

void sigterm_stops_time_loop() {
  g_in_loop = 1;
}

}  // namespace emc::app
