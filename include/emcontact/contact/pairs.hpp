#pragma once
// Contact pairs (ALGORITHM.md §2): the slave nodes of a deformable body's surface against the
// 3-node facets of a master surface (a deformable body's boundary or a rigid surface body).
// Node numbering of the contact geometry: deformable nodes keep their global id n in
// [0, num_nodes); rigid nodes are num_nodes + k, k indexing Model::rigid_X.
#include <Teuchos_ParameterList.hpp>

#include <array>
#include <string>
#include <vector>

#include "emcontact/fem/model.hpp"

namespace emc::contact {

enum class Kind { full_stick, frictionless };

struct Pair {
  std::string name;
  Kind kind = Kind::full_stick;
  double dmax = 0;                         ///< activation only for -dmax < g_N < 0 (§6.3)
  std::vector<int> slaves;                 ///< global node ids, sorted
  std::vector<std::array<int, 3>> facets;  ///< geometry node ids, outward from the master
  int master_body = -1;
};

/// Builds the pairs of the `Contact` section (empty if there is none). Throws InputError
/// naming `file` and the parameter for unknown bodies/surfaces or a rigid slave.
std::vector<Pair> build_pairs(const Teuchos::ParameterList& params, const fem::Model& model,
                              const std::string& file);

/// Current positions of every geometry node: X + u for deformable nodes (u: all 3 N
/// displacements, replicated), rigid_X for the rigid ones.
std::vector<double> positions(const fem::Model& model, const std::vector<double>& u);

}  // namespace emc::contact
