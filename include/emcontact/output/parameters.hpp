#pragma once
// The `Output` section of the input: declared and read here (the app takes the values through
// settings()), put in the input's schema by the app (emc::app::input_schema).
#include <Teuchos_ParameterList.hpp>
#include <string>

namespace emc::output {

/// Valid parameters of `Output`: `directory`, `every` (field output every N steps, 0 = none),
/// `progress`, `checkpoint every`, `plot`.
Teuchos::RCP<const Teuchos::ParameterList> valid_parameters();

/// The values of a validated `Output` section.
struct Settings {
  std::string directory;     ///< `directory`
  int every = 0;             ///< `every`: field output every N steps, 0 = none
  bool progress = true;      ///< `progress`: the progress line
  int checkpoint_every = 0;  ///< `checkpoint every`: 0 = never
  bool plot = false;         ///< `plot`: DIR/energies.png at the end
};
Settings settings(const Teuchos::ParameterList& output);

}  // namespace emc::output
