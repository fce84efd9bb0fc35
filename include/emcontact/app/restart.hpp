#pragma once
// Checkpoint and restart of a whole simulation (Output/checkpoint every, --restart).
#include <string>

#include "emcontact/app/root_gather.hpp"
#include "emcontact/app/simulation.hpp"
#include "emcontact/output/monitors.hpp"

namespace emc::app {

/// Writes the complete state of `sim` to `path` (collective; rank 0 writes, atomically).
void save_checkpoint(const Simulation& sim, const RootGather& dofs, const std::string& path);

/// Restores the state of `sim` from `path` (collective). Throws emc::Error naming the file if
/// it cannot be read, was written for another model (fingerprint), is corrupt (checksum, an
/// index or size that does not fit), or is at or past Time/end. A changed Time/dt applies
/// from the restart on (a note says so).
void load_checkpoint(Simulation& sim, const RootGather& dofs, const std::string& path);

/// SIGTERM, SIGINT, SIGHUP: a restart from a checkpoint of the regular grid (`Output/checkpoint
/// every`) continues exactly as the uninterrupted run (both rebuild the preconditioner there); one
/// written at another step would not (the uninterrupted run reuses an older preconditioner).
/// So the checkpoint of step `kept` (>= 0: `path` holds it) stays and the steps after it are
/// recomputed; with none (`kept` < 0) the current state is written. Returns the message.
std::string stop_checkpoint(const Simulation& sim, const RootGather& dofs, const std::string& path,
                            long kept);
/// True if `a` and `b` name the same existing file.
bool same_file(const std::string& a, const std::string& b);

/// The monitor rows kept by a restart must be steps 0, 1, ..., n without a gap or repeat;
/// throws emc::Error naming `file` and the first missing (or repeated) step.
void check_monitor_steps(const std::vector<output::MonitorRow>& rows, const std::string& file);

}  // namespace emc::app
