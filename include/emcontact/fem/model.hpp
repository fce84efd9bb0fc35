#pragma once
// The description of the problem: all bodies' meshes concatenated, materials, initial
// velocities, loads and fixed nodes. The tetrahedra are on rank 0 and the per-node data
// (coordinates, fixed and massless flags) on every rank until fem::distribute hands every
// rank its part of the tets and a layer of ghosts, and keeps of the per-node data only the
// nodes those tets use and the bodies' surface nodes (docs/developer-guide.md, "Distributed
// model"). Nodes keep their global ids everywhere: Model::x(n), is_fixed(n), is_massless(n).
#include <Teuchos_ParameterList.hpp>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "emcontact/fem/material.hpp"
#include "emcontact/fem/scatter.hpp"
#include "emcontact/mesh/body_mesh.hpp"
#include "kernels/em_tet4.hpp"

namespace emc::fem {

struct Body {
  std::string name;
  int node_begin = 0, node_end = 0;  ///< global node range [begin, end)
  int tet_begin = 0, tet_end = 0;    ///< global tet range
  /// Material/model and its constants: young and poisson the small-strain ones, c1 = mu/2 - c2
  /// and c2 Mooney-Rivlin's (0 for the other models).
  MaterialModel model = MaterialModel::svk;
  double young = 0, poisson = 0, density = 0, c1 = 0, c2 = 0;
  MaterialConstants material() const { return {model, young, poisson, c1, c2}; }
  std::array<double, 3> velocity{}, angular_velocity{};
  mesh::BodyMesh mesh;  ///< the body's own mesh (local node numbers), for its named surfaces
  /// A rigid surface body (no tets): its nodes are not unknowns; they live in Model::rigid_X
  /// from rigid_begin on, fixed in space (docs/THEORY.md §1.3, §2.1).
  bool rigid = false;
  int rigid_begin = 0;
  /// Reference geometry over all the body's tets (body_geometry; on every rank once
  /// fem::distribute has run): the centre of mass (the consistent mass's, which the moved mass
  /// of docs/THEORY.md §6.8 keeps), the median longest tet edge and the largest distance of a
  /// node from the nodes' centroid.
  std::array<double, 3> centre{};
  double median_edge = 0, radius = 0;
};

/// docs/THEORY.md §6.8: the velocity of each massless node as an affine combination of massive
/// nodes of its body, v_c = sum_j w_cj v_j with sum_j w_cj = 1 and sum_j w_cj X_j = X_c (so that
/// every affine field, a rigid motion among them, is reproduced), in CSR form.
struct MasslessFit {
  std::vector<int> node;       ///< the massless nodes, ascending
  std::vector<int> start;      ///< node k's supports: support[start[k] .. start[k + 1])
  std::vector<int> support;    ///< massive nodes
  std::vector<double> weight;  ///< w_cj, one per support
  /// the index of node n in `node`, or -1 when n is not massless
  int find(int n) const;
};

struct Model {
  /// The global ids of the nodes held here, ascending; empty while every node is held, node n
  /// at n (before fem::distribute, or a model built on every rank). The per-node arrays X,
  /// fixed and massless follow this order.
  std::vector<int> node_ids;
  int global_nodes = 0;          ///< the nodes of all deformable bodies (once node_ids is set)
  std::vector<double> X;         ///< reference coordinates, 3 per held node
  std::vector<int> tets;         ///< 4 global node ids per held tet
  std::vector<int> body_of_tet;  ///< body index per held tet
  /// The global id of each held tet. Empty while the model holds every tet, tet e being id e
  /// (rank 0 before fem::distribute, or a model built on every rank). After fem::distribute:
  /// this rank's own tets (the first owned_tets), then its ghosts (the other ranks' tets that
  /// touch a node it owns, and every tet with a massless node), each in ascending id.
  std::vector<long long> tet_gid;
  int owned_tets = 0;         ///< held tets this rank owns (all held tets before distribute)
  long long global_tets = 0;  ///< the tets of all bodies
  /// FNV-1a of the bytes of X, the global tets, rigid_X and fixed, all global (the model's
  /// identity for checkpoints; computed where every tet is held)
  std::uint64_t mesh_fnv = 0;
  std::vector<Body> bodies;
  std::vector<char> fixed;  ///< per held node: displacement prescribed to zero
  /// per held node (or empty): its mass is moved onto massive nodes of its body
  /// (docs/THEORY.md §6.8; the slave surfaces of pairs with `massless slave = true`)
  std::vector<char> massless;
  MasslessFit massless_fit;     ///< the massless nodes' affine fits (fit_massless_nodes)
  std::vector<double> rigid_X;  ///< nodes of the rigid surface bodies, 3 each
  std::array<double, 3> gravity{};
  kernels::Integrator integrator = kernels::Integrator::energy_momentum;
  Scatter scatter = resolve_scatter(ScatterChoice::automatic);  ///< Solver/Assembly/scatter

  /// The global node count (of the deformable bodies; rigid nodes are numbered after them).
  int num_nodes() const { return node_ids.empty() ? static_cast<int>(X.size() / 3) : global_nodes; }
  int held_nodes() const { return static_cast<int>(X.size() / 3); }
  bool holds_all_nodes() const { return node_ids.empty(); }
  /// The index of global node n in the per-node arrays, or -1 when it is not held here.
  int local_node(int n) const;
  /// The index of global node n in the per-node arrays; throws Error when it is not held.
  int held_node(int n) const;
  /// The global id of held node l.
  int node_id(int l) const { return node_ids.empty() ? l : node_ids[l]; }
  /// The reference coordinates of global node n (held here).
  const double* x(int n) const { return &X[3 * static_cast<std::size_t>(held_node(n))]; }
  bool is_fixed(int n) const { return fixed[held_node(n)] != 0; }
  bool is_massless(int n) const { return !massless.empty() && massless[held_node(n)] != 0; }
  int num_tets() const { return static_cast<int>(tets.size() / 4); }  ///< held tets
  /// The global id of held tet e.
  long long tet_id(int e) const { return tet_gid.empty() ? e : tet_gid[e]; }
  /// True when every tet is held here, at its global id.
  bool holds_all_tets() const { return tet_gid.empty() && num_tets() == global_tets; }
};

/// FNV-1a's offset basis and the bytes of v folded into h.
inline constexpr std::uint64_t fnv_basis = 14695981039346656037ull;
template <class T>
void fnv_into(std::uint64_t& h, const std::vector<T>& v) {
  const auto* p = reinterpret_cast<const unsigned char*>(v.data());
  for (std::size_t i = 0; i < v.size() * sizeof(T); ++i) h = (h ^ p[i]) * 1099511628211ull;
}

/// Assembles the model from the validated parameters and the bodies' meshes (in the order of
/// the `Bodies` sublists). `file` names the input in error messages. Meshes whose tets were
/// dropped (mesh::drop_tets: the ranks other than 0) give a model without tets; where the tets
/// are given the bodies' geometry and mesh_fnv are computed. The meshes' tets are dropped.
Model build_model(const Teuchos::ParameterList& params, std::vector<mesh::BodyMesh> meshes,
                  const std::string& file);

/// The initial velocity of global node n (held here): v + omega x (X - X_c), X_c its body's
/// centre of mass (docs/THEORY.md §1.3 consistent mass: the volume-weighted centroid of its
/// tets).
std::array<double, 3> initial_velocity(const Model& m, int n);
/// The initial velocity of every node (3 each) of a model holding every node.
std::vector<double> initial_velocity(const Model& m);

/// Keeps of the per-node arrays (X, fixed, massless) only the global nodes `held` (ascending,
/// with every node the held tets use): m.node_ids becomes `held`.
void keep_nodes(Model& m, std::vector<int> held);

/// Centre of mass of body b in the reference configuration (Body::centre).
inline std::array<double, 3> centre_of_mass(const Model& m, int b) {
  return m.bodies[b].centre;
}
/// Body b's Body::centre, median_edge and radius from its tets (a model holding all tets).
void body_geometry(Model& m, int b);
/// docs/THEORY.md §6.8: bit a set when node a of tet e is massless (0 without massless nodes).
int massless_mask(const Model& m, int e);

/// docs/THEORY.md §6.8: fills m.massless_fit from m.massless. Returns -1, or a massless node
/// whose body has no massive nodes around it that span 3D (no affine fit exists).
int fit_massless_nodes(Model& m);

/// docs/THEORY.md §6.8: the element's M'_e = T_e^T M_e T_e on its supports (`nodes`, ascending
/// global ids; `M` row-major, nodes.size() squared) for an element with massless nodes.
void moved_element_mass(const Model& m, int e, std::vector<int>& nodes, std::vector<double>& M);

/// The row sums of the mass matrix per global node, M 1 (one component; docs/THEORY.md §1.3 and,
/// with massless nodes, §6.8): sum_n (row sum)_n V_n is the linear momentum of a field V. From
/// this rank's own tets: on a distributed model, the sum over the ranks is M 1. A vector over
/// every global node: for tests and checks, not for the solver.
std::vector<double> mass_row_sums(const Model& m);

}  // namespace emc::fem
