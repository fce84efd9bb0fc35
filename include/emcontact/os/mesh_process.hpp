#pragma once
// Rank 0 builds the meshes in a child process (fork), which streams them back through a pipe and
// exits: Gmsh's memory (about 520 bytes per tet at its peak, more than the model it makes) goes
// back to the system before the solver allocates, so rank 0's peak is the solver's like every
// other rank's instead of the mesher's.
#include <functional>
#include <string>
#include <vector>

#include "emcontact/mesh/body_mesh.hpp"

namespace emc::os {

/// Runs `build` in a child process and returns its meshes. An exception in the child is thrown
/// again here as emc::InputError with its message (an out-of-memory one as
/// out_of_memory_message says); a child that ends without a result (killed: by the kernel's
/// out-of-memory killer, a signal) as emc::Error naming how it ended. Where no process can be
/// started (fork or pipe fails) `build` runs here instead.
std::vector<mesh::BodyMesh> build_in_child_process(
    const std::function<std::vector<mesh::BodyMesh>()>& build);

}  // namespace emc::os
