#pragma once
// Contact pairs (docs/THEORY.md §2.1): the slave nodes of a deformable body's surface against the
// 3-node facets of a master surface (a deformable body's boundary or a rigid surface body).
// Node numbering of the contact geometry: deformable nodes keep their global id n in
// [0, num_nodes); rigid nodes are num_nodes + k, k indexing Model::rigid_X.
#include <array>
#include <string>
#include <vector>

#include "emcontact/fem/model.hpp"

namespace emc::contact {

enum class Kind { full_stick, frictionless, coulomb };

struct Pair {
  std::string name;
  Kind kind = Kind::full_stick;
  double mu = 0;                ///< Coulomb friction coefficient (docs/THEORY.md §11)
  double dmax = 0;              ///< activation only for -dmax < g_N < 0 (§6.3)
  bool close_gap = false;       ///< active nodes end every step on the master (docs/THEORY.md §7)
  bool massless_slave = false;  ///< the slave nodes' mass moved inward (docs/THEORY.md §6.8)
  std::vector<int> slaves;      ///< global node ids, sorted
  /// geometry node ids, outward from the master: the master surface's; for a named surface of a
  /// deformable body, the rest of the body's boundary after them (docs/THEORY.md §6.3)
  std::vector<std::array<int, 3>> facets;
  int master_body = -1;
  int slave_body = -1;
  bool rigid_master = false;
  double edge = 0;  ///< mean edge length of the named master facets (reference configuration)
  /// The slave surface's triangles (global node ids) and, per slave node (index k into
  /// `slaves`), the triangles around it: slave_tris[tri_start[k] .. tri_start[k + 1]).
  std::vector<std::array<int, 3>> slave_facets;
  std::vector<int> tri_start, slave_tris;
};

/// One `Contact/<pair>` sublist as read (contact::read_pair_settings; the surfaces not yet
/// found in the model).
struct PairSettings {
  std::string name;  ///< the sublist's name
  std::string type;  ///< `type` as spelled
  Kind kind = Kind::full_stick;
  double mu = 0;           ///< `friction coefficient`
  bool close_gap = false;  ///< `close gap`
  bool massless_slave = false;
  std::string slave, master;  ///< `body` or `body/surface`
  double dmax = 0;            ///< `max penetration` (0: automatic)
};

/// Builds the pairs of the `Contact` section's settings (none if it has none). Throws InputError
/// naming `file` and the parameter for unknown bodies/surfaces or a rigid slave.
std::vector<Pair> build_pairs(const std::vector<PairSettings>& settings, const fem::Model& model,
                              const std::string& file);

/// docs/THEORY.md §6.8: marks the slave nodes of the pairs with `massless slave` in
/// model.massless (left empty when no pair asks for it) and fits each one's velocity over the
/// massive nodes around it (fem::fit_massless_nodes, where the model holds every tet: rank 0;
/// fem::distribute gives the others the fit); throws InputError naming `file` and the pair when
/// a body's massive nodes cannot carry its slave nodes' mass.
void mark_massless_slaves(const std::vector<Pair>& pairs, fem::Model& model,
                          const std::string& file);

/// Current positions of every geometry node: X + u for the deformable nodes the model holds
/// (u: all 3 N displacements, or empty for none; 0 at the nodes not held), rigid_X for the
/// rigid ones. Of global size: for the set-up only.
std::vector<double> positions(const fem::Model& model, const std::vector<double>& u);

/// The outward unit normal of the slave surface at slave node s (global id) in configuration
/// x: the area-weighted mean of its slave triangles' normals (zero if s is not a slave).
void slave_normal(const Pair& p, int s, const std::vector<double>& x, double n[3]);

}  // namespace emc::contact
