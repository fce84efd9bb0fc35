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
#include "emcontact/app/progress.hpp"
#include "emcontact/app/restart.hpp"
#include "emcontact/app/root_gather.hpp"
#include "emcontact/app/scale_check.hpp"
#include "emcontact/app/shared_input.hpp"
#include "emcontact/app/simulation.hpp"
#include "emcontact/app/time_loop.hpp"
#include "emcontact/app/writers.hpp"
#include "emcontact/contact/contact.hpp"
#include "emcontact/contact/parameters.hpp"
#include "emcontact/error.hpp"
#include "emcontact/fem/discretization.hpp"
#include "emcontact/format.hpp"
#include "emcontact/linalg/elimination.hpp"
#include "emcontact/linalg/linear_solver.hpp"
#include "emcontact/os/plot.hpp"
#include "emcontact/os/signals.hpp"
#include "emcontact/output/fields.hpp"
#include "emcontact/output/monitors.hpp"
#include "emcontact/output/parallel_hdf5.hpp"
#include "emcontact/parallel.hpp"
#include "emcontact/time/interrupt.hpp"
#include "emcontact/time/parameters.hpp"
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

/// docs/THEORY.md §6.7: with Time/settle steps > 0 the bodies come to rest under their loads
/// before t = 0 (not at a restart: the checkpoint holds the state).
void settle(Simulation& sim, const time::SettleOptions& o, const std::string& file,
            const Comm& comm) {
  if (o.max_steps == 0) return;
  const time::SettleReport r = sim.stepper->settle(o);
  if (!r.converged)
    throw RunError(
        format("%s: Time/settle steps = %d: the bodies are not at rest after %d settling "
               "steps (%s; Time/settle tolerance = %.3g); allowed: bodies that touch their "
               "supports at the start (a body without support has no static equilibrium), "
               "or more settle steps",
               file.c_str(), o.max_steps, r.steps,
               r.moved_away ? "a body moved farther than the bodies' extent"
                            : "a step of dt from rest still gives kinetic energy",
               o.tolerance));
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
  const time::Settings ts =
      time::read_settings(P.sublist("Time"), P.sublist("Solver").sublist("Newton"));
  sim->model.integrator = ts.integrator;  // the time module's choice, the fem kernels' stress
  auto pairs =
      contact::build_pairs(contact::read_pair_settings(P, opt.input), sim->model, opt.input);
  // before the element data are built; rank 0 fits (it holds every tet): its refusal on all
  on_every_rank(*comm, [&] { contact::mark_massless_slaves(pairs, sim->model, opt.input); });
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
  sim->newton = std::make_unique<time::Newton>(disc, *sim->elim, *sim->solver, ts.newton);
  sim->state.u = rcp(new Vector(disc.owned_map()));
  sim->state.V = initial_velocity(disc);
  sim->stepper = std::make_unique<time::Stepper>(
      ts.step, *sim->newton, *sim->elim, owned_fixed_dofs(disc), sim->contact.get(), sim->state);
  sim->stepper->check_start(opt.input);  // the first step's scales against the tolerances
  if (opt.restart.empty()) settle(*sim, ts.settle, opt.input, *comm);
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

namespace {

/// A run's output: its directory (open and locked until the end), the writers, and what a
/// --restart read.
struct RunOutput {
  RestartInput restart;
  output::MonitorRow row0;  ///< the first row (the checkpoint's after --restart)
  std::unique_ptr<OutputDirectory> output_dir;
  output::Directory dir;  ///< this rank's descriptor of it
  Writers w;
};

/// --restart: the checkpoint and its monitors are read, checked and loaded before anything is
/// written (a refused restart leaves the output directory as it was, or not created); then the
/// directory and the writers (collective).
RunOutput open_output(Simulation& sim, const Options& opt, const output::Settings& out,
                      Summary& sum) {
  const fem::Model& model = sim.model;
  const fem::Discretization& disc = *sim.disc;
  const Comm& comm = *disc.comm();
  RunOutput o;
  // this rank's block of the per-node values of checkpoints (written and read by every rank)
  const auto block = output::block_of(3LL * model.num_nodes(), comm.getRank(), comm.getSize());
  auto dofs = std::make_unique<RootGather>(disc.owned_map(), block.first, block.count);
  o.row0 = monitor_row(disc, sim.state, time::StepReport{});
  if (!opt.restart.empty()) {
    o.restart = read_restart(sim, opt.restart);
    o.row0 = apply_restart(sim, *dofs, o.restart, opt.restart);
  }
  // what the run will write, from the steps it has left at the nominal dt
  const auto& stepper = *sim.stepper;
  const auto need = output::estimate_output(out, model.num_nodes(), model.global_tets,
                                            (stepper.end() - sim.state.t) / stepper.nominal_dt());
  o.output_dir = std::make_unique<OutputDirectory>(opt, out, comm, need);
  o.dir = output::shared_directory(raw_comm(comm), o.output_dir->dir());
  o.w = make_writers(disc, *o.output_dir, out.every, std::move(dofs));
  sum.output_dir = o.output_dir->path();
  sum.tets = model.global_tets;
  sum.nodes = model.num_nodes();
  return o;
}

/// The rows and the frame the loop starts from (the checkpoint's after --restart).
LoopStart first_rows(const Simulation& sim, const Options& opt, const output::Settings& out,
                     RunOutput& o, Summary& sum) {
  const auto& s = sim.state;
  const bool root = sim.disc->comm()->getRank() == 0;
  if (!opt.restart.empty()) {  // the monitors up to the checkpoint's step, its frames
    if (root)
      for (const auto& r : o.restart.rows) o.w.monitors->append(r);
    if (o.w.fields) o.w.fields->resume(s.step);
  } else {
    if (root) o.w.monitors->append(o.row0);
    o.w.fields_frame(*sim.disc, s);
  }
  sum.first_step = s.step;  // the checkpoint's step after --restart, else 0
  LoopStart start{o.row0, -1, out.checkpoint_every};
  // the step of DIR/checkpoint.h5 if this run wrote it or restarted from it, else -1
  start.kept = same_file(opt.restart, sum.output_dir + "/checkpoint.h5") ? s.step : -1;
  // rank 0's files decide: whether a stop writes a checkpoint is collective
  Teuchos::broadcast(*sim.disc->comm(), 0, 1, &start.kept);
  return start;
}

/// docs/THEORY.md §8: what each rank holds and receives of contact (the largest over ranks).
void contact_traffic(const Simulation& sim, Summary& sum) {
  if (!sim.contact) return;
  const auto& t = sim.contact->nodes().traffic();
  long long mine[4] = {t.nodes, t.remote, 8LL * 3 * t.remote, t.imports}, most[4];
  Teuchos::reduceAll(*sim.disc->comm(), Teuchos::REDUCE_MAX, 4, mine, most);
  sum.contact_nodes = most[0];
  sum.contact_remote = most[1];
  sum.contact_bytes = most[2];
  sum.contact_imports = most[3];
}

}  // namespace

Summary run(const Options& opt, RCP<const Comm> comm) {
  Teuchos::Time clock("emcontact: wall", true);
  auto sim = setup(opt, comm);
  const output::Settings out = output::settings(sim->in.params->sublist("Output"));
  Summary sum;
  RunOutput o = open_output(*sim, opt, out, sum);
  const bool root = comm->getRank() == 0;
  Progress progress(root && out.progress, sim->stepper->end());
  comm->barrier();
  sum.setup_seconds = clock.totalElapsedTime(true);
  const LoopStart start = first_rows(*sim, opt, out, o, sum);
  os::signals_stop_time_loop();
  time_loop(*sim, o.w, o.dir, progress, start, sum);
  if (root && out.plot) os::plot_monitors(o.output_dir->dir());
  sum.steps = sim->state.step - sum.first_step;  // the steps this run computed
  sum.time = sim->state.t;
  contact_traffic(*sim, sum);
  comm->barrier();
  sum.stepping_seconds = clock.totalElapsedTime(true) - sum.setup_seconds;
  return sum;
}

}  // namespace emc::app
