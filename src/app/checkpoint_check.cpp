#include "emcontact/app/checkpoint_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <unordered_set>

#include "emcontact/contact/active.hpp"
#include "emcontact/contact/detection.hpp"  // entry_rule, kernels::facet_outside
#include "emcontact/error.hpp"
#include "emcontact/format.hpp"
#include "emcontact/input/echo.hpp"
#include "emcontact/output/parallel_hdf5.hpp"

namespace emc::app {
namespace {

std::string hex(std::uint64_t h) {
  return format("%016llx", static_cast<unsigned long long>(h));
}

std::vector<std::string> lines(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

/// "model" lines of the checkpoint and of the input: the first difference, or "".
std::string first_difference(const std::string& stored, const std::string& input) {
  const auto a = lines(stored), b = lines(input);
  for (std::size_t i = 0; i < std::max(a.size(), b.size()); ++i) {
    const std::string x = i < a.size() ? a[i] : "(nothing)", y = i < b.size() ? b[i] : "(nothing)";
    if (x != y) return "checkpoint \"" + x + "\", input \"" + y + "\"";
  }
  return "";
}

/// `v` with 17 significant digits (exact), as the monitors hold it.
std::string number(double v) {
  return format("%.17g", v);
}

[[noreturn]] void refuse(const std::string& path, const std::string& what) {
  throw Error(path + ": " + what +
              "; refused (not a checkpoint of this input's model, or corrupt)");
}

void check_scalars(const output::Checkpoint& c, const std::string& path) {
  auto need = [&](bool ok, const char* name, double v, const char* allowed) {
    if (!ok)
      refuse(path, std::string("the checkpoint's ") + name + " = " + input::echo_number(v) +
                       " is not " + allowed);
  };
  need(std::isfinite(c.t) && c.t >= 0, "t", c.t, "a finite time >= 0");
  need(std::isfinite(c.dt) && c.dt > 0, "dt", c.dt, "a finite step > 0");
  need(std::isfinite(c.last_h) && c.last_h >= 0, "last_h", c.last_h, "a finite step >= 0");
  need(std::isfinite(c.newton_contraction), "newton_contraction", c.newton_contraction, "finite");
  need(std::isfinite(c.nominal_dt) && c.nominal_dt > 0, "nominal_dt", c.nominal_dt,
       "a finite step > 0");
  // the stepper's step sizes never exceed its Time/dt (cuts halve them, regrowth stops there)
  if (c.dt > c.nominal_dt || c.last_h > c.nominal_dt)
    refuse(path, "the checkpoint's " + std::string(c.dt > c.nominal_dt ? "dt = " : "last_h = ") +
                     number(c.dt > c.nominal_dt ? c.dt : c.last_h) +
                     " is above the Time/dt of its run, " + number(c.nominal_dt) +
                     " (allowed: at most that)");
}

void check_arrays(const output::Checkpoint& c, const Simulation& sim, const std::string& path) {
  const auto& comm = *sim.disc->comm();  // this rank's block of the per-node values
  const auto n = static_cast<std::size_t>(
      output::block_of(3LL * sim.model.num_nodes(), comm.getRank(), comm.getSize()).count);
  auto sized = [&](const std::vector<double>& v, const char* name, bool may_be_empty) {
    if (v.size() != n && !(may_be_empty && v.empty()))
      refuse(path, std::string("the checkpoint's ") + name + " has " + std::to_string(v.size()) +
                       " values, the input's mesh needs " + std::to_string(n));
    for (double x : v)
      if (!std::isfinite(x))
        refuse(path, std::string("the checkpoint's ") + name + " is not finite");
  };
  sized(c.u, "u", false);
  sized(c.V, "V", false);
  sized(c.last_increment, "last_increment", true);
  if (c.active.size() % contact::kPackedActive != 0 ||
      c.normal_force.size() != c.active.size() / contact::kPackedActive)
    refuse(path, "the checkpoint's active set has " + std::to_string(c.active.size()) +
                     " values and " + std::to_string(c.normal_force.size()) +
                     " normal forces (5 values and 1 force per active node)");
  const std::size_t entries = c.normal_force.size();
  if (!c.state.empty() && c.state.size() != entries * contact::kPackedState)
    refuse(path, "the checkpoint's active set has " + std::to_string(entries) + " nodes and " +
                     std::to_string(c.state.size()) + " state values (" +
                     std::to_string(contact::kPackedState) + " per active node, or none)");
}

/// An integer in [0, n), or refused naming `what`.
int index_in(double v, std::size_t n, const std::string& what, const std::string& path) {
  if (!(v >= 0 && v < double(n) && v == std::floor(v)))
    refuse(path, "the checkpoint's active set has " + what + " " + input::echo_number(v) +
                     " (allowed: 0 to " + std::to_string(long(n) - 1) + ")");
  return static_cast<int>(v);
}

/// docs/THEORY.md §11.7: the state of entry `slave` of `pair` (kPackedState values at `p`):
/// slip and off are 0 or 1, only a Coulomb entry slides, only a sticking Coulomb entry is off
/// (any other off entry was released at the end of its step), the direction is finite and at
/// most a unit vector (a unit vector when it slides, to the round-off of its normalisation).
void check_state(const double* p, const contact::Pair& pair, int slave, const std::string& path) {
  auto need = [&](bool ok, const std::string& what) {
    if (!ok)
      refuse(path, "the checkpoint's active node " + std::to_string(slave) + " of pair " +
                       pair.name + " has " + what);
  };
  const bool coulomb = pair.kind == contact::Kind::coulomb;
  need(p[0] == 0 || p[0] == 1, "slip = " + input::echo_number(p[0]) + " (allowed: 0 or 1)");
  need(p[4] == 0 || p[4] == 1, "off = " + input::echo_number(p[4]) + " (allowed: 0 or 1)");
  need(p[0] == 0 || coulomb, "slip = 1 in a pair that is not coulomb");
  need(p[4] == 0 || (coulomb && p[0] == 0), "off = 1 but is not a sticking coulomb entry");
  const double norm = std::sqrt(p[1] * p[1] + p[2] * p[2] + p[3] * p[3]);
  need(std::isfinite(norm) && norm <= 1 + 1e-12,
       "a slip direction of length " + input::echo_number(norm) + " (allowed: at most 1)");
  need(p[0] == 0 || norm >= 1 - 1e-12,
       "slip = 1 with a direction of length " + input::echo_number(norm) + " (allowed: 1)");
}

/// docs/THEORY.md §2.4, §5.5: an entry lies on its facet within the edge extension of
/// activation (xi clamped to the triangle at activation; a sliding entry beyond it is off and
/// released at the end of its step), except a sticking Coulomb entry that slid off its facet
/// (off = 1, §11.7), which keeps the xi it slid to.
void check_xi(const double* xi, bool off, const contact::Pair& pair, int slave,
              const std::string& path) {
  const double edge = contact::entry_rule(pair).edge, outside = kernels::facet_outside(xi);
  if (outside > edge && !off)
    refuse(path, "the checkpoint's active node " + std::to_string(slave) + " of pair " + pair.name +
                     " has xi = (" + number(xi[0]) + ", " + number(xi[1]) +
                     "), outside its facet by " + number(outside) + " (allowed: up to " +
                     number(edge) + ", the edge extension of activation)");
}

void check_active(const output::Checkpoint& c, const Simulation& sim, const std::string& path) {
  static const std::vector<contact::Pair> none;
  const auto& pairs = sim.contact ? sim.contact->pairs() : none;
  std::unordered_set<int> seen;
  for (std::size_t k = 0; k + contact::kPackedActive <= c.active.size();
       k += contact::kPackedActive) {
    const int slave = index_in(c.active[k], sim.model.num_nodes(), "node", path);
    const auto& pair = pairs[index_in(c.active[k + 1], pairs.size(), "pair", path)];
    index_in(c.active[k + 2], pair.facets.size(), "facet of pair " + pair.name, path);
    if (!std::binary_search(pair.slaves.begin(), pair.slaves.end(), slave))
      refuse(path, "the checkpoint's active node " + std::to_string(slave) +
                       " is not a slave node of pair " + pair.name);
    if (!seen.insert(slave).second)  // one entry per slave node: eliminated once (§3)
      refuse(path, "the checkpoint's active node " + std::to_string(slave) +
                       " is listed twice (allowed: one entry per slave node)");
    if (!std::isfinite(c.active[k + 3]) || !std::isfinite(c.active[k + 4]) ||
        !std::isfinite(c.normal_force[k / contact::kPackedActive]))
      refuse(path, "the checkpoint's active node " + std::to_string(slave) +
                       " has coordinates or a normal force that are not finite");
    const std::size_t entry = k / contact::kPackedActive;
    const double* state = c.state.empty() ? nullptr : &c.state[entry * contact::kPackedState];
    if (state) check_state(state, pair, slave, path);
    check_xi(&c.active[k + 3], state && state[4] == 1, pair, slave, path);
  }
}

}  // namespace

std::string model_fingerprint(const Simulation& sim) {
  const auto& m = sim.model;
  std::ostringstream os;
  os.precision(17);
  os << "nodes: " << m.num_nodes() << "\ntets: " << m.global_tets
     << "\nrigid nodes: " << m.rigid_X.size() / 3 << "\nintegrator: " << int(m.integrator)
     << "\nbodies: " << m.bodies.size() << "\n";
  for (const auto& b : m.bodies) {
    os << "body " << b.name << ": nodes " << b.node_end - b.node_begin << ", tets "
       << b.tet_end - b.tet_begin << ", rigid " << b.rigid << ", young " << b.young << ", poisson "
       << b.poisson << ", density " << b.density;
    if (b.model == fem::MaterialModel::neo_hookean) os << ", model neo-hookean";
    if (b.model == fem::MaterialModel::mooney_rivlin)
      os << ", model mooney-rivlin, c1 " << b.c1 << ", c2 " << b.c2;
    os << "\n";
  }
  std::uint64_t h = m.mesh_fnv;  // X, the tets, rigid_X, fixed: hashed where all were held
  if (sim.contact) {
    os << "pairs: " << sim.contact->pairs().size() << "\n";
    for (const auto& p : sim.contact->pairs()) {
      os << "pair " << p.name << ": "
         << (p.kind == contact::Kind::frictionless ? "frictionless"
             : p.kind == contact::Kind::coulomb    ? "coulomb"
                                                   : "full stick")
         << ", slaves " << p.slaves.size() << ", facets " << p.facets.size() << ", master body "
         << p.master_body << "\n";
      fem::fnv_into(h, p.slaves);
      fem::fnv_into(h, p.facets);
    }
  }
  os << "geometry hash: " << hex(h) << "\n";
  return os.str();
}

void check_model(const std::string& model, const Simulation& sim, const std::string& path) {
  const std::string diff = first_difference(model, model_fingerprint(sim));
  if (!diff.empty()) refuse(path, "written for another model: " + diff);
}

void check_checkpoint(const output::Checkpoint& c, const Simulation& sim, const std::string& path) {
  check_model(c.model, sim, path);
  check_scalars(c, path);
  check_arrays(c, sim, path);
  check_active(c, sim, path);
}

void check_against_monitors(const output::Checkpoint& c,
                            const std::vector<output::MonitorRow>& rows, const std::string& path,
                            const std::string& monitors) {
  for (std::size_t i = 1; i < rows.size(); ++i)
    if (!(rows[i].time > rows[i - 1].time))
      throw Error(monitors + ": t = " + number(rows[i].time) + " at step " +
                  std::to_string(rows[i].step) + " is not after t = " + number(rows[i - 1].time) +
                  " at step " + std::to_string(rows[i - 1].step) +
                  " (allowed: times that increase from row to row)");
  if (rows.empty()) throw Error(monitors + ": no row for the checkpoint's step");
  const output::MonitorRow& row = rows.back();
  auto need = [&](bool ok, const std::string& what, double mine, double theirs) {
    if (!ok)
      refuse(path, "the checkpoint's " + what + " = " + number(mine) + " at step " +
                       std::to_string(c.step) + " disagrees with " + monitors + " (" + what +
                       " = " + number(theirs) + " in the row of that step)");
  };
  // both hold the same doubles, written to 17 digits: equal bit for bit
  need(c.t == row.time, "t", c.t, row.time);
  if (c.step > 0) need(c.last_h == row.dt, "last step size (dt of the row)", c.last_h, row.dt);
}

void check_facet_point(const contact::Active& a, const contact::Pair& pair,
                       const std::array<double, 2>& d, const std::string& path) {
  const double h = std::max(d[1], pair.edge);
  const double allowed = pair.dmax + 2 * contact::entry_rule(pair).edge * h + 1e-9 * h;
  if (!(d[0] <= allowed))
    throw Error(path + ": the checkpoint's active node " + std::to_string(a.slave) + " of pair " +
                pair.name + " lies " + number(d[0]) + " from its facet " + std::to_string(a.facet) +
                "'s point at xi = (" + number(a.xi[0]) + ", " + number(a.xi[1]) +
                ") (allowed: up to " + number(allowed) +
                ", the pair's max penetration and the facet tolerance); refused (corrupt, or "
                "forged)");
}

void check_restored_monitors(const output::MonitorRow& m, const MonitorScales& scales,
                             const output::MonitorRow& row, const std::string& path,
                             const std::string& monitors) {
  auto need = [&](const char* what, double mine, double kept, double scale) {
    if (std::fabs(mine - kept) <= kRestoreTolerance * scale) return;
    throw Error(path + ": its state's " + what + " = " + number(mine) + " at step " +
                std::to_string(row.step) + " disagrees with " + monitors + " (" + number(kept) +
                " in the row of that step; allowed: a difference up to " +
                number(kRestoreTolerance * scale) +
                ", the round-off of its recomputation); refused (a checkpoint of another run "
                "of this model, or corrupt)");
  };
  const double E = scales.energy, P = scales.momentum, R = scales.length;
  need("kinetic energy", m.kinetic, row.kinetic, E);
  need("elastic energy", m.elastic, row.elastic, E);
  need("potential energy", m.potential, row.potential, E);
  need("total energy", m.total, row.total, E);
  static const char* L[] = {"Lx", "Ly", "Lz"};
  static const char* J[] = {"Jx", "Jy", "Jz"};
  static const char* com[] = {"com_x", "com_y", "com_z"};
  for (int i = 0; i < 3; ++i) need(L[i], m.L[i], row.L[i], P);
  for (int i = 0; i < 3; ++i) need(J[i], m.J[i], row.J[i], R * P);
  for (int i = 0; i < 3; ++i) need(com[i], m.com[i], row.com[i], R);
}

}  // namespace emc::app
