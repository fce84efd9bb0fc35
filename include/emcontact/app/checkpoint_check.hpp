#pragma once
// A checkpoint is read back only into the model it was written for, and only with values that
// fit it: the model's fingerprint (sizes, bodies, materials, contact pairs, a hash of the
// geometry) is stored in it, and every index and size is checked against the input's model.
#include <string>
#include <vector>

#include "emcontact/app/simulation.hpp"
#include "emcontact/output/checkpoint.hpp"
#include "emcontact/output/monitors.hpp"

namespace emc::app {

/// The fingerprint of `sim`'s model, one "key: value" per line.
std::string model_fingerprint(const Simulation& sim);

/// Throws emc::Error "<path>: ..." naming the first line of the stored fingerprint `model` that
/// differs from `sim`'s.
void check_model(const std::string& model, const Simulation& sim, const std::string& path);

/// Throws emc::Error "<path>: ..." naming the first thing of `c` that does not fit `sim`: the
/// model (the first differing fingerprint line), a scalar (not finite, out of range, a step
/// size above the Time/dt it was written with), an array's length, an active contact entry's
/// node, pair, facet, coordinates (not finite, or xi outside its facet beyond the edge
/// extension of activation), an entry listed twice, an entry's state.
void check_checkpoint(const output::Checkpoint& c, const Simulation& sim, const std::string& path);

/// A checkpoint is written after the monitors row of its step (a SIGKILL between leaves the
/// row, never the checkpoint alone): `rows` (steps 0 to the checkpoint's) have increasing times,
/// and the checkpoint's t and last step size are the last row's time and dt. Throws emc::Error
/// naming `path` (or `monitors`) and the disagreement.
void check_against_monitors(const output::Checkpoint& c,
                            const std::vector<output::MonitorRow>& rows, const std::string& path,
                            const std::string& monitors);

}  // namespace emc::app
