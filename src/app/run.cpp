// The application's data flow, one way: input -> mesh -> model -> discretization -> per step
// [assemble -> eliminate -> solve -> update] -> monitors and fields.
#include "emcontact/app/run.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_TimeMonitor.hpp>
#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "emcontact/app/input_schema.hpp"
#include "emcontact/app/meshes.hpp"
#include "emcontact/app/output_dir.hpp"
#include "emcontact/app/plot.hpp"
#include "emcontact/app/progress.hpp"
#include "emcontact/app/restart.hpp"
#include "emcontact/app/root_gather.hpp"
#include "emcontact/app/scale_check.hpp"
#include "emcontact/app/shared_input.hpp"
#include "emcontact/app/signals.hpp"
#include "emcontact/app/simulation.hpp"
#include "emcontact/contact/contact.hpp"
#include "emcontact/error.hpp"
#include "emcontact/fem/discretization.hpp"
#include "emcontact/linalg/elimination.hpp"
#include "emcontact/linalg/linear_solver.hpp"
#include "emcontact/output/fields.hpp"
#include "emcontact/output/monitors.hpp"
#include "emcontact/output/parallel_hdf5.hpp"
#include "emcontact/parallel.hpp"
#include "emcontact/time/interrupt.hpp"
#include "emcontact/time/stepper.hpp"

namespace emc::app {

using Teuchos::RCP;
using Teuchos::rcp;

namespace {

/// Displacement fixed (Dirichlet) dofs that this rank owns (docs/THEORY.md §3.1: zero columns
/// of P).
std::vector<GO> owned_fixed_dofs(const fem::Discretization& disc) {
  std::vector<GO> fixed;
  for (int n : disc.part().owned_nodes)
    if (disc.model().is_fixed(n))
      for (int c = 0; c < 3; ++c) fixed.push_back(fem::dof_gid(n, c));
  return fixed;
}

/// Initial velocity restricted to the owned dofs; zero on fixed nodes.
RCP<Vector> initial_velocity(const fem::Discretization& disc) {
  auto out = rcp(new Vector(disc.owned_map()));
  auto h = out->getLocalViewHost(Tpetra::Access::OverwriteAll);
  const auto& map = *disc.owned_map();
  for (std::size_t l = 0; l < map.getNodeNumElements(); ++l) {
    const GO g = map.getGlobalElement(static_cast<LO>(l));
    const int n = static_cast<int>(g / 3);
    h(l, 0) = disc.model().is_fixed(n) ? 0.0 : fem::initial_velocity(disc.model(), n)[g % 3];
  }
  return out;
}

/// The monitors (rank 0), the fields (every rank its block of rows: node_rows, tet_rows) and the
/// checkpoints' blocks (dofs).
struct Writers {
  std::unique_ptr<output::MonitorWriter> monitors;
  std::unique_ptr<output::FieldWriter> fields;
  std::unique_ptr<RootGather> dofs, node_rows, tet_rows;
  int every = 0;

  void fields_frame(const fem::Discretization& disc, const time::State& s) {
    if (every <= 0 || s.step % every != 0) return;
    Teuchos::TimeMonitor t(*Teuchos::TimeMonitor::getNewTimer("emcontact: output"));
    output::FieldFrame f;
    f.step = s.step;
    f.time = s.t;
    f.displacement = (*node_rows)(*s.u);
    f.velocity = (*node_rows)(*s.V);
    f.von_mises = (*tet_rows)(*disc.von_mises(*s.u));
    // per node contact status and normal force, packed in the x and y dofs of a dof vector
    Vector c(disc.owned_map());
    {
      auto h = c.getLocalViewHost(Tpetra::Access::OverwriteAll);
      Kokkos::deep_copy(h, 0.0);
      // the nodes the monitors count (§6.5): 1 active, 2 released at the end of the step
      for (std::size_t k = 0; k < s.contact_nodes.size(); ++k) {
        const LO l = disc.owned_map()->getLocalElement(fem::dof_gid(s.contact_nodes[k], 0));
        h(l, 0) = s.contact_status[k];
        h(l + 1, 0) = s.contact_force[k];
        h(l + 2, 0) = k < s.contact_slip.size() ? s.contact_slip[k] : 0;
      }
    }
    const auto packed = (*node_rows)(c);
    for (std::size_t n = 0; 3 * n < packed.size(); ++n) {
      f.contact_status.push_back(packed[3 * n]);
      f.normal_force.push_back(packed[3 * n + 1]);
      f.slip.push_back(packed[3 * n + 2]);
    }
    fields->write(f);
  }
};

/// The field writer of every rank, each with its block of rows of mesh.h5 and the frames
/// (collective; writes mesh.h5).
void make_field_writer(const fem::Discretization& disc, const OutputDirectory& dir, Writers& w) {
  const auto& model = disc.model();
  const auto layout =
      output::FieldLayout::blocks(raw_comm(*disc.comm()), model.num_nodes(), model.global_tets);
  w.node_rows = std::make_unique<RootGather>(disc.owned_map(), fem::dof_gid(layout.node_first, 0),
                                             3 * layout.node_count);
  w.tet_rows = std::make_unique<RootGather>(disc.element_map(), layout.tet_first, layout.tet_count);
  // this rank's rows: the nodes' coordinates and the tets (4 nodes and the body of each), from
  // the ranks that own them
  const std::vector<double> X = (*w.node_rows)(*disc.reference_positions());
  std::vector<long long> tets(4 * static_cast<std::size_t>(layout.tet_count));
  std::vector<int> body(static_cast<std::size_t>(layout.tet_count));
  const auto& mine = disc.part().my_tets;
  for (int c = 0; c < 5; ++c) {
    Vector v(disc.element_map());
    {
      auto h = v.getLocalViewHost(Tpetra::Access::OverwriteAll);
      for (std::size_t k = 0; k < mine.size(); ++k)
        h(k, 0) = c < 4 ? model.tets[4 * std::size_t(mine[k]) + c] : model.body_of_tet[mine[k]];
    }
    const auto rows = (*w.tet_rows)(v);
    for (std::size_t j = 0; j < rows.size(); ++j)
      if (c < 4)
        tets[4 * j + c] = std::llround(rows[j]);
      else
        body[j] = static_cast<int>(rows[j]);
  }
  w.fields = std::make_unique<output::FieldWriter>(output::shared_directory(layout.comm, dir.dir()),
                                                   layout, X, tets, body);
}

/// The writers into `dir` and the gathers (every rank); `dofs` is built before, for the restart.
Writers make_writers(const fem::Discretization& disc, const OutputDirectory& dir, int every,
                     std::unique_ptr<RootGather> dofs) {
  Writers w;
  w.every = every;
  output::on_root(raw_comm(*disc.comm()), [&] {  // a refusal stops every rank
    w.monitors = std::make_unique<output::MonitorWriter>(dir.dir(), "monitors.csv");
  });
  w.dofs = std::move(dofs);
  if (every > 0) make_field_writer(disc, dir, w);
  return w;
}

/// The energy scale of the relative energy error: the largest K + W + |Pi| so far, the scale of
/// the round-off of E = K + W + Pi (and the monitors' checks' scale). |E0| is not: it is 0, or
/// nearly, for a body at rest on a slope (potential and elastic energy cancelling).
double energy_scale(const output::MonitorRow& r, double scale) {
  return std::max({scale, r.kinetic + r.elastic + std::fabs(r.potential), 1e-300});
}

/// docs/THEORY.md §6.7: with Time/settle steps > 0 the bodies come to rest under their loads
/// before t = 0 (not at a restart: the checkpoint holds the state).
void settle(Simulation& sim, const Teuchos::ParameterList& time, const std::string& file,
            const Comm& comm) {
  const time::SettleOptions o = time::settle_options(time);
  if (o.max_steps == 0) return;
  const time::SettleReport r = sim.stepper->settle(o);
  char buf[400];
  if (!r.converged) {
    std::snprintf(buf, sizeof buf,
                  "%s: Time/settle steps = %d: the bodies are not at rest after %d settling "
                  "steps (%s; Time/settle tolerance = %.3g); allowed: bodies that touch their "
                  "supports at the start (a body without support has no static equilibrium), "
                  "or more settle steps",
                  file.c_str(), o.max_steps, r.steps,
                  r.moved_away ? "a body moved farther than the bodies' extent"
                               : "a step of dt from rest still gives kinetic energy",
                  o.tolerance);
    throw RunError(buf);
  }
  if (comm.getRank() == 0)
    std::printf(
        "emcontact: settled to static equilibrium in %d steps (%d Newton iterations, "
        "steps up to %.3g s)%s\n",
        r.steps, r.newton_iterations, r.largest_h,
        r.steady ? "; a steady free motion remains (a frictionless slide or twist)" : "");
}

}  // namespace

std::unique_ptr<Simulation> setup(const Options& opt, RCP<const Comm> comm) {
  auto sim = std::make_unique<Simulation>();
  sim->in = read_shared_input(opt.input, opt.overrides, *comm);  // rank 0's file on every rank
  const auto& P = *sim->in.params;
  auto meshes = build_meshes(P, sim->in.dir, opt.input, *comm);
  sim->model = fem::build_model(P, std::move(meshes), opt.input);
  auto pairs = contact::build_pairs(P, sim->model, opt.input);
  // before the element data are built; rank 0 fits (it holds every tet): its refusal on all
  output::on_every_rank(raw_comm(*comm),
                        [&] { contact::mark_massless_slaves(pairs, sim->model, opt.input); });
  // rank 0 hands out the tets: from here on each rank holds its own and a layer of ghosts
  auto part = fem::distribute(sim->model, comm);
  sim->disc = std::make_unique<fem::Discretization>(sim->model, std::move(part), comm);
  const auto& disc = *sim->disc;
  sim->contact = std::make_unique<contact::Contact>(disc, std::move(pairs));
  if (opt.restart.empty()) sim->contact->check_initial_penetration(opt.input);
  check_contact_scales(sim->model, sim->contact->pairs(), opt.input);
  note_parameter_scales(sim->model, P);  // named if a step cannot be solved
  sim->elim = std::make_unique<linalg::Elimination>(disc.owned_map());
  sim->solver = std::make_unique<linalg::LinearSolver>(P.sublist("Solver").sublist("Linear"), comm,
                                                       opt.input);
  sim->elim->keep_graph(sim->solver->direct());
  // CG needs a symmetric matrix: the mid-point tangent without frictionless contact is; the
  // energy-momentum tangent (docs/THEORY.md §1.4) and the frictionless P^T A Pt + X (§5.4) are not
  bool frictionless = false;
  for (const auto& pr : sim->contact->pairs()) frictionless |= pr.kind != contact::Kind::full_stick;
  if (comm->getRank() == 0 && sim->solver->assumes_symmetric() &&
      (sim->model.integrator == kernels::Integrator::energy_momentum || frictionless))
    std::fprintf(stderr,
                 "warning: %s: Solver/Linear/type = cg on a non-symmetric Newton matrix "
                 "(energy-momentum tangent or frictionless contact); gmres is the safe choice\n",
                 opt.input.c_str());
  sim->newton = std::make_unique<time::Newton>(
      disc, *sim->elim, *sim->solver, time::newton_options(P.sublist("Solver").sublist("Newton")));
  sim->state.u = rcp(new Vector(disc.owned_map()));
  sim->state.V = initial_velocity(disc);
  sim->stepper =
      std::make_unique<time::Stepper>(P.sublist("Time"), *sim->newton, *sim->elim,
                                      owned_fixed_dofs(disc), sim->contact.get(), sim->state);
  sim->stepper->check_start(opt.input);  // the first step's scales against the tolerances
  if (opt.restart.empty()) settle(*sim, P.sublist("Time"), opt.input, *comm);
  return sim;
}

output::MonitorRow monitor_row(const fem::Discretization& disc, const time::State& s,
                               const time::StepReport& rep) {
  const auto m = disc.monitors(*s.u, *s.V);
  output::MonitorRow r;
  r.step = s.step;
  r.time = s.t;
  r.kinetic = m.kinetic;
  r.elastic = m.elastic;
  r.potential = m.potential;
  r.total = m.kinetic + m.elastic + m.potential;
  for (int i = 0; i < 3; ++i) {
    r.L[i] = m.L[i];
    r.J[i] = m.J[i];
    r.com[i] = m.mass > 0 ? m.moment[i] / m.mass : 0.0;
  }
  r.active_contacts = rep.contact.active;
  r.gap_min = rep.contact.active ? rep.contact.gap_min : 0.0;
  r.gap_max = rep.contact.active ? rep.contact.gap_max : 0.0;
  r.contact_resolves = rep.contact.resolves;
  r.normal_force_min = rep.contact.normal_force_min;
  r.dissipated = s.dissipated;
  r.newton_iterations = rep.newton_iterations;
  r.dt = rep.dt;
  r.linear_iterations = rep.linear_iterations;
  return r;
}

Summary run(const Options& opt, RCP<const Comm> comm) {
  Teuchos::Time clock("emcontact: wall", true);
  auto sim = setup(opt, comm);
  const auto& P = *sim->in.params;
  const fem::Model& model = sim->model;
  const fem::Discretization& disc = *sim->disc;
  time::State& state = sim->state;
  time::Stepper& stepper = *sim->stepper;

  const output::Settings out = output::settings(P.sublist("Output"));
  Summary sum;
  // this rank's block of the per-node values of checkpoints (written and read by every rank)
  const auto block = output::block_of(3LL * model.num_nodes(), comm->getRank(), comm->getSize());
  auto dofs = std::make_unique<RootGather>(disc.owned_map(), block.first, block.count);
  auto row0 = monitor_row(disc, state, time::StepReport{});
  // --restart: the checkpoint and its monitors are read, checked and loaded before anything is
  // written (a refused restart leaves the output directory as it was, or not created)
  RestartInput restart;
  if (!opt.restart.empty()) {
    restart = read_restart(*sim, opt.restart);
    row0 = apply_restart(*sim, *dofs, restart, opt.restart);
  }
  // what the run will write, from the steps it has left at the nominal dt
  const auto need = output::estimate_output(out, model.num_nodes(), model.global_tets,
                                            (stepper.end() - state.t) / stepper.nominal_dt());
  const OutputDirectory output_dir(opt, out, *comm, need);  // open and locked until the end
  const output::Directory dir = output::shared_directory(raw_comm(*comm), output_dir.dir());
  sum.output_dir = output_dir.path();
  Writers w = make_writers(disc, output_dir, out.every, std::move(dofs));
  const bool root = comm->getRank() == 0;
  Progress progress(root && out.progress, stepper.end());

  sum.tets = model.global_tets;
  sum.nodes = model.num_nodes();
  comm->barrier();
  sum.setup_seconds = clock.totalElapsedTime(true);
  if (!opt.restart.empty()) {  // the monitors up to the checkpoint's step, its frames
    if (root)
      for (const auto& r : restart.rows) w.monitors->append(r);
    if (w.fields) w.fields->resume(state.step);
  } else if (root) {
    w.monitors->append(row0);
  }
  double escale = energy_scale(row0, 0.0);
  sum.first_step = state.step;  // the checkpoint's step after --restart, else 0
  if (opt.restart.empty()) w.fields_frame(disc, state);
  const int checkpoint_every = out.checkpoint_every;
  signals_stop_time_loop();
  // the step of DIR/checkpoint.h5 if this run wrote it or restarted from it, else -1
  long kept = same_file(opt.restart, sum.output_dir + "/checkpoint.h5") ? state.step : -1;
  // rank 0's files decide: whether a stop writes a checkpoint is collective
  Teuchos::broadcast(*comm, 0, 1, &kept);
  auto stop_on_sigterm = [&]() {
    if (root) w.monitors->flush(true);
    throw RunError(stop_checkpoint(*sim, *w.dofs, dir, kept));
  };
  try {
    while (!stepper.finished()) {
      time::StepReport rep;
      try {
        rep = stepper.advance();
      } catch (const time::Interrupted&) {
        stop_on_sigterm();
      }
      const auto row = monitor_row(disc, state, rep);
      escale = energy_scale(row, escale);
      // docs/THEORY.md §11.2: with friction E + D is what is conserved (D = 0 without it)
      const double err =
          std::fabs(row.total + row.dissipated - row0.total - row0.dissipated) / escale;
      sum.max_energy_error = std::max(sum.max_energy_error, err);
      sum.dissipates |= row.dissipated != row0.dissipated;
      sum.newton_iterations += rep.newton_iterations;
      if (root) {
        Teuchos::TimeMonitor t(*Teuchos::TimeMonitor::getNewTimer("emcontact: output"));
        w.monitors->append(row);
        w.monitors->flush(false, 1.0);
      }
      w.fields_frame(disc, state);
      if (checkpoint_every > 0 && state.step % checkpoint_every == 0) {
        Teuchos::TimeMonitor t(*Teuchos::TimeMonitor::getNewTimer("emcontact: output"));
        // monitors first: a kill between the two leaves rows beyond the checkpoint (ignored by
        // --restart), never a checkpoint without its row (found by kill_and_restart)
        if (root) w.monitors->flush(true);
        save_checkpoint(*sim, *w.dofs, dir, "checkpoint.h5");
        kept = state.step;
        sim->solver->invalidate();  // a restart starts with a fresh one: so does this run
        sim->elim->forget_graph();
      }
      progress.update(state.step, state.t, rep.dt, rep.newton_iterations, err, rep.contact.active,
                      sum.dissipates);
      if (time::stop_requested(*comm)) stop_on_sigterm();  // every rank at the same step
    }
  } catch (const RunError& e) {  // collective: every rank stops at the same step
    progress.finish();
    if (root) w.monitors->flush(true);
    const std::string file = sum.output_dir + "/checkpoint.h5";
    if (std::string(e.what()).find("stopped by SIG") != std::string::npos) throw;
    save_checkpoint(*sim, *w.dofs, dir, "checkpoint.h5");  // to look at or restart
    throw RunError(std::string(e.what()) + "; the last accepted step is in " + file);
  } catch (const Error&) {
    progress.finish();
    if (root) w.monitors->flush(true);
    throw;
  }
  progress.finish();
  if (root) w.monitors->flush(true);
  if (root && out.plot) plot_monitors(output_dir.dir());
  sum.steps = state.step - sum.first_step;  // the steps this run computed
  sum.time = state.t;
  if (sim->contact) {  // docs/THEORY.md §8: what each rank holds and receives of contact
    const auto& t = sim->contact->nodes().traffic();
    long long mine[4] = {t.nodes, t.remote, 8LL * 3 * t.remote, t.imports}, most[4];
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, 4, mine, most);
    sum.contact_nodes = most[0];
    sum.contact_remote = most[1];
    sum.contact_bytes = most[2];
    sum.contact_imports = most[3];
  }
  comm->barrier();
  sum.stepping_seconds = clock.totalElapsedTime(true) - sum.setup_seconds;
  return sum;
}

}  // namespace emc::app
