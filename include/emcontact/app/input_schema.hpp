#pragma once
// The whole input schema, assembled from the parameters each module declares
// (emcontact/<module>/parameters.hpp), with the checks across sections; the app reads the input
// with it. The input module itself knows no other module.
#include <string>
#include <vector>

#include "emcontact/input/input.hpp"

namespace emc::app {

/// The sections `Time`, `Bodies`, `Loads`, `Dirichlet`, `Contact`, `Solver`, `Output` (in
/// documentation order) and the cross-checks: at least one body; `Time/end` >= `dt`, at most 1e9
/// steps; Dirichlet conditions and contact pairs name existing bodies (and a surface); a contact
/// pair's slave is not a rigid surface type (`plane`, `rectangle`) and not on the master's body;
/// a rigid surface body has zero Initial velocities.
input::Schema input_schema();

/// input::read_input with input_schema().
input::Input read_input(const std::string& file, const std::vector<std::string>& overrides);

}  // namespace emc::app
