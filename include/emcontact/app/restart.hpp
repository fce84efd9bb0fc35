#pragma once
// Checkpoint and restart of a whole simulation (Output/checkpoint every, --restart).
#include <string>
#include <vector>

#include "emcontact/app/root_gather.hpp"
#include "emcontact/app/simulation.hpp"
#include "emcontact/output/checkpoint.hpp"
#include "emcontact/output/monitors.hpp"
#include "emcontact/output/open_directory.hpp"

namespace emc::app {

/// Writes the complete state of `sim` to the file `name` of `dir` (collective: every rank writes
/// its block of the per-node values, `dofs` the block's gather, output::block_of; `dir` is every
/// rank's output::shared_directory; atomically).
void save_checkpoint(const Simulation& sim, const RootGather& dofs, const output::Directory& dir,
                     const std::string& name);

/// What --restart continues from: the checkpoint (this rank's block of the per-node values, the
/// rest whole) and the monitors of its directory up to its step (on rank 0; empty elsewhere).
struct RestartInput {
  output::Checkpoint checkpoint;
  std::vector<output::MonitorRow> rows;
};

/// Reads the checkpoint `path` and the monitors.csv beside it and checks them completely, before
/// anything is written (collective). Throws InputError on every rank with the lowest failing
/// rank's message naming the file if
/// the checkpoint cannot be read, was written for another model (fingerprint), is corrupt or
/// forged (checksum, a dataset of another shape, an index, size or value that does not fit, see
/// check_checkpoint), disagrees with its monitors row, or is at or past Time/end.
RestartInput read_restart(const Simulation& sim, const std::string& path);

/// Restores the state of `sim` from `in` (collective); the preconditioner starts fresh, as after
/// a checkpoint. A changed Time/dt applies from the restart on (a note says so). Returns the
/// monitors row of step 0 (E0, on every rank); D goes on from the checkpoint step's row.
output::MonitorRow apply_restart(Simulation& sim, const RootGather& dofs, RestartInput& in,
                                 const std::string& path);

/// SIGTERM, SIGINT, SIGHUP: a restart from a checkpoint of the regular grid (`Output/checkpoint
/// every`) continues exactly as the uninterrupted run (both rebuild the preconditioner there); one
/// written at another step would not (the uninterrupted run reuses an older preconditioner).
/// So the checkpoint of step `kept` (>= 0: checkpoint.h5 of `dir` holds it) stays and the steps
/// after it are recomputed; with none (`kept` < 0) the current state is written. Returns the
/// message.
std::string stop_checkpoint(const Simulation& sim, const RootGather& dofs,
                            const output::Directory& dir, long kept);
/// True if `a` and `b` name the same existing file.
bool same_file(const std::string& a, const std::string& b);

/// The monitor rows kept by a restart from a checkpoint of step `step` must be steps 0, 1, ...,
/// `step` without a gap, repeat or negative step; throws emc::Error naming `file` and what is
/// wrong (the first missing, repeated, out-of-order or negative step).
void check_monitor_steps(const std::vector<output::MonitorRow>& rows, long step,
                         const std::string& file);

}  // namespace emc::app
