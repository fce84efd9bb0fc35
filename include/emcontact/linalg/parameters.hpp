#pragma once
// The `Solver` section of the input (Newton and linear solver): declared here, put in
// the input's schema by the app (emc::app::input_schema).
#include <Teuchos_ParameterList.hpp>

namespace emc::linalg {

/// Valid parameters of `Solver`: sublist `Newton` (`relative tolerance`, `absolute tolerance`,
/// `max iterations`) and sublist `Linear` (`type`: gmres | cg | klu2 | mumps, `preconditioner`:
/// ilu | schwarz | muelu | none, `tolerance`, `max iterations`, `reuse preconditioner`,
/// `factorisation reuse rate`, `residual check factor`, and the pass-through sublists `Belos`,
/// `Ifpack2`, `MueLu` whose contents go unchanged to Trilinos).
Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();

}  // namespace emc::linalg
