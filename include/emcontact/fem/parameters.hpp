#pragma once
// The body, load, Dirichlet and assembly parts of the input: declared here, put in the input's
// schema by the app (which adds each body's `Mesh` sublist from
// emc::mesh::valid_mesh_parameters()).
#include <Teuchos_ParameterList.hpp>

namespace emc::fem {

/// Template of one `Bodies/<body>` sublist without its `Mesh`: sublists `Material` (`young`,
/// `poisson`, `density`) and `Initial` (`velocity`, `angular velocity` about the body's centre
/// of mass, both Array(double) of 3 components).
Teuchos::RCP<const Teuchos::ParameterList> valid_body_parameters();

/// Valid parameters of `Loads`: `gravity` (Array(double), 3 components).
Teuchos::RCP<const Teuchos::ParameterList> valid_load_parameters();

/// Template of one `Dirichlet/<condition>` sublist: `body` (the name of a body) and `surface`
/// (a named surface of that body's mesh); both required (default ""). The displacement of the
/// surface's nodes is fixed to zero.
Teuchos::RCP<const Teuchos::ParameterList> valid_dirichlet_parameters();

/// Valid parameters of `Solver/Assembly`: `scatter` (coloured or atomic, see
/// emcontact/fem/scatter.hpp).
Teuchos::RCP<const Teuchos::ParameterList> valid_assembly_parameters();

}  // namespace emc::fem
