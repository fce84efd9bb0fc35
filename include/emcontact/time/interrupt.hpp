#pragma once
// A request to stop the time loop (SIGTERM, SIGINT or SIGHUP): set from a signal handler,
// checked collectively between steps, at every Newton iterate and at every operator
// application of a Krylov solve, so that a long step (many iterations, step cuts, a long linear
// solve) stops too and every rank stops at the same point.
#include <csignal>

#include "emcontact/error.hpp"
#include "emcontact/types.hpp"

namespace emc::time {

/// The name of a stop signal: "SIGTERM", "SIGINT", "SIGHUP" (else "a signal").
const char* signal_name(int signal);

/// The signal every rank agreed on at the last stop_requested() that returned true (SIGTERM
/// before any).
int stop_signal();

/// Thrown (on every rank) by a Newton iteration or the time loop when a stop was requested:
/// the state is still the last accepted step.
class Interrupted : public Error {
 public:
  Interrupted() : Error(std::string("stopped by ") + signal_name(stop_signal())) {}
};

/// The time loop stopped by a signal after saving what a restart needs: the message says where
/// to continue from. Handled by type (never by its text).
class Stopped : public RunError {
 public:
  explicit Stopped(const std::string& what) : RunError(what) {}
};

/// The flag a signal handler sets to the signal's number (async-signal-safe); 0: none.
volatile std::sig_atomic_t& stop_flag();

/// Collective: true on every rank if any rank's flag is set (stop_signal() then names the same
/// signal on every rank).
bool stop_requested(const Comm& comm);

}  // namespace emc::time
