#pragma once
// The `Time` section of the input and `Solver/Newton`: declared here, put in the
// input's schema by the app (emc::app::input_schema).
#include <Teuchos_ParameterList.hpp>

#include "emcontact/time/settings.hpp"

namespace emc::time {

/// Valid parameters of `Time` the time module reads (defaults, validators, doc strings): `dt`,
/// `end`, `max step cuts`, `grow after`, `settle steps`, `settle tolerance`, `integrator` (the
/// element kernels' stress, which the app hands to the fem model).
Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();

/// Valid parameters of `Solver/Newton`: `relative tolerance`, `absolute tolerance`, `max
/// iterations`, `adaptive linear tolerance`, `warm re-solves`, `search tolerance`.
Teuchos::RCP<const Teuchos::ParameterList> valid_newton_parameters();

/// The settings of the validated `Time` sublist and `Solver/Newton` sublist (read once, at
/// set-up; nothing else of the time module reads the input).
Settings read_settings(const Teuchos::ParameterList& time, const Teuchos::ParameterList& newton);

}  // namespace emc::time
