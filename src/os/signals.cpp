#include "emcontact/os/signals.hpp"

#include <unistd.h>

#include <csignal>

#include "emcontact/time/interrupt.hpp"

namespace emc::os {
namespace {

enum Phase : int { kStarting, kSetup, kTimeLoop, kEnding };

volatile std::sig_atomic_t g_rank = 0;
volatile std::sig_atomic_t g_phase = kStarting;
volatile std::sig_atomic_t g_held = 0;       ///< a signal that came while starting
volatile std::sig_atomic_t g_exit_code = 1;  ///< the exit code of a run ending with an error

constexpr char kTerm[] =
    "error: stopped by SIGTERM during setup (before the first step: nothing to restart from)\n";
constexpr char kInt[] =
    "error: stopped by SIGINT during setup (before the first step: nothing to restart from)\n";
constexpr char kHup[] =
    "error: stopped by SIGHUP during setup (before the first step: nothing to restart from)\n";

/// Async-signal-safe: write(2) of a constant (rank 0), then _exit.
[[noreturn]] void exit_during_setup(int signal) {
  if (g_rank == 0) {
    const char* msg = signal == SIGINT ? kInt : signal == SIGHUP ? kHup : kTerm;
    const std::size_t len = signal == SIGINT   ? sizeof kInt
                            : signal == SIGHUP ? sizeof kHup
                                               : sizeof kTerm;
    const ssize_t n = write(STDERR_FILENO, msg, len - 1);
    (void)n;
  }
  _exit(1);
}

extern "C" void on_stop_signal(int signal) {
  if (g_phase == kEnding) _exit(g_exit_code);  // its error is said already: no second line
  if (g_phase == kTimeLoop) {
    time::stop_flag() = signal;
  } else if (g_phase == kStarting) {
    g_held = signal;
  } else {
    exit_during_setup(signal);
  }
}

void install() {
  for (const int signal : {SIGTERM, SIGINT, SIGHUP}) {
    struct sigaction old {};
    if (sigaction(signal, nullptr, &old) != 0) continue;
    if (old.sa_handler == SIG_IGN && signal != SIGTERM) continue;  // nohup, background jobs
    struct sigaction sa {};
    sa.sa_handler = on_stop_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;  // interrupted reads and writes go on
    sigaction(signal, &sa, nullptr);
  }
}

}  // namespace

void install_stop_handlers() {
  install();
}

void stop_handlers_ready(int rank) {
  g_rank = rank;
  install();
  g_phase = kSetup;
  if (g_held != 0) exit_during_setup(g_held);
}

void signals_stop_time_loop() {
  g_phase = kTimeLoop;
}

void signals_ending(int code) {
  g_exit_code = code;
  g_phase = kEnding;
}

}  // namespace emc::os
