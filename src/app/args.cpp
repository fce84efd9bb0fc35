#include <cstring>

#include "emcontact/app/run.hpp"
#include "emcontact/error.hpp"

namespace emc::app {

std::string usage() {
  return "usage: emcontact INPUT.xml [--set Section/Sub/name=value ...] [--output DIR]\n"
         "                 [--restart DIR/checkpoint.h5]\n"
         "  --set     override any parameter of the input (repeatable), e.g. --set Time/end=0.5\n"
         "  --output  write monitors.csv and the fields to DIR instead of Output/directory\n"
         "  --restart continue from a checkpoint (Output/checkpoint every); the monitors of DIR\n"
         "            up to its step are kept and the run goes on from there\n"
         "Parameters are documented in inputs/README.md.";
}

Options parse_args(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&](const std::string& flag) -> std::string {
      const auto eq = a.find('=');
      if (eq != std::string::npos) return a.substr(eq + 1);
      if (i + 1 >= argc) throw InputError(flag + " needs a value\n" + usage());
      return argv[++i];
    };
    if (a == "-h" || a == "--help") {
      o.help = true;
    } else if (a == "--set" || a.rfind("--set=", 0) == 0) {
      o.overrides.push_back(value("--set"));
    } else if (a == "--output" || a.rfind("--output=", 0) == 0) {
      o.output_dir = value("--output");
    } else if (a == "--restart" || a.rfind("--restart=", 0) == 0) {
      o.restart = value("--restart");
    } else if (!a.empty() && a[0] == '-') {
      throw InputError("unknown option \"" + a + "\"\n" + usage());
    } else if (o.input.empty()) {
      o.input = a;
    } else {
      throw InputError("more than one input file (\"" + o.input + "\", \"" + a + "\")\n" +
                       usage());
    }
  }
  if (o.input.empty() && !o.help) throw InputError("no input file given\n" + usage());
  return o;
}

}  // namespace emc::app
