// The time loop of a run (see time_loop.hpp).
#include "emcontact/app/time_loop.hpp"

#include <Teuchos_TimeMonitor.hpp>
#include <algorithm>
#include <cmath>

#include "emcontact/app/restart.hpp"
#include "emcontact/error.hpp"
#include "emcontact/linalg/elimination.hpp"
#include "emcontact/linalg/linear_solver.hpp"
#include "emcontact/time/interrupt.hpp"

namespace emc::app {

namespace {

/// The energy scale of the relative energy error: the largest K + W + |Pi| so far, the scale of
/// the round-off of E = K + W + Pi (and the monitors' checks' scale). |E0| is not: it is 0, or
/// nearly, for a body at rest on a slope (potential and elastic energy cancelling).
double energy_scale(const output::MonitorRow& r, double scale) {
  return std::max({scale, r.kinetic + r.elastic + std::fabs(r.potential), 1e-300});
}

class TimeLoop {
 public:
  TimeLoop(Simulation& sim, Writers& w, const output::Directory& dir, Progress& progress,
           const LoopStart& start, Summary& sum)
      : sim_(sim),
        w_(w),
        dir_(dir),
        progress_(progress),
        start_(start),
        kept_(start.kept),
        sum_(sum),
        root_(sim.disc->comm()->getRank() == 0),
        escale_(energy_scale(start.row0, 0.0)) {}

  void run() {
    try {
      while (!sim_.stepper->finished()) step();
    } catch (const time::Stopped&) {  // its checkpoint is written already
      progress_.finish();
      throw;
    } catch (const RunError& e) {  // collective: every rank stops at the same step
      progress_.finish();
      flush();
      save_checkpoint(sim_, *w_.dofs, dir_, "checkpoint.h5");  // to look at or restart
      throw RunError(std::string(e.what()) + "; the last accepted step is in " + sum_.output_dir +
                     "/checkpoint.h5");
    } catch (const Error&) {
      progress_.finish();
      flush();
      throw;
    }
    progress_.finish();
    flush();
  }

 private:
  Simulation& sim_;
  Writers& w_;
  const output::Directory& dir_;
  Progress& progress_;
  const LoopStart& start_;
  long kept_;  ///< the step of DIR/checkpoint.h5 (a stop after it writes none), else -1
  Summary& sum_;
  const bool root_;
  double escale_;

  void step() {
    time::StepReport rep;
    try {
      rep = sim_.stepper->advance();
    } catch (const time::Interrupted&) {
      stop();
    }
    const double err = record(rep);
    checkpoint_if_due();
    const auto& s = sim_.state;
    progress_.update(s.step, s.t, rep.dt, rep.newton_iterations, err, rep.contact.active,
                     sum_.dissipates);
    if (time::stop_requested(*sim_.disc->comm())) stop();  // every rank at the same step
  }

  /// The step's monitors row and frame; its energy error.
  double record(const time::StepReport& rep) {
    const auto row = monitor_row(*sim_.disc, sim_.state, rep);
    const auto& row0 = start_.row0;
    escale_ = energy_scale(row, escale_);
    // docs/THEORY.md §11.2: with friction E + D is what is conserved (D = 0 without it)
    const double err =
        std::fabs(row.total + row.dissipated - row0.total - row0.dissipated) / escale_;
    sum_.max_energy_error = std::max(sum_.max_energy_error, err);
    sum_.dissipates |= row.dissipated != row0.dissipated;
    sum_.newton_iterations += rep.newton_iterations;
    if (root_) {
      Teuchos::TimeMonitor t(*Teuchos::TimeMonitor::getNewTimer("emcontact: output"));
      w_.monitors->append(row);
      w_.monitors->flush(false, 1.0);
    }
    w_.fields_frame(*sim_.disc, sim_.state);
    return err;
  }

  void checkpoint_if_due() {
    const long step = sim_.state.step;
    if (start_.checkpoint_every <= 0 || step % start_.checkpoint_every != 0) return;
    Teuchos::TimeMonitor t(*Teuchos::TimeMonitor::getNewTimer("emcontact: output"));
    // monitors first: a kill between the two leaves rows beyond the checkpoint (ignored by
    // --restart), never a checkpoint without its row (found by kill_and_restart)
    flush();
    save_checkpoint(sim_, *w_.dofs, dir_, "checkpoint.h5");
    kept_ = step;
    sim_.solver->invalidate();  // a restart starts with a fresh one: so does this run
    sim_.elim->forget_graph();
  }

  [[noreturn]] void stop() {
    flush();
    throw time::Stopped(stop_checkpoint(sim_, *w_.dofs, dir_, kept_));
  }

  void flush() {
    if (root_) w_.monitors->flush(true);
  }
};

}  // namespace

void time_loop(Simulation& sim, Writers& w, const output::Directory& dir, Progress& progress,
               const LoopStart& start, Summary& sum) {
  TimeLoop(sim, w, dir, progress, start, sum).run();
}

}  // namespace emc::app
