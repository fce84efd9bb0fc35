#pragma once
// A checkpoint is read back only into the model it was written for, and only with values that
// fit it: the model's fingerprint (sizes, bodies, materials, contact pairs, a hash of the
// geometry) is stored in it, and every index and size is checked against the input's model.
#include <array>
#include <string>
#include <vector>

#include "emcontact/app/simulation.hpp"
#include "emcontact/contact/active.hpp"
#include "emcontact/contact/pairs.hpp"
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

/// The scales of the monitored quantities of a state, against which a recomputation's round-off
/// is measured: energy K + W + |Pi|, momentum sqrt(2 M K) (>= sum_A m_A |V_A|), length the
/// largest |x_A| (so J <= length * momentum, |centre of mass| <= length).
struct MonitorScales {
  double energy = 0, momentum = 0, length = 0;
};

/// docs/user-guide.md, "Checkpoints and restart": the restored state's monitors `mine` (computed
/// from the checkpoint's u and V as a step's row is) against `row`, the kept monitors row of the
/// checkpoint's step, which was computed from the same state when it was written: the kinetic,
/// elastic, potential and total energy, L, J and the centre of mass agree within kRestoreTolerance
/// of their scales, or the checkpoint belongs to another run of the same model (another initial
/// velocity, say). Throws emc::Error naming `path`, the quantity, both values and `monitors`.
void check_restored_monitors(const output::MonitorRow& mine, const MonitorScales& scales,
                             const output::MonitorRow& row, const std::string& path,
                             const std::string& monitors);

/// An active entry `a` of `pair` restored from a checkpoint lies at its facet point: `d` the
/// distance from its slave to its facet's point at xi and the facet's longest edge
/// (contact::Contact::facet_point_distances) in the checkpoint's configuration. Allowed: the
/// pair's max penetration (the deepest gap of an activation, kept by full stick and
/// frictionless alike) plus twice the edge extension of activation times the facet's size (the
/// clamp of xi onto the facet), plus round-off. Throws emc::Error naming `path` otherwise (an
/// entry moved onto another facet).
void check_facet_point(const contact::Active& a, const contact::Pair& pair,
                       const std::array<double, 2>& d, const std::string& path);

/// Relative to the quantity's scale: the same state recomputed on another rank count sums its
/// elements in another order (about sqrt(elements) x 1e-16 of the scale; 1e-9 holds to 1e8
/// elements even at the worst-case n x 1e-16), while a different run differs at O(1).
constexpr double kRestoreTolerance = 1e-9;

}  // namespace emc::app
