#pragma once
// The `Contact` part of the input: declared here, put in the input's schema by the app (which
// also cross-checks the body names, see emc::app::input_schema).
#include <Teuchos_ParameterList.hpp>
#include <string>
#include <vector>

#include "emcontact/contact/pairs.hpp"

namespace emc::contact {

/// Template of one `Contact/<pair>` sublist (a contact pair, user-named):
/// - `slave` (string, required, default ""): a body name, or `body/surface` naming one of its
///   named surfaces; a deformable body (with tets).
/// - `master` (string, required, default ""): a body name or `body/surface`; deformable or a
///   rigid surface body; not the slave's body.
/// - `type` (string): "full stick" (default) or "frictionless"; its validator gives the Kind
///   (Teuchos::getIntegralValue<Kind>).
/// - `max penetration` (double >= 0, default 0 = automatic: half the mean edge of the master's
///   facets): a slave node is activated only while its penetration is below it.
Teuchos::RCP<const Teuchos::ParameterList> valid_pair_parameters();

/// The pairs of the validated input's `Contact` section (none if it has none), read once at
/// set-up. Throws InputError naming `file` and the parameter for a friction coefficient without
/// type = coulomb, or a massless slave with close gap.
std::vector<PairSettings> read_pair_settings(const Teuchos::ParameterList& params,
                                             const std::string& file);

}  // namespace emc::contact
