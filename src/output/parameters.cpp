// Schema of the `Output` section, and its values.
#include "emcontact/output/parameters.hpp"

#include "emcontact/input/validators.hpp"

namespace emc::output {

Teuchos::RCP<const Teuchos::ParameterList> valid_parameters() {
  using namespace emc::input;
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("Output"));
  pl->set("directory", std::string("output"),
          "Directory of monitors.csv and the field files (created if missing; not a symbolic "
          "link). --output overrides it; so does --restart DIR/checkpoint.h5, which continues "
          "in DIR.",
          any_string());
  pl->set("every", 10, "Field output (HDF5/XDMF) every N steps; 0 = no field output.",
          int_at_least(0));
  pl->set("progress", true, "Print a progress line per step on the terminal.");
  pl->set("checkpoint every", 0,
          "Write DIR/checkpoint.h5 (the complete state: displacements, velocities, the active "
          "contact set, step size and counters) every N steps, atomically; 0 = never. "
          "`emcontact input.xml --restart DIR/checkpoint.h5` continues from it.",
          int_at_least(0));
  pl->set("plot", false,
          "At the end of the run, write DIR/energies.png (kinetic, elastic, potential and total "
          "energy, L and J against time) with tools/plot_monitors.py (Debian's /usr/bin/python3 "
          "and matplotlib); if plotting fails the run only warns.");
  return pl;
}

Settings settings(const Teuchos::ParameterList& output) {
  Settings s;
  s.directory = output.get<std::string>("directory");
  s.every = output.get<int>("every");
  s.progress = output.get<bool>("progress");
  s.checkpoint_every = output.get<int>("checkpoint every");
  s.plot = output.get<bool>("plot");
  return s;
}

}  // namespace emc::output
