#pragma once
// A checkpoint is read back only into the model it was written for, and only with values that
// fit it: the model's fingerprint (sizes, bodies, materials, contact pairs, a hash of the
// geometry) is stored in it, and every index and size is checked against the input's model.
#include <string>

#include "emcontact/app/simulation.hpp"
#include "emcontact/output/checkpoint.hpp"

namespace emc::app {

/// The fingerprint of `sim`'s model, one "key: value" per line.
std::string model_fingerprint(const Simulation& sim);

/// Throws emc::Error "<path>: ..." naming the first thing of `c` that does not fit `sim`: the
/// model (the first differing fingerprint line), a scalar (not finite, out of range), an
/// array's length, an active contact entry's node, pair, facet or coordinates.
void check_checkpoint(const output::Checkpoint& c, const Simulation& sim, const std::string& path);

}  // namespace emc::app
