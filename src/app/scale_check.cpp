#include "emcontact/app/scale_check.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "emcontact/contact/active.hpp"
#include "emcontact/error.hpp"
#include "emcontact/format.hpp"
#include "emcontact/input/detail.hpp"
#include "emcontact/input/echo.hpp"

namespace emc::app {
namespace {

struct Box {
  std::array<double, 3> lo{}, hi{};
  bool empty = true;
  void add(const double* x) {
    for (int c = 0; c < 3; ++c) {
      lo[c] = empty ? x[c] : std::min(lo[c], x[c]);
      hi[c] = empty ? x[c] : std::max(hi[c], x[c]);
    }
    empty = false;
  }
  double diagonal() const {
    if (empty) return 0;
    return std::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  }
};

std::string number(double x) {
  return format("%.3g", x);
}

/// docs/THEORY.md §6.3: the smallest max penetration, the round-off of a gap g_N on the master
/// (contact::gap_roundoff: 64 eps of the largest coordinate and the facet size): a window
/// -dmax < g_N < 0 narrower than that holds no penetration that can be told from touching.
double min_penetration(const Box& master, double edge) {
  double xmax = 0;
  for (int c = 0; c < 3; ++c)
    xmax = std::max({xmax, std::fabs(master.lo[c]), std::fabs(master.hi[c])});
  const double x[3] = {xmax, 0, 0};
  return contact::gap_roundoff(edge, x);
}

/// Coordinates of contact geometry node `n` (deformable: global node, rigid: num_nodes + k).
const double* geometry_node(const fem::Model& m, int n) {
  return n < m.num_nodes() ? m.x(n) : &m.rigid_X[3 * (n - m.num_nodes())];
}

/// The hints noted by note_parameter_scales.
std::string g_hints;

/// A parameter's value as the user writes it.
std::string value(double x) {
  return input::detail::format_double(x);
}

std::string vec(const std::array<double, 3>& v) {
  return "{" + value(v[0]) + ", " + value(v[1]) + ", " + value(v[2]) + "}";
}

double length(const std::array<double, 3>& v) {
  return std::hypot(v[0], v[1], v[2]);
}

/// The hints of one deformable body (see note_parameter_scales).
void body_hints(const fem::Body& b, const fem::Model& model, double dt, double dt_min, double end,
                std::vector<std::string>& hints) {
  const double h = b.median_edge, radius = b.radius;
  if (!(h > 0)) return;
  const std::string at = "Bodies/" + input::echo(b.name) + "/";
  const auto add = [&](const std::string& hint) { hints.push_back(hint); };
  const double c = std::sqrt(b.young / b.density), waves = c * dt / h;
  if (waves > 1e3)
    add("Time/dt = " + value(dt) + " with " + at + "Material/young = " + value(b.young) +
        " and density = " + value(b.density) + ": the elastic wave, sqrt(young / density) = " +
        number(c) + " m/s, crosses c dt / h = " + number(waves) + " elements (h = " + number(h) +
        ") per step, and the Newton matrix's condition grows as its square (a "
        "smaller Time/dt, or a direct solver: Solver/Linear/type)");
  if (b.poisson > 0.499)
    add(at + "Material/poisson = " + value(b.poisson) +
        ": nearly incompressible (lambda / mu = " + number(2 * b.poisson / (1 - 2 * b.poisson)) +
        "), an ill-conditioned Newton matrix (a direct solver copes: Solver/Linear/type)");
  const double omega = length(b.angular_velocity);
  if (omega * dt_min > 0.5)
    add(at + "Initial/angular velocity = " + vec(b.angular_velocity) + " turns the body by " +
        number(omega * dt_min) + " rad even in the smallest step (dt = " + number(dt_min) +
        " after Time/max step cuts), and Newton needs well below 1 rad per step (a smaller "
        "Time/dt)");
  const double stress = b.density * omega * omega * radius * radius;
  if (stress > b.young)
    add(at + "Initial/angular velocity = " + vec(b.angular_velocity) +
        ": its centrifugal stress, density omega^2 r^2 = " + number(stress) + ", is " +
        number(stress / b.young) + " times young: it tears the body apart");
  const double flight = length(b.velocity) * end + 0.5 * length(model.gravity) * end * end;
  if (flight * std::numeric_limits<double>::epsilon() > 1e-3 * h)
    add(at + "Initial/velocity = " + vec(b.velocity) +
        " and Loads/gravity = " + vec(model.gravity) + " move the body up to " + number(flight) +
        " by Time/end: its positions lose more than 1e-3 of an element (h = " + number(h) +
        ") to round-off");
}

}  // namespace

void note_parameter_scales(const fem::Model& model, const Teuchos::ParameterList& params) {
  const auto& time = params.sublist("Time");
  const double dt = time.get<double>("dt"), end = time.get<double>("end");
  const double dt_min = std::ldexp(dt, -time.get<int>("max step cuts"));
  std::vector<std::string> hints;
  for (const auto& b : model.bodies)
    if (!b.rigid) body_hints(b, model, dt, dt_min, end, hints);
  g_hints.clear();
  // the first two, and how many more (one line stays readable)
  for (std::size_t k = 0; k < hints.size() && k < 2; ++k)
    g_hints += (k ? "; " : "; parameters that may keep the step from being solved: ") + hints[k];
  if (hints.size() > 2) g_hints += "; and " + std::to_string(hints.size() - 2) + " more";
}

std::string step_failure_hint() {
  return g_hints;
}

std::string with_step_failure_hint(const std::string& message) {
  if (g_hints.empty() || message.find("could not be solved") == std::string::npos) return message;
  const auto kept = message.find("; the last accepted step is in ");
  if (kept == std::string::npos) return message + g_hints;
  return message.substr(0, kept) + g_hints + message.substr(kept);
}

void check_contact_scales(const fem::Model& model, const std::vector<contact::Pair>& pairs,
                          const std::string& file) {
  for (const auto& p : pairs) {
    Box master;
    for (const auto& f : p.facets)
      for (int n : f) master.add(geometry_node(model, n));
    const double d = master.diagonal();
    const std::string allowed = "allowed: 0 (automatic) or a depth from " +
                                number(min_penetration(master, p.edge)) + " to " + number(d);
    if (p.dmax > d && d > 0)
      throw InputError(file + ": parameter \"Contact/" + p.name + "/max penetration\": value " +
                       number(p.dmax) + " is larger than the master surface (bounding box " +
                       "diagonal " + number(d) + "): contact would never activate; " + allowed);
    if (p.dmax < min_penetration(master, p.edge))
      throw InputError(file + ": parameter \"Contact/" + p.name + "/max penetration\": value " +
                       number(p.dmax) + " is below the round-off of a gap on the master (" +
                       number(min_penetration(master, p.edge)) +
                       "): no penetration could be told from touching; " + allowed);
  }
  Box deformable;  // over the held nodes: they hold every body's boundary, so its extremes
  for (std::size_t i = 0; i + 2 < model.X.size(); i += 3) deformable.add(&model.X[i]);
  const double size = deformable.diagonal();
  for (const auto& b : model.bodies) {
    if (!b.rigid || size <= 0) continue;
    Box rigid;
    for (std::size_t i = 0; i + 2 < b.mesh.X.size(); i += 3) rigid.add(&b.mesh.X[i]);
    if (rigid.diagonal() > kMaxRigidScale * size)
      throw InputError(file + ": parameter \"Bodies/" + b.name + "/Mesh\": the rigid surface " +
                       "is " + number(rigid.diagonal()) + " across, more than 1e6 times the " +
                       "deformable bodies (" + number(size) + "): its round-off would swamp " +
                       "the gaps; allowed: a rigid surface at most " +
                       number(kMaxRigidScale * size) + " across ('half width', corners)");
  }
}

}  // namespace emc::app
