#pragma once
// The `Time` section of the input: declared here, put in the
// input's schema by the app (emc::app::input_schema).
#include <Teuchos_ParameterList.hpp>

namespace emc::time {

/// Valid parameters of `Time` (defaults, validators, doc strings): `dt`, `end`, `integrator`
/// ("energy-momentum" or "midpoint"), `max step cuts`, `grow after`.
Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();

}  // namespace emc::time
