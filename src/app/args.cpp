#include <Trilinos_version.h>

#include <Kokkos_Core.hpp>
#include <algorithm>
#include <climits>
#include <cstring>

#include "emcontact/app/run.hpp"
#include "emcontact/error.hpp"
#include "emcontact/input/echo.hpp"

namespace emc::app {
namespace {

/// Kokkos' option for the number of threads in the linked Kokkos: --kokkos-num-threads from
/// Kokkos 3.7 on, --kokkos-threads before (Kokkos 3.4 refuses the newer spelling).
#if KOKKOS_VERSION >= 30700
constexpr const char* kKokkosThreadsOption = "--kokkos-num-threads";
#else
constexpr const char* kKokkosThreadsOption = "--kokkos-threads";
#endif

/// Refuses a path no file system accepts (a name longer than NAME_MAX, 255 bytes, or the
/// whole longer than PATH_MAX, 4096): it could only fail later, echoed in full.
void check_path_length(const std::string& flag, const std::string& path) {
  std::size_t longest = 0, start = 0;
  while (start <= path.size()) {
    const std::size_t slash = std::min(path.find('/', start), path.size());
    longest = std::max(longest, slash - start);
    start = slash + 1;
  }
  if (longest > NAME_MAX || path.size() >= PATH_MAX)
    throw InputError(flag + " \"" + input::echo(path) + "\": " +
                     (longest > NAME_MAX ? "a name in it has " + std::to_string(longest) + " bytes"
                                         : "it has " + std::to_string(path.size()) + " bytes") +
                     "; allowed: names of at most " + std::to_string(NAME_MAX) +
                     " bytes, paths shorter than " + std::to_string(PATH_MAX));
}

/// Sets `slot` to `v`, refusing a second `flag` (which one was meant is not for us to guess).
void once(const std::string& flag, std::string& slot, const std::string& v) {
  if (!slot.empty())
    throw InputError(flag + " given twice (\"" + input::echo(slot) + "\" and \"" + input::echo(v) +
                     "\"); allowed: once");
  slot = v;
}

/// A warning if an earlier --set names the parameter of the last one: the last one applies (a
/// wrapper script's default overridden on its command line), but a typo'd repeat is seen.
void warn_repeated_set(Options& o) {
  const auto name = [](const std::string& s) { return s.substr(0, s.find('=')); };
  const std::string last = name(o.overrides.back());
  for (std::size_t k = 0; k + 1 < o.overrides.size(); ++k)
    if (name(o.overrides[k]) == last) {
      o.warnings.push_back("--set " + input::echo(last) + " given twice (\"" +
                           input::echo(o.overrides[k]) + "\", then \"" +
                           input::echo(o.overrides.back()) + "\"): the last one applies");
      return;
    }
}

}  // namespace

std::string usage() {
  return "usage: emcontact INPUT.xml [--set Section/Sub/name=value ...] [--output DIR]\n"
         "                 [--overwrite] [--restart CHECKPOINT_DIR/checkpoint.h5]\n"
         "  --set       override any parameter of the input (repeatable), e.g. --set Time/end=0.5\n"
         "  --output    write monitors.csv and the fields to DIR instead of Output/directory\n"
         "  --overwrite let a new run replace the files of an earlier run in DIR (monitors.csv,\n"
         "              checkpoint.h5, fields.xdmf, fields_*.h5, mesh.h5, energies.png); without\n"
         "              it a DIR holding any of them is refused. Other files are never touched\n"
         "  --restart   continue from a checkpoint (Output/checkpoint every): the monitors of its\n"
         "              directory up to its step are kept and the run goes on from there, in that\n"
         "              directory, or in a new DIR given by --output (a branch)\n"
         "  --version   print emcontact's, Trilinos' and Kokkos' versions and Kokkos' backend\n"
         "  --help, -h  this text\n"
         "One run at a time per DIR (DIR/.emcontact.lock). Parameters: inputs/README.md.\n"
         "Kokkos' own options (e.g. " +
         std::string(kKokkosThreadsOption) + "=N) pass through: --kokkos-help lists them.";
}

std::string version() {
  const int kv = KOKKOS_VERSION;
  return std::string("emcontact ") + EMC_VERSION + " (git " + EMC_GIT_COMMIT + ")\nTrilinos " +
         TRILINOS_VERSION_STRING + ", Kokkos " + std::to_string(kv / 10000) + "." +
         std::to_string(kv / 100 % 100) + "." + std::to_string(kv % 100) +
         ", default execution space " + Kokkos::DefaultExecutionSpace::name();
}

std::string early_option(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--set" || a == "--output" || a == "--restart") {
      ++i;  // a value, whatever it reads
    } else if (a == "-h" || a == "--help") {
      return "help";
    } else if (a == "--version") {
      return "version";
    }
  }
  return "";
}

Options parse_args(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&](const std::string& flag) -> std::string {
      const auto eq = a.find('=');
      std::string v;
      if (eq != std::string::npos) {
        v = a.substr(eq + 1);
      } else {
        if (i + 1 >= argc) throw InputError(flag + " needs a value\n" + usage());
        v = argv[++i];
      }
      // an empty value (e.g. an unset shell variable) must not fall back to a default
      if (v.empty())
        throw InputError(flag + ": empty value; allowed: a non-empty " +
                         (flag == "--set" ? "Section/name=value" : "path"));
      return v;
    };
    if (a == "-h" || a == "--help") {
      o.help = true;
    } else if (a == "--set" || a.rfind("--set=", 0) == 0) {
      o.overrides.push_back(value("--set"));
      warn_repeated_set(o);
    } else if (a == "--output" || a.rfind("--output=", 0) == 0) {
      once("--output", o.output_dir, value("--output"));
      check_path_length("--output", o.output_dir);
    } else if (a == "--overwrite") {
      o.overwrite = true;
    } else if (a == "--restart" || a.rfind("--restart=", 0) == 0) {
      once("--restart", o.restart, value("--restart"));
    } else if (!a.empty() && a[0] == '-') {
      throw InputError("unknown option \"" + input::echo(a) + "\"\n" + usage());
    } else if (o.input.empty()) {
      o.input = a;
    } else {
      throw InputError("more than one input file (\"" + input::echo(o.input) + "\", \"" +
                       input::echo(a) + "\")\n" + usage());
    }
  }
  if (o.input.empty() && !o.help) throw InputError("no input file given\n" + usage());
  return o;
}

}  // namespace emc::app
