#include "emcontact/contact/pairs.hpp"

#include <algorithm>
#include <cmath>

#include "emcontact/error.hpp"
#include "emcontact/format.hpp"
#include "emcontact/input/echo.hpp"
#include "kernels/facet.hpp"

namespace emc::contact {

namespace {

struct SurfaceRef {
  int body = -1;
  std::string surface;  ///< empty: the whole boundary
};

SurfaceRef parse_ref(const fem::Model& m, const std::string& ref, const std::string& where) {
  SurfaceRef r;
  const auto slash = ref.find('/');
  const std::string body = ref.substr(0, slash);
  if (slash != std::string::npos) r.surface = ref.substr(slash + 1);
  std::string names;
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    names += (b ? ", " : "") + m.bodies[b].name;
    if (m.bodies[b].name == body) r.body = static_cast<int>(b);
  }
  if (r.body < 0) throw InputError(where + ": no body named \"" + body + "\"; bodies: " + names);
  // body/boundary is the whole boundary, as the body's name alone (unless the mesh names a
  // surface "boundary" of its own)
  if (r.surface == "boundary" && m.bodies[r.body].mesh.surfaces.count("boundary") == 0)
    r.surface.clear();
  return r;
}

/// Triangles (body-local node ids) of a body's surface: a named surface, or for a whole
/// deformable body its boundary, for a rigid body all its triangles.
std::vector<std::array<int, 3>> surface_triangles(const fem::Body& b, const std::string& name,
                                                  const std::string& where) {
  if (name.empty()) {
    if (!b.rigid) return mesh::boundary_triangles(b.mesh);
    std::vector<std::array<int, 3>> all;
    for (const auto& [n, tris] : b.mesh.surfaces) all.insert(all.end(), tris.begin(), tris.end());
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    return all;
  }
  auto it = b.mesh.surfaces.find(name);
  if (it == b.mesh.surfaces.end()) {
    std::vector<std::string> names;
    for (const auto& [n, t] : b.mesh.surfaces) names.push_back(n);
    throw InputError(where + ": body \"" + input::echo(b.name) + "\" has no surface \"" +
                     input::echo(name) + "\"; its surfaces: " + input::echo_list(names, 10) +
                     " and \"boundary\" (its whole boundary, also named by the body alone)");
  }
  return it->second;
}

/// Half the mean edge length of the facets (reference configuration).
double half_mean_edge(const std::vector<std::array<int, 3>>& facets, const std::vector<double>& x) {
  double sum = 0;
  for (const auto& f : facets)
    for (int k = 0; k < 3; ++k) {
      const int a = f[k], b = f[(k + 1) % 3];
      double d2 = 0;
      for (int i = 0; i < 3; ++i) d2 += std::pow(x[3 * a + i] - x[3 * b + i], 2);
      sum += std::sqrt(d2);
    }
  return facets.empty() ? 0 : 0.5 * sum / (3.0 * facets.size());
}

/// The triangles around each slave node (CSR over the index into p.slaves).
void index_slave_triangles(Pair& p) {
  const auto index = [&p](int node) {
    return static_cast<int>(std::lower_bound(p.slaves.begin(), p.slaves.end(), node) -
                            p.slaves.begin());
  };
  p.tri_start.assign(p.slaves.size() + 1, 0);
  for (const auto& t : p.slave_facets)
    for (int a : t) ++p.tri_start[index(a) + 1];
  for (std::size_t k = 0; k < p.slaves.size(); ++k) p.tri_start[k + 1] += p.tri_start[k];
  p.slave_tris.resize(p.tri_start.back());
  std::vector<int> fill(p.tri_start.begin(), p.tri_start.end() - 1);
  for (std::size_t t = 0; t < p.slave_facets.size(); ++t)
    for (int a : p.slave_facets[t]) p.slave_tris[fill[index(a)]++] = static_cast<int>(t);
}

/// docs/THEORY.md §6.3, a named master surface: the rest of the deformable master body's
/// boundary follows the named surface's facets in p.facets, outward, so that a slave node that
/// reaches the body through another face (over the named surface's edge) is held there too.
void add_rest_of_boundary(const fem::Body& mb, Pair& p) {
  const auto key = [](std::array<int, 3> t) {
    std::sort(t.begin(), t.end());
    return t;
  };
  std::vector<std::array<int, 3>> named;
  for (const auto& f : p.facets) named.push_back(key(f));
  std::sort(named.begin(), named.end());
  for (const auto& t : mesh::boundary_triangles(mb.mesh)) {
    const std::array<int, 3> f = {mb.node_begin + t[0], mb.node_begin + t[1], mb.node_begin + t[2]};
    if (!std::binary_search(named.begin(), named.end(), key(f))) p.facets.push_back(f);
  }
}

}  // namespace

void slave_normal(const Pair& p, int s, const std::vector<double>& x, double n[3]) {
  n[0] = n[1] = n[2] = 0;
  const auto it = std::lower_bound(p.slaves.begin(), p.slaves.end(), s);
  if (it == p.slaves.end() || *it != s) return;
  const auto k = it - p.slaves.begin();
  for (int j = p.tri_start[k]; j < p.tri_start[k + 1]; ++j) {
    const auto& t = p.slave_facets[p.slave_tris[j]];
    double xm[3][3];
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < 3; ++i) xm[a][i] = x[3 * t[a] + i];
    const kernels::Facet f = kernels::facet(xm);
    for (int i = 0; i < 3; ++i) n[i] += f.area2 * f.n[i];
  }
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (int i = 0; i < 3; ++i) n[i] = len > 0 ? n[i] / len : 0.0;
}

std::vector<double> positions(const fem::Model& model, const std::vector<double>& u) {
  const std::size_t deformable = 3 * static_cast<std::size_t>(model.num_nodes());
  std::vector<double> x(deformable + model.rigid_X.size(), 0.0);
  for (int l = 0; l < model.held_nodes(); ++l) {
    const std::size_t k = 3 * static_cast<std::size_t>(model.node_id(l));
    for (int c = 0; c < 3; ++c) x[k + c] = model.X[3 * l + c] + (u.empty() ? 0.0 : u[k + c]);
  }
  std::copy(model.rigid_X.begin(), model.rigid_X.end(), x.begin() + deformable);
  return x;
}

std::vector<Pair> build_pairs(const std::vector<PairSettings>& settings, const fem::Model& model,
                              const std::string& file) {
  std::vector<Pair> pairs;
  const auto x0 = positions(model, {});
  for (const PairSettings& c : settings) {
    const std::string where = file + ": Contact/" + c.name;
    Pair p;
    p.name = c.name;
    p.kind = c.kind;
    p.mu = c.mu;
    p.close_gap = c.close_gap;
    p.massless_slave = c.massless_slave;
    const SurfaceRef s = parse_ref(model, c.slave, where + "/slave");
    const SurfaceRef m = parse_ref(model, c.master, where + "/master");
    const fem::Body& sb = model.bodies[s.body];
    const fem::Body& mb = model.bodies[m.body];
    if (sb.rigid)
      throw InputError(where + "/slave: \"" + sb.name +
                       "\" is a rigid surface; a slave must be a deformable body (a rigid "
                       "surface is always the master)");
    if (s.body == m.body)
      throw InputError(where + ": slave and master are the same body \"" + sb.name +
                       "\"; self-contact is not supported");
    for (const auto& t : surface_triangles(sb, s.surface, where + "/slave")) {
      p.slave_facets.push_back({sb.node_begin + t[0], sb.node_begin + t[1], sb.node_begin + t[2]});
      for (int a : t) p.slaves.push_back(sb.node_begin + a);
    }
    std::sort(p.slaves.begin(), p.slaves.end());
    p.slaves.erase(std::unique(p.slaves.begin(), p.slaves.end()), p.slaves.end());
    index_slave_triangles(p);
    const int off = mb.rigid ? model.num_nodes() + mb.rigid_begin : mb.node_begin;
    for (const auto& t : surface_triangles(mb, m.surface, where + "/master"))
      p.facets.push_back({off + t[0], off + t[1], off + t[2]});
    if (p.facets.empty()) throw InputError(where + "/master: the surface has no triangles");
    p.master_body = m.body;
    p.slave_body = s.body;
    p.rigid_master = mb.rigid;
    p.edge = 2 * half_mean_edge(p.facets, x0);
    if (!mb.rigid && !m.surface.empty()) add_rest_of_boundary(mb, p);
    p.dmax = c.dmax > 0 ? c.dmax : 0.5 * p.edge;
    pairs.push_back(std::move(p));
  }
  return pairs;
}

void mark_massless_slaves(const std::vector<Pair>& pairs, fem::Model& model,
                          const std::string& file) {
  if (!model.holds_all_nodes()) throw Error("internal: mark_massless_slaves after distribute");
  for (const auto& p : pairs) {
    if (!p.massless_slave) continue;
    model.massless.resize(model.num_nodes(), 0);
    for (int s : p.slaves) model.massless[s] = 1;
  }
  // docs/THEORY.md §6.8: the fit needs every tet: rank 0's (fem::distribute hands it out)
  if (!model.holds_all_tets()) return;
  const int bad = fem::fit_massless_nodes(model);
  if (bad < 0) return;
  for (const auto& p : pairs)
    if (p.massless_slave && std::binary_search(p.slaves.begin(), p.slaves.end(), bad)) {
      std::string body;
      for (const auto& b : model.bodies)
        if (!b.rigid && bad >= b.node_begin && bad < b.node_end) body = b.name;
      throw InputError(file + ": Contact/" + p.name + "/massless slave: the nodes of body \"" +
                       body + "\" off its slave surface do not span 3D around slave node " +
                       std::to_string(bad + 1) +
                       ", so its mass cannot be moved onto them keeping the body's centre of "
                       "mass and inertia; allowed: a slave surface with nodes behind it "
                       "(body/surface) or a finer mesh");
    }
}

}  // namespace emc::contact
