#pragma once
// The mesh of one body: P1 tetrahedra, node coordinates and named surfaces. Plain arrays, no
// Trilinos: every rank holds the whole (replicated) mesh; the fem module partitions elements.
// A mesh without tetrahedra is a rigid surface (see is_rigid): its nodes and its triangles.
#include <array>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace emc::mesh {

struct BodyMesh {
  std::vector<double> X;  ///< reference coordinates, 3 per node
  std::vector<int> tets;  ///< 4 node indices per tet (0-based, this body's nodes); empty: rigid
  /// Named boundary surfaces (Gmsh physical surface names, or the generators' face names),
  /// triangles with outward orientation (node indices of this body). For a rigid surface
  /// (no tets): its triangles as the user or the generator oriented them (the normal
  /// (b-a)x(c-a) points to the side contact happens on), `surface` holding all of them.
  std::map<std::string, std::vector<std::array<int, 3>>> surfaces;

  int num_nodes() const { return static_cast<int>(X.size() / 3); }
  int num_tets() const { return static_cast<int>(tets.size() / 4); }
};

/// True for a rigid surface body: a mesh without tetrahedra (nodes and triangles only).
inline bool is_rigid(const BodyMesh& m) {
  return m.tets.empty();
}

/// Signed reference volume of tet e (docs/THEORY.md §1.1: V_e > 0 for a valid element).
double tet_volume(const BodyMesh& m, int e);

/// Throws InputError naming `where` and the first element (1-based id, as in the .msh file or
/// the generator's numbering) whose volume is negative (inverted) or below 1e-12 of the mean
/// element volume (degenerate). A mesh without tets (a rigid surface) has nothing to check.
void check_tets(const BodyMesh& m, const std::string& where);

/// As above, but naming tet e by element_ids[e] (e.g. its element tag in the .msh file) when
/// `element_ids` is not empty.
void check_tets(const BodyMesh& m, const std::string& where,
                const std::vector<std::size_t>& element_ids);

/// The boundary triangles of the tet mesh (faces that belong to exactly one tet), oriented
/// with the normal pointing out of the body, sorted deterministically. Empty for a rigid
/// surface (no tets): its triangles are in `surfaces`.
std::vector<std::array<int, 3>> boundary_triangles(const BodyMesh& m);

/// The sorted, unique nodes of a named surface; throws InputError naming `where` and the
/// available surface names if it does not exist. The name "boundary" is always available
/// (all boundary nodes; for a rigid surface, all its nodes).
std::vector<int> surface_nodes(const BodyMesh& m, const std::string& name,
                               const std::string& where);

}  // namespace emc::mesh
