#pragma once
// A request to stop the time loop (SIGTERM): set from a signal handler, checked collectively
// between steps and at every Newton iterate, so that a long step (many iterations, step cuts)
// stops too and every rank stops at the same point.
#include <csignal>

#include "emcontact/error.hpp"
#include "emcontact/types.hpp"

namespace emc::time {

/// Thrown (on every rank) by a Newton iteration or the time loop when a stop was requested:
/// the state is still the last accepted step.
class Interrupted : public Error {
 public:
  Interrupted() : Error("stopped by SIGTERM") {}
};

/// The flag a signal handler sets (async-signal-safe).
volatile std::sig_atomic_t& stop_flag();

/// Collective: true on every rank if any rank's flag is set.
bool stop_requested(const Comm& comm);

}  // namespace emc::time
