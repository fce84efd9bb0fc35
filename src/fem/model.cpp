#include "emcontact/fem/model.hpp"

#include <Teuchos_Array.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "emcontact/error.hpp"
#include "emcontact/input/input.hpp"
#include "emcontact/types.hpp"
#include "kernels/tet4_loops.hpp"

namespace emc::fem {

Scatter resolve_scatter(ScatterChoice choice) {
  // auto: atomic adds in the Serial backend, where they are plain adds in loop order
  // (reproducible, and faster: perf/README.md "OpenMP threads"); the coloured loops on a threaded
  // backend, where threads would reorder the adds and where an atomic add stays a locked
  // instruction even on one thread (3-4x slower than the coloured loops there)
  if (choice == ScatterChoice::automatic)
    return kernels::one_thread<ExecSpace>() ? Scatter::atomic : Scatter::coloured;
  return choice == ScatterChoice::coloured ? Scatter::coloured : Scatter::atomic;
}

namespace {

std::array<double, 3> vec3(const Teuchos::ParameterList& p, const std::string& name,
                           const std::string& where) {
  const auto& a = p.get<Teuchos::Array<double>>(name);
  if (a.size() != 3)
    throw InputError(where + "/" + name + ": expected 3 components, got " +
                     std::to_string(a.size()));
  return {a[0], a[1], a[2]};
}

/// docs/THEORY.md §12.1: Mooney-Rivlin's c2 (c1 = mu / 2 - c2 with the small-strain mu of young
/// and poisson) at most mu / 2 (c1 >= 0) and lambda / 4 (the volumetric term's lambda - 4 c2 >=
/// 0: below, W has no minimum in J).
void mooney_rivlin_constants(const Teuchos::ParameterList& mat, Body& b, const std::string& at) {
  b.c2 = mat.get<double>("c2");
  const kernels::Lame l = kernels::lame(b.young, b.poisson);
  b.c1 = 0.5 * l.mu - b.c2;
  const double most = std::min(0.5 * l.mu, 0.25 * l.lambda);
  const auto g = [](double v) {
    std::ostringstream os;
    os << std::setprecision(6) << v;
    return os.str();
  };
  if (b.c2 > most)
    throw InputError(at + "c2: " + g(b.c2) + " is above " +
                     (0.5 * l.mu <= 0.25 * l.lambda ? "mu / 2 = " : "lambda / 4 = ") + g(most) +
                     " (mu, lambda of young and poisson: c1 = mu / 2 - c2 and the volumetric "
                     "lambda - 4 c2 must not be negative); allowed: 0 <= c2 <= " +
                     g(most));
}

Body make_body(const std::string& name, const Teuchos::ParameterList& bp, mesh::BodyMesh mesh,
               const std::string& where) {
  Body b;
  b.name = name;
  const auto& mat = bp.sublist("Material");
  const std::string at = where + "/Material/";
  b.model = Teuchos::getIntegralValue<MaterialModel>(mat, "model");
  b.young = mat.get<double>("young");
  b.poisson = mat.get<double>("poisson");
  b.density = mat.get<double>("density");
  if (b.model == MaterialModel::mooney_rivlin) mooney_rivlin_constants(mat, b, at);
  const auto& init = bp.sublist("Initial");
  b.velocity = vec3(init, "velocity", where + "/Initial");
  b.angular_velocity = vec3(init, "angular velocity", where + "/Initial");
  b.mesh = std::move(mesh);
  return b;
}

/// Marks the nodes of every Dirichlet condition's surface as fixed.
void apply_dirichlet(const Teuchos::ParameterList& params, Model& m, const std::string& file) {
  if (!params.isSublist("Dirichlet")) return;
  const auto& dl = params.sublist("Dirichlet");
  for (const std::string& cname : input::sublist_names(dl)) {
    const auto& c = dl.sublist(cname);
    const std::string where = file + ": Dirichlet/" + cname;
    const std::string body = c.get<std::string>("body");
    const std::string surface = c.get<std::string>("surface");
    int bi = -1;
    for (std::size_t k = 0; k < m.bodies.size(); ++k)
      if (m.bodies[k].name == body) bi = static_cast<int>(k);
    if (bi < 0) throw InputError(where + "/body: no body named \"" + body + "\"");
    const Body& b = m.bodies[bi];
    if (b.rigid)
      throw InputError(where + "/body: \"" + body + "\" is a rigid surface: it is fixed already");
    for (int n : mesh::surface_nodes(b.mesh, surface, where + "/surface"))
      m.fixed[b.node_begin + n] = 1;
  }
}

}  // namespace

Model build_model(const Teuchos::ParameterList& params, std::vector<mesh::BodyMesh> meshes,
                  const std::string& file) {
  Model m;
  bool held = true;
  const auto& bl = params.sublist("Bodies");
  std::size_t k = 0;
  for (const std::string& name : input::sublist_names(bl)) {
    if (k >= meshes.size()) throw Error("internal: fewer meshes than bodies");
    Body b = make_body(name, bl.sublist(name), std::move(meshes[k++]), file + ": Bodies/" + name);
    b.node_begin = b.node_end = m.num_nodes();
    b.tet_begin = b.tet_end = static_cast<int>(m.global_tets);
    if (mesh::is_rigid(b.mesh)) {  // a rigid surface body
      for (double v : {b.velocity[0], b.velocity[1], b.velocity[2], b.angular_velocity[0],
                       b.angular_velocity[1], b.angular_velocity[2]})
        if (v != 0)
          throw InputError(file + ": Bodies/" + name +
                           "/Initial: a rigid surface (a mesh without tetrahedra) is fixed; "
                           "allowed: zero velocity and angular velocity");
      b.rigid = true;
      b.rigid_begin = static_cast<int>(m.rigid_X.size() / 3);
      m.rigid_X.insert(m.rigid_X.end(), b.mesh.X.begin(), b.mesh.X.end());
      m.bodies.push_back(std::move(b));
      continue;
    }
    held = held && b.mesh.dropped_tets < 0;
    m.X.insert(m.X.end(), b.mesh.X.begin(), b.mesh.X.end());
    for (int t : b.mesh.tets) m.tets.push_back(b.node_begin + t);
    b.node_end = m.num_nodes();
    m.global_tets += b.mesh.body_tets();
    b.tet_end = static_cast<int>(m.global_tets);
    m.body_of_tet.resize(m.num_tets(), static_cast<int>(m.bodies.size()));
    mesh::drop_tets(b.mesh);  // the model holds them now
    std::vector<double>().swap(b.mesh.X);
    m.bodies.push_back(std::move(b));
  }
  if (held) {  // every tet is here: the bodies' geometry and the mesh's identity
    m.owned_tets = m.num_tets();
    for (std::size_t b = 0; b < m.bodies.size(); ++b)
      if (!m.bodies[b].rigid) body_geometry(m, static_cast<int>(b));
  }
  m.fixed.assign(m.num_nodes(), 0);
  apply_dirichlet(params, m, file);
  if (held) {
    m.mesh_fnv = fnv_basis;
    fnv_into(m.mesh_fnv, m.X);
    fnv_into(m.mesh_fnv, m.tets);
    fnv_into(m.mesh_fnv, m.rigid_X);
    fnv_into(m.mesh_fnv, m.fixed);
  }
  if (params.isSublist("Loads"))
    m.gravity = vec3(params.sublist("Loads"), "gravity", file + ": Loads");
  if (params.isSublist("Solver") && params.sublist("Solver").isSublist("Assembly")) {
    const auto& a = params.sublist("Solver").sublist("Assembly");
    if (a.isParameter("scatter"))
      m.scatter = resolve_scatter(Teuchos::getIntegralValue<ScatterChoice>(a, "scatter"));
  }
  return m;
}

int massless_mask(const Model& m, int e) {
  int mask = 0;
  if (m.massless.empty()) return mask;
  for (int a = 0; a < 4; ++a)
    if (m.is_massless(m.tets[4 * e + a])) mask |= 1 << a;
  return mask;
}

// docs/THEORY.md §6.8: the moved mass has the same first moment (its T reproduces affine fields)
void body_geometry(Model& m, int b) {
  Body& body = m.bodies[b];
  double vol = 0;
  std::array<double, 3> c{};
  std::vector<double> edges;
  edges.reserve(body.tet_end - body.tet_begin);
  for (int e = body.tet_begin; e < body.tet_end; ++e) {
    double x[4][3];
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) x[a][i] = m.x(m.tets[4 * e + a])[i];
    const double v = kernels::tet_volume(x);
    vol += v;
    for (int i = 0; i < 3; ++i) c[i] += v * 0.25 * (x[0][i] + x[1][i] + x[2][i] + x[3][i]);
    double edge = 0;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        edge = std::max(edge, std::hypot(x[i][0] - x[j][0], x[i][1] - x[j][1], x[i][2] - x[j][2]));
    edges.push_back(edge);
  }
  for (int i = 0; i < 3; ++i) c[i] /= vol;
  body.centre = c;
  body.median_edge = 0;
  if (!edges.empty()) {
    std::nth_element(edges.begin(), edges.begin() + edges.size() / 2, edges.end());
    body.median_edge = edges[edges.size() / 2];
  }
  // the largest distance of a node from the nodes' centroid
  const int nn = body.node_end - body.node_begin;
  std::array<double, 3> g{};
  for (int n = body.node_begin; n < body.node_end; ++n)
    for (int k = 0; k < 3; ++k) g[k] += m.X[3 * n + k] / nn;
  body.radius = 0;
  for (int n = body.node_begin; n < body.node_end; ++n)
    body.radius = std::max(
        body.radius, std::hypot(m.X[3 * n] - g[0], m.X[3 * n + 1] - g[1], m.X[3 * n + 2] - g[2]));
}

std::array<double, 3> initial_velocity(const Model& m, int n) {
  for (const Body& body : m.bodies) {
    if (body.rigid || n < body.node_begin || n >= body.node_end) continue;
    const auto& c = body.centre;
    const auto& v = body.velocity;
    const auto& w = body.angular_velocity;
    const double* X = m.x(n);
    const double r[3] = {X[0] - c[0], X[1] - c[1], X[2] - c[2]};
    return {v[0] + w[1] * r[2] - w[2] * r[1], v[1] + w[2] * r[0] - w[0] * r[2],
            v[2] + w[0] * r[1] - w[1] * r[0]};
  }
  return {0.0, 0.0, 0.0};
}

std::vector<double> initial_velocity(const Model& m) {
  if (!m.holds_all_nodes()) throw Error("internal: initial_velocity of every node needs them all");
  std::vector<double> V(m.X.size(), 0.0);
  for (int n = 0; n < m.num_nodes(); ++n) {
    const auto v = initial_velocity(m, n);
    std::copy(v.begin(), v.end(), V.begin() + 3 * std::size_t(n));
  }
  return V;
}

int Model::local_node(int n) const {
  if (node_ids.empty()) return n >= 0 && n < held_nodes() ? n : -1;
  const auto it = std::lower_bound(node_ids.begin(), node_ids.end(), n);
  return it != node_ids.end() && *it == n ? static_cast<int>(it - node_ids.begin()) : -1;
}

int Model::held_node(int n) const {
  const int l = local_node(n);
  if (l < 0) throw Error("internal: node " + std::to_string(n) + " is not held on this rank");
  return l;
}

void keep_nodes(Model& m, std::vector<int> held) {
  const int global = m.num_nodes();
  std::vector<double> X(3 * held.size());
  std::vector<char> fixed(held.size()), massless(m.massless.empty() ? 0 : held.size());
  for (std::size_t l = 0; l < held.size(); ++l) {
    const int l0 = m.held_node(held[l]);
    std::copy_n(&m.X[3 * std::size_t(l0)], 3, &X[3 * l]);
    fixed[l] = m.fixed[l0];
    if (!massless.empty()) massless[l] = m.massless[l0];
  }
  m.X = std::move(X);
  m.fixed = std::move(fixed);
  m.massless = std::move(massless);
  held.shrink_to_fit();  // gathered from 4 ids per tet: its capacity would outweigh X
  m.node_ids = std::move(held);
  m.global_nodes = global;
}

}  // namespace emc::fem
