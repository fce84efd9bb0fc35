#pragma once
// Contact parameters whose scale defeats the contact search: a `max penetration` larger than
// the master surface (its activation window -dmax < g < -1e-12 dmax then misses every real
// penetration) or below the round-off of the gaps (no depth can be told from touching), or a
// rigid surface so much larger than the deformable bodies that the gaps drown in the round-off
// of its coordinates. Each made contact silently vanish.
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

}  // namespace emc::app
