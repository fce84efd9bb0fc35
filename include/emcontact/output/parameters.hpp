#pragma once
// The `Output` section of the input: declared here, put in the
// input's schema by the app (emc::app::input_schema).
#include <Teuchos_ParameterList.hpp>

namespace emc::output {

/// Valid parameters of `Output`: `directory`, `every` (field output every N steps, 0 = none),
/// `progress`.
Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();

}  // namespace emc::output
