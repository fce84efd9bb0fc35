#include "emcontact/app/restart.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "emcontact/app/checkpoint_check.hpp"
#include "emcontact/contact/active.hpp"
#include "emcontact/error.hpp"
#include "emcontact/format.hpp"
#include "emcontact/output/atomic_file.hpp"
#include "emcontact/output/checkpoint.hpp"
#include "emcontact/output/parallel_hdf5.hpp"
#include "emcontact/parallel.hpp"
#include "emcontact/time/interrupt.hpp"

namespace emc::app {

namespace {

/// The stepper's scalars, between State and Checkpoint (the same names in both).
template <class From, class To>
void copy_scalars(const From& f, To& t) {
  t.step = f.step;
  t.t = f.t;
  t.dt = f.dt;
  t.good_steps = f.good_steps;
  t.last_h = f.last_h;
  t.last_iterations = f.last_iterations;
  t.newton_contraction = f.newton_contraction;
}

/// A checkpoint at or past Time/end leaves nothing to run: say so (exit 1) rather than exit 0
/// having done nothing.
void check_time(const output::Checkpoint& c, const time::Stepper& stepper,
                const std::string& path) {
  if (c.t < stepper.end() - 1e-9 * stepper.nominal_dt()) return;
  throw Error(path + format(": the checkpoint is at step %ld, t = %.17g, at or past Time/end = "
                            "%.17g: nothing left to run (a later Time/end continues the run)",
                            c.step, c.t, stepper.end()));
}

/// A changed Time/dt applies from the restart on (the step size of the next step and the
/// target of any regrowth after cuts), with a note.
void apply_new_dt(const output::Checkpoint& c, const time::Stepper& stepper, time::State& s,
                  const std::string& path, bool root) {
  if (c.nominal_dt == stepper.nominal_dt()) return;
  s.dt = stepper.nominal_dt();
  s.good_steps = 0;
  if (root)
    std::fprintf(stderr,
                 "note: --restart %s: Time/dt changed from %.17g to %.17g: the new dt applies "
                 "from step %ld on\n",
                 path.c_str(), c.nominal_dt, stepper.nominal_dt(), c.step + 1);
}

/// Every rank's active entries into `c`: per entry its packed values, its normal force and its
/// state (slip, direction, off; docs/THEORY.md §11.7: what the next step starts from).
void gather_active(const Simulation& sim, output::Checkpoint& c) {
  const auto& s = sim.state;
  constexpr std::size_t n = contact::kPackedActive, stride = n + 1 + contact::kPackedState;
  std::vector<double> mine;
  for (std::size_t k = 0; k < s.active.size(); ++k) {
    contact::pack(s.active[k], mine);
    mine.push_back(k < s.normal_force.size() ? s.normal_force[k] : 0.0);
    contact::pack_state(s.active[k], mine);
  }
  const auto all = allgather(*sim.disc->comm(), mine);
  for (std::size_t k = 0; k + stride <= all.size(); k += stride) {
    c.active.insert(c.active.end(), all.begin() + k, all.begin() + k + n);
    c.normal_force.push_back(all[k + n]);
    c.state.insert(c.state.end(), all.begin() + k + n + 1, all.begin() + k + stride);
  }
}

/// My entries of the checkpoint's active set (broadcast to every rank), with their normal forces
/// and states (all stick and none off if the checkpoint has none: written before §11.7).
void scatter_active(const output::Checkpoint& c, Simulation& sim) {
  auto& s = sim.state;
  s.active.clear();
  s.normal_force.clear();
  const int rank = sim.disc->comm()->getRank();
  constexpr std::size_t n = contact::kPackedActive;
  for (std::size_t k = 0; k + n <= c.active.size(); k += n) {
    contact::Active a = contact::unpack(&c.active[k]);
    if (sim.disc->part().owner(sim.model, a.slave) != rank) continue;
    const std::size_t entry = k / n;
    if (!c.state.empty()) contact::unpack_state(&c.state.at(entry * contact::kPackedState), a);
    s.active.push_back(a);
    s.normal_force.push_back(c.normal_force.at(entry));
  }
}

/// What the input's model needs of a checkpoint, checked before its datasets are read: its
/// fingerprint, 3 values per node, at most one entry per slave node.
output::CheckpointShape checkpoint_shape(const Simulation& sim, const std::string& path) {
  static_assert(output::kActiveValues == contact::kPackedActive);
  static_assert(output::kStateValues == contact::kPackedState);
  output::CheckpointShape shape;
  shape.values = 3 * static_cast<std::size_t>(sim.model.num_nodes());
  if (sim.contact)
    for (const auto& p : sim.contact->pairs()) shape.max_entries += p.slaves.size();
  shape.check_model = [&sim, path](const std::string& model) { check_model(model, sim, path); };
  return shape;
}

/// The rows of the checkpoint's directory's monitors.csv up to its step, checked: steps 0 to
/// the checkpoint's, each once, in time order, and the checkpoint's t and last step size as its
/// row has them.
std::vector<output::MonitorRow> kept_monitors(const output::Checkpoint& c,
                                              const std::string& path) {
  const std::string file = output::parent_directory(path) + "/monitors.csv";
  std::vector<output::MonitorRow> rows;
  try {
    for (const auto& r : output::read_monitors(file))
      if (r.step <= c.step) rows.push_back(r);
    check_monitor_steps(rows, c.step, file);
  } catch (const std::exception& e) {
    throw Error(std::string("--restart ") + path + ": " + e.what());
  }
  check_against_monitors(c, rows, path, file);
  return rows;
}

/// The restored u and V against the kept monitors row of the checkpoint's step (collective:
/// every rank computes the monitors, rank 0 holds the rows; a refusal stops every rank).
void check_restored_state(const Simulation& sim, const RestartInput& in, const std::string& path) {
  const auto& disc = *sim.disc;
  const auto& s = sim.state;
  const auto m = disc.monitors(*s.u, *s.V);
  const output::MonitorRow mine = monitor_row(disc, s, time::StepReport{});
  const auto x = disc.reference_positions();
  x->update(1.0, *s.u, 1.0);
  MonitorScales scales;
  scales.energy = m.kinetic + m.elastic + std::fabs(m.potential);
  scales.momentum = std::sqrt(2.0 * m.mass * m.kinetic);
  scales.length = std::sqrt(3.0) * x->normInf();  // collective
  const std::string file = output::parent_directory(path) + "/monitors.csv";
  // every active entry's facet point at its slave (each rank its own entries)
  std::vector<std::array<double, 2>> d;
  if (sim.contact && !sim.contact->empty()) {
    sim.contact->select(*s.u, *s.u, sim.contact->gather(s.active));
    d = sim.contact->facet_point_distances(sim.contact->positions(*s.u), s.active);
  }
  on_every_rank(*disc.comm(), [&] {
    for (std::size_t k = 0; k < d.size(); ++k)
      check_facet_point(s.active[k], sim.contact->pairs()[s.active[k].pair], d[k], path);
    if (disc.comm()->getRank() == 0)
      check_restored_monitors(mine, scales, in.rows.back(), path, file);
  });
}

}  // namespace

void save_checkpoint(const Simulation& sim, const RootGather& dofs, const output::Directory& dir,
                     const std::string& name) {
  const auto& s = sim.state;
  output::Checkpoint c;
  copy_scalars(s, c);
  c.nominal_dt = sim.stepper->nominal_dt();
  c.model = model_fingerprint(sim);
  c.u = dofs(*s.u);
  c.V = dofs(*s.V);
  int has = s.last_increment.is_null() ? 0 : 1;
  if (has) c.last_increment = dofs(*s.last_increment);
  gather_active(sim, c);
  output::write_checkpoint_collectively(raw_comm(*sim.disc->comm()), dir, name, c,
                                        3 * static_cast<std::size_t>(sim.model.num_nodes()));
}

RestartInput read_restart(const Simulation& sim, const std::string& path) {
  const auto& comm = *sim.disc->comm();
  const MPI_Comm raw = raw_comm(comm);
  RestartInput in;
  // every rank its block of the per-node values and the rest whole (the same refusal on every
  // rank), then each rank's checks of its block, rank 0's of the monitors
  in.checkpoint = output::read_checkpoint_collectively(raw, path, checkpoint_shape(sim, path));
  on_every_rank(raw, [&] {
    check_checkpoint(in.checkpoint, sim, path);
    check_time(in.checkpoint, *sim.stepper, path);
    if (comm.getRank() == 0) in.rows = kept_monitors(in.checkpoint, path);
  });
  return in;
}

output::MonitorRow apply_restart(Simulation& sim, const RootGather& dofs, RestartInput& in,
                                 const std::string& path) {
  const auto& comm = *sim.disc->comm();
  output::Checkpoint& c = in.checkpoint;
  std::vector<double> scalars = c.scalars();
  scalars.push_back(double(c.last_increment.size()));
  broadcast_vector(comm, scalars);
  const bool has_increment = scalars.back() > 0;
  scalars.pop_back();
  c.set_scalars(scalars, path);
  broadcast_vector(comm, c.active);
  broadcast_vector(comm, c.normal_force);
  broadcast_vector(comm, c.state);
  auto& s = sim.state;
  copy_scalars(c, s);
  apply_new_dt(c, *sim.stepper, s, path, comm.getRank() == 0);
  dofs.scatter(c.u, *s.u);
  dofs.scatter(c.V, *s.V);
  s.last_increment = Teuchos::null;
  if (has_increment) {
    s.last_increment = Teuchos::rcp(new Vector(s.u->getMap()));
    dofs.scatter(c.last_increment, *s.last_increment);
  }
  scatter_active(c, sim);
  check_restored_state(sim, in, path);
  // docs/THEORY.md §7.2: which nodes keep their gap follows from u_n and the active set, as at
  // the end of the step that wrote the checkpoint
  if (sim.contact && sim.contact->closes_gaps())
    sim.contact->mark_kept_gaps(s.active, sim.contact->positions(*s.u));
  // the preconditioner starts fresh, as after a checkpoint
  sim.solver->invalidate();
  sim.elim->forget_graph();
  c = output::Checkpoint();  // loaded: only the monitors rows are kept
  output::MonitorRow row0;
  if (comm.getRank() == 0) row0 = in.rows.front();
  double e0[2] = {row0.total, in.rows.empty() ? 0.0 : in.rows.back().dissipated};
  Teuchos::broadcast(comm, 0, 2, e0);  // every rank needs E0 for the energy error
  row0.total = e0[0];
  // docs/THEORY.md §11.7: D goes on from the checkpoint step's row (written to round-trip)
  s.dissipated = e0[1];
  return row0;
}

std::string stop_checkpoint(const Simulation& sim, const RootGather& dofs,
                            const output::Directory& dir, long kept) {
  const std::string path = dir.path("checkpoint.h5");
  const auto& s = sim.state;
  const std::string stopped = format("stopped by %s after step %ld (t = %.6g); ",
                                     time::signal_name(time::stop_signal()), s.step, s.t);
  if (kept < 0 || kept == s.step) {
    if (kept < 0) save_checkpoint(sim, dofs, dir, "checkpoint.h5");
    return stopped + "continue with --restart " + path;
  }
  return stopped + ("continue with --restart " + path + " (step " + std::to_string(kept) +
                    ", on the checkpoint grid: steps " + std::to_string(kept + 1) + " to " +
                    std::to_string(s.step) + " are recomputed, identically)");
}

bool same_file(const std::string& a, const std::string& b) {
  std::error_code ec;
  return !a.empty() && std::filesystem::equivalent(a, b, ec) && !ec;
}

void check_monitor_steps(const std::vector<output::MonitorRow>& rows, long step,
                         const std::string& file) {
  const std::string keeps =
      " (a restart keeps the rows of steps 0 to " + std::to_string(step) + ", each once, in order)";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const long s = rows[i].step, want = static_cast<long>(i);
    if (s == want) continue;
    if (s < 0)
      throw Error(file + ": a row has the negative step " + std::to_string(s) +
                  " (no row for step " + std::to_string(want) + ")" + keeps);
    if (s > want) throw Error(file + ": no row for step " + std::to_string(want) + keeps);
    throw Error(file + ": step " + std::to_string(s) +
                (s == rows[i - 1].step ? " given twice"
                                       : " after step " + std::to_string(rows[i - 1].step)) +
                keeps);
  }
  if (rows.empty() || rows.back().step != step)
    throw Error(file + ": no row for the checkpoint's step " + std::to_string(step));
}

}  // namespace emc::app
