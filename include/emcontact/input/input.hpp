#pragma once
// Reading and validating the Teuchos XML input (the app's only entry to parameters).
#include <Teuchos_ParameterList.hpp>
#include <string>
#include <vector>

namespace emc::input {

struct Input {
  Teuchos::RCP<Teuchos::ParameterList> params;  ///< validated, defaults filled in
  std::string file;                             ///< the XML file as given
  std::string dir;                              ///< its directory (relative mesh files)
};

/// Reads `file`, applies `overrides` ("Section/Sub/name=value", value parsed with the type the
/// schema gives that parameter), validates every sublist (Bodies/<any>, Dirichlet/<any>,
/// Contact/<any> against their templates), fills defaults and cross-checks: Dirichlet and
/// Contact name existing bodies, a contact pair's slave is not a rigid surface type (`plane`,
/// `rectangle`) and not on the master's body, a rigid surface body has zero Initial velocities.
/// Throws emc::InputError naming the file, the parameter path and what is allowed. Pure function of
/// its arguments (call on every rank).
Input read_input(const std::string& file, const std::vector<std::string>& overrides);

/// The whole schema, with one example entry for the user-named sublists ("Bodies/<body>",
/// "Dirichlet/<condition>", "Contact/<pair>"); used to generate inputs/README.md.
Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();

/// Markdown documentation of every parameter (name, type, default, allowed values, doc string).
std::string schema_markdown();

}  // namespace emc::input
