#pragma once
// The `Time` section of the input and `Solver/Newton`: declared here, put in the
// input's schema by the app (emc::app::input_schema).
#include <Teuchos_ParameterList.hpp>

namespace emc::time {

/// Valid parameters of `Time` the time module reads (defaults, validators, doc strings): `dt`,
/// `end`, `max step cuts`, `grow after`, `settle steps`, `settle tolerance` (`integrator` is the
/// fem module's: emc::fem::valid_time_parameters).
Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();

/// Valid parameters of `Solver/Newton` (read by newton_options): `relative tolerance`,
/// `absolute tolerance`, `max iterations`, `adaptive linear tolerance`.
Teuchos::RCP<const Teuchos::ParameterList> valid_newton_parameters();

}  // namespace emc::time
