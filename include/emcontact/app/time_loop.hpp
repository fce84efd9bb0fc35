#pragma once
// The time loop of a run: the steps to Time/end, each one's monitors row, field frame and
// checkpoint; a stop by a signal, and a failed step, leave a checkpoint to restart from.
#include "emcontact/app/progress.hpp"
#include "emcontact/app/run.hpp"
#include "emcontact/app/simulation.hpp"
#include "emcontact/app/writers.hpp"
#include "emcontact/output/monitors.hpp"
#include "emcontact/output/open_directory.hpp"

namespace emc::app {

/// Where the loop starts from.
struct LoopStart {
  output::MonitorRow row0;   ///< the first row (the checkpoint's after --restart)
  long kept = -1;            ///< the step of DIR/checkpoint.h5 if this run wrote it or read it
  int checkpoint_every = 0;  ///< Output/checkpoint every (0: none)
};

/// Collective: steps `sim` to Time/end, appending each step's row (rank 0), frame and due
/// checkpoint to `w` in `dir`, and adding to `sum` the largest energy error (of E + D, on the
/// scale K + W + |Pi|), the Newton iterations and whether friction dissipated. Throws
/// time::Stopped after a signal (the checkpoint to continue from written), RunError after a
/// step that failed (the last accepted step saved to DIR/checkpoint.h5), other errors as thrown;
/// the monitors are flushed in every case.
void time_loop(Simulation& sim, Writers& w, const output::Directory& dir, Progress& progress,
               const LoopStart& start, Summary& sum);

}  // namespace emc::app
