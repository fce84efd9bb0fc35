#pragma once
// The application: command line, setup (input -> mesh -> model -> discretization), the time
// loop with its progress line, output and the timer summary.
#include <string>
#include <vector>

#include "emcontact/types.hpp"

namespace emc::app {

struct Options {
  std::string input;                   ///< the XML file
  std::vector<std::string> overrides;  ///< --set Section/Sub/name=value
  std::string output_dir;              ///< --output DIR (overrides Output/directory)
  std::string restart;                 ///< --restart FILE: continue from a checkpoint
  bool overwrite = false;              ///< --overwrite: replace an earlier run's files in DIR
  bool help = false;
  std::vector<std::string> warnings;  ///< for rank 0 to print: a --set given twice
};

/// Parses argv; throws InputError with the usage on a bad command line.
Options parse_args(int argc, char** argv);
std::string usage();
/// emcontact's version (and git commit), the Trilinos version and Kokkos' default backend.
std::string version();
/// "help", "version" or "" for the first of --help/-h and --version on the command line,
/// looked for before MPI and Kokkos start (Kokkos would print its own option list first).
std::string early_option(int argc, char** argv);

struct Summary {
  long steps = 0;       ///< computed by this run (after --restart: since the checkpoint)
  long first_step = 0;  ///< the step it started from (the checkpoint's, or 0)
  double time = 0;
  long long newton_iterations = 0;
  /// max_n |E_n + D_n - E_0 - D_0| / max_n (K + W + |Pi|)_n (D: friction's work)
  double max_energy_error = 0;
  bool dissipates = false;  ///< friction dissipated energy in the run (D changed)
  std::string output_dir;
  long long tets = 0, nodes = 0;
  double setup_seconds = 0, stepping_seconds = 0;  ///< wall time before / in the time loop
  /// docs/THEORY.md §8, the largest over the ranks at the last selection: contact nodes, those
  /// owned by another rank, and the bytes a rank receives per import of their positions; the
  /// number of imports per rank over the run (0 without contact).
  long long contact_nodes = 0, contact_remote = 0, contact_bytes = 0, contact_imports = 0;
};

/// Runs the whole simulation on `comm`. Throws emc::Error (after writing what it had).
Summary run(const Options& opt, Teuchos::RCP<const Comm> comm);

}  // namespace emc::app
