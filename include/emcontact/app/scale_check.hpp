#pragma once
// Contact parameters whose scale defeats the contact search: a `max penetration` larger than
// the master surface (its activation window -dmax < g < -1e-12 dmax then misses every real
// penetration) or below the round-off of the gaps (no depth can be told from touching), or a
// rigid surface so much larger than the deformable bodies that the gaps drown in the round-off
// of its coordinates. Each made contact silently vanish.
#include <Teuchos_ParameterList.hpp>
#include <string>
#include <vector>

#include "emcontact/contact/pairs.hpp"
#include "emcontact/fem/model.hpp"

namespace emc::app {

/// Rigid surface bodies may be at most this many times the size (bounding box diagonal) of
/// the deformable bodies together.
constexpr double kMaxRigidScale = 1e6;

/// Throws InputError naming `file` and the parameter if a pair's `max penetration` exceeds its
/// master surface's bounding box diagonal or lies below the round-off of a gap on it
/// (docs/THEORY.md §6.3), or a rigid body's extent exceeds kMaxRigidScale times the deformable
/// bodies' extent.
void check_contact_scales(const fem::Model& model, const std::vector<contact::Pair>& pairs,
                          const std::string& file);

/// Notes the parameters of `params` (validated) that may keep a step of `model` from being
/// solved, for step_failure_hint: a deformable body whose elastic wave crosses more than 1e3
/// elements per step (Time/dt, young, density: the Newton matrix's condition grows as the
/// square), a nearly incompressible one (poisson above 0.499), one that turns by more than
/// 0.5 rad in the smallest step (angular velocity, Time/dt, Time/max step cuts) or that
/// centrifugal stress tears apart, or bodies that fly so far by Time/end (velocity, gravity)
/// that their positions lose 1e-3 of an element to round-off. Call on every rank.
void note_parameter_scales(const fem::Model& model, const Teuchos::ParameterList& params);

/// "; parameters that may keep the step from being solved: ..." as noted, or "".
std::string step_failure_hint();

/// `message` of a run that stopped, with step_failure_hint() inserted if it is a step that
/// could not be solved (before "; the last accepted step is in ...").
std::string with_step_failure_hint(const std::string& message);

}  // namespace emc::app
