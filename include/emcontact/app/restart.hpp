#pragma once
// Checkpoint and restart of a whole simulation (Output/checkpoint every, --restart).
#include <string>

#include "emcontact/app/root_gather.hpp"
#include "emcontact/app/simulation.hpp"

namespace emc::app {

/// Writes the complete state of `sim` to `path` (collective; rank 0 writes, atomically).
void save_checkpoint(const Simulation& sim, const RootGather& dofs, const std::string& path);

/// Restores the state of `sim` from `path` (collective). Throws emc::Error naming the file if
/// it cannot be read or does not fit the mesh of the input.
void load_checkpoint(Simulation& sim, const RootGather& dofs, const std::string& path);

}  // namespace emc::app
