#pragma once
// The mesh of one body: P1 tetrahedra, node coordinates and named surfaces. Plain arrays, no
// Trilinos. Rank 0 builds or reads every mesh; the other ranks get the nodes and the surfaces
// but not the tetrahedra (see drop_tets), which the fem module partitions and hands out.
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

  /// The number of tetrahedra when they are not held here (drop_tets), else -1.
  int dropped_tets = -1;
  /// boundary_triangles of the tetrahedra, kept when they are dropped (empty until then).
  std::vector<std::array<int, 3>> boundary;

  int num_nodes() const { return static_cast<int>(X.size() / 3); }
  /// The tetrahedra held here (0 once dropped).
  int num_tets() const { return static_cast<int>(tets.size() / 4); }
  /// The tetrahedra of the body, held here or not.
  int body_tets() const { return dropped_tets >= 0 ? dropped_tets : num_tets(); }
};

/// True for a rigid surface body: a mesh without tetrahedra (nodes and triangles only).
inline bool is_rigid(const BodyMesh& m) {
  return m.body_tets() == 0;
}

/// Frees the tetrahedra, keeping their count and boundary triangles (the surfaces contact and
/// boundary conditions use). Nothing to do for a rigid surface or a mesh dropped already.
void drop_tets(BodyMesh& m);

/// Signed reference volume of tet e (docs/THEORY.md §1.1: V_e > 0 for a valid element).
double tet_volume(const BodyMesh& m, int e);

/// A tetrahedron's volume must exceed this fraction of the mesh's median volume.
constexpr double kMinVolumeRatio = 1e-12;
/// A tetrahedron's shape quality (its volume over that of the regular tetrahedron on its
/// longest edge: about its thickness over that edge when flat) must reach this: the Newton
/// matrix's condition grows as 1/quality^2, and beyond 1e12 no solve reaches its tolerance (a
/// ball squashed to 1e-9 of its height fails every step; Gmsh's meshes stay above 1e-3).
constexpr double kMinShapeQuality = 1e-6;
/// Node coordinates must be at most this in magnitude: a tet's volume, a body's mass and its
/// moments of inertia (cubes and squares of coordinates times the density) then stay finite.
constexpr double kMaxCoordinate = 1e30;
/// A node of a tet mesh may lie at most this many median longest edges of its tets from the
/// mesh's median node position (per coordinate): far beyond any graded mesh, but a stray node
/// (or one in other units) at 1e20 is named instead of the element it makes huge.
constexpr double kMaxNodeDistance = 1e9;

/// Throws InputError naming `where` and the first element (1-based id, as in the .msh file or
/// the generator's numbering) whose volume is negative (inverted), not finite, or at most
/// kMinVolumeRatio of the median element volume (degenerate; the median, not the mean, so
/// that one huge element does not make the others look degenerate), then the first whose
/// shape quality is below kMinShapeQuality (flat). A mesh without tets (a rigid surface) has
/// nothing to check.
void check_tets(const BodyMesh& m, const std::string& where);

/// As above, but naming tet e by element_ids[e] (e.g. its element tag in the .msh file) when
/// `element_ids` is not empty.
void check_tets(const BodyMesh& m, const std::string& where,
                const std::vector<std::size_t>& element_ids);

/// Throws InputError naming `where` and the first node (node_ids[n], e.g. its tag in the .msh
/// file, or n + 1 if `node_ids` is empty) with a coordinate beyond kMaxCoordinate in magnitude,
/// or, in a tet mesh, farther than kMaxNodeDistance median longest edges from the median node
/// position.
void check_nodes(const BodyMesh& m, const std::string& where,
                 const std::vector<std::size_t>& node_ids);

/// Throws InputError naming `where` and both element ids (as check_tets) if two tets have the
/// same 4 nodes (in any order), or lie on the same 4 points through different nodes at exactly
/// the same coordinates (a second copy of the mesh in the same file). Tets that merely overlap
/// are not looked for.
void check_distinct_tets(const BodyMesh& m, const std::string& where,
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
