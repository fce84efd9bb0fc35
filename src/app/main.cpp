// emcontact: conserving dynamic contact by direct elimination. See README.md.
#include <mpi.h>

#include <Teuchos_TimeMonitor.hpp>
#include <Tpetra_Core.hpp>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "emcontact/app/error_exit.hpp"
#include "emcontact/app/kokkos_options.hpp"
#include "emcontact/app/run.hpp"
#include "emcontact/app/scale_check.hpp"
#include "emcontact/app/shared_input.hpp"
#include "emcontact/error.hpp"
#include "emcontact/os/memory.hpp"
#include "emcontact/os/signals.hpp"
#include "emcontact/output/hdf5_file.hpp"

namespace {
/// Rank 0 of the job, or not under an MPI launcher, from the launchers' environment (MPI is not
/// started yet).
bool first_process() {
  for (const char* v : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"})
    if (const char* r = std::getenv(v)) return std::string(r) == "0";
  return true;
}

/// An error before MPI and Kokkos have both started: every rank has it (the same command
/// line), the first process says it.
int fail_before_start(const std::string& message) {
  if (first_process()) std::fprintf(stderr, "error: %s\n", message.c_str());
  int started = 0, finished = 0;
  MPI_Initialized(&started);
  MPI_Finalized(&finished);
  if (started && !finished) MPI_Finalize();
  return 1;
}
}  // namespace

int main(int argc, char** argv) {
  // a signal from here on ends the run with its one-line message (held until MPI has started)
  emc::os::install_stop_handlers();
  // --help and --version answer before MPI and Kokkos start
  const std::string early = emc::app::early_option(argc, argv);
  if (!early.empty()) {
    if (first_process())
      std::cout << (early == "help" ? emc::app::usage() : emc::app::version()) << std::endl;
    return 0;
  }
  emc::os::keep_freed_memory();  // before MPI and Kokkos allocate
  // Kokkos parses its options in the ScopeGuard and throws on a bad one: they are checked
  // first, and anything else it throws still ends in one line
  std::optional<Tpetra::ScopeGuard> scope;
  try {
    emc::app::check_kokkos_options(argc, argv);
    scope.emplace(&argc, &argv);
  } catch (const std::exception& e) {
    return fail_before_start(e.what());
  }
  emc::output::silence_hdf5_errors();  // errors are reported in one line each
  auto comm = Tpetra::getDefaultComm();
  const bool root = comm->getRank() == 0;
  const emc::app::ErrorExit error_exit;
  emc::os::stop_handlers_ready(comm->getRank());
  try {
    // every rank runs rank 0's command line (an MPMD launch may give the ranks others)
    auto args = emc::app::rank0_arguments(argc, argv, *comm);
    std::vector<char*> arg_ptrs{argv[0]};
    for (auto& a : args) arg_ptrs.push_back(a.data());
    const auto opt = emc::app::parse_args(static_cast<int>(arg_ptrs.size()), arg_ptrs.data());
    if (root)
      for (const auto& w : opt.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    if (opt.help) {
      if (root) std::cout << emc::app::usage() << std::endl;
      return 0;
    }
    Teuchos::Time wall("wall", true);
    const auto s = emc::app::run(opt, comm);
    if (root) {
      std::printf(
          "emcontact: %lld tets, %lld nodes on %d rank(s); setup %.3f s; %ld steps%s to "
          "t = %.6g in %.3f s (%.4f s/step, %.2f Newton iterations/step); total %.3f "
          "s; max |%s-E0|/max(K+W+|Pi|) = %.3e; output in %s\n",
          s.tets, s.nodes, comm->getSize(), s.setup_seconds, s.steps,
          s.first_step > 0 ? (" from step " + std::to_string(s.first_step)).c_str() : "", s.time,
          s.stepping_seconds, s.steps ? s.stepping_seconds / s.steps : 0.0,
          s.steps ? double(s.newton_iterations) / s.steps : 0.0, wall.totalElapsedTime(true),
          s.dissipates ? "E+D" : "E", s.max_energy_error, s.output_dir.c_str());
      if (s.contact_nodes > 0)
        std::printf(
            "emcontact: %lld contact nodes per rank (%lld owned by other ranks), %lld bytes "
            "received per import of their positions, %lld imports (the largest over the "
            "ranks)\n",
            s.contact_nodes, s.contact_remote, s.contact_bytes, s.contact_imports);
    }
    const std::string memory = emc::os::gather_peak_memory(*comm);  // collective
    if (root) std::printf("%s\n", memory.c_str());
    std::fflush(stdout);
    Teuchos::TimeMonitor::summarize(comm.ptr(), std::cout, false, true, false);
    return 0;
  } catch (const emc::Error& e) {
    // a solver's out-of-memory, reported as a failed step
    if (emc::os::is_out_of_memory(e)) return error_exit.fail(emc::os::out_of_memory_message(e), 1);
    return error_exit.fail(emc::app::with_step_failure_hint(e.what()), 1);
  } catch (const std::exception& e) {
    // out of memory (std::bad_alloc, or Kokkos' allocation failure) is a model too large for
    // the machine: one line naming its size, exit 1
    if (emc::os::is_out_of_memory(e)) return error_exit.fail(emc::os::out_of_memory_message(e), 1);
    return error_exit.fail(e.what(), 2);
  }
}
