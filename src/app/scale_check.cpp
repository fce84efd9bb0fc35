#include "emcontact/app/scale_check.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include "emcontact/contact/active.hpp"
#include "emcontact/error.hpp"

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
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
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
  return n < m.num_nodes() ? &m.X[3 * n] : &m.rigid_X[3 * (n - m.num_nodes())];
}

}  // namespace

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
  Box deformable;
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
