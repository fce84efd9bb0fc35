#pragma once
// Private helpers of the mesh module (not part of its interface): the Gmsh session guard, the
// conversion of Gmsh's tets into a BodyMesh and the outward orientation of surface triangles.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "emcontact/mesh/body_mesh.hpp"

namespace emc::mesh::detail {

/// RAII guard around one Gmsh session: initializes Gmsh (quiet, single-threaded, deterministic
/// options, messages captured by Gmsh's logger) and finalizes it on destruction, which also
/// clears the "busy" lock Gmsh leaves behind after a failed read. Nested guards share the
/// outermost session. Not thread-safe (neither is Gmsh).
class GmshSession {
 public:
  GmshSession();
  ~GmshSession();
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

  /// The last error Gmsh logged (empty if none).
  static std::string last_error();
};

/// Runs `f` (Gmsh calls) and turns any exception Gmsh throws (std::string in Gmsh 4.8, an
/// std::exception in later versions) into emc::InputError "<where>: <what>: <gmsh message>".
template <class F>
void with_gmsh(const std::string& where, const std::string& what, F&& f);

/// Rethrows the exception in flight (inside a catch block) as emc::InputError.
[[noreturn]] void rethrow_gmsh_error(const std::string& where, const std::string& what);

template <class F>
void with_gmsh(const std::string& where, const std::string& what, F&& f) {
  try {
    f();
  } catch (...) {
    rethrow_gmsh_error(where, what);
  }
}

/// Tets of the current Gmsh model as Gmsh node tags (4 per tet) and element tags.
struct GmshTets {
  std::vector<std::size_t> element_tags;
  std::vector<std::size_t> node_tags;
};

/// The 4-node tets of the given 3D entities (all volume entities if `entities` is empty), in
/// entity order. Throws InputError if those entities hold any other 3D element type.
GmshTets gmsh_tets(const std::vector<int>& entities, const std::string& where);

/// A BodyMesh with the nodes used by `t` (numbered 0..n-1 by increasing Gmsh tag) and its
/// tets, in Gmsh's order and orientation. `used_tags` receives the sorted Gmsh tags of the
/// kept nodes (local index i <-> used_tags[i]).
BodyMesh body_from_gmsh(const GmshTets& t, std::vector<std::size_t>& used_tags);

/// As body_from_gmsh, without Gmsh: the coordinates come from the node table `node_tags`
/// (any order) and `coords` (3 per node), which must hold every node of `t`.
BodyMesh body_from_tags(const GmshTets& t, const std::vector<std::size_t>& node_tags,
                        const std::vector<double>& coords, std::vector<std::size_t>& used_tags);

/// The coordinates (3 per node) of the nodes used by the node tags `element_nodes`, numbered
/// 0..n-1 by increasing tag, taken from the node table `node_tags` / `coords` (3 per node);
/// `used_tags` receives those sorted, unique tags.
std::vector<double> node_coordinates(const std::vector<std::size_t>& element_nodes,
                                     const std::vector<std::size_t>& node_tags,
                                     const std::vector<double>& coords,
                                     std::vector<std::size_t>& used_tags);

/// Local index of Gmsh node `tag` in the sorted `used_tags`, or -1 if it is not used.
int local_node(const std::vector<std::size_t>& used_tags, std::size_t tag);

/// Orients triangles (node indices of `m`) outward: a triangle that is a face of exactly one
/// tet gets its normal pointing away from that tet's fourth node; a face of two tets (an
/// internal surface) keeps its given orientation; a triangle that is no face of `m` is dropped.
std::vector<std::array<int, 3>> orient_on_body(const BodyMesh& m,
                                               const std::vector<std::array<int, 3>>& tris);

/// A rigid surface (no tets): the n1 x n2 grid of parallelograms spanned by `a` / n1 and
/// `b` / n2 from `origin` (node (i, j) at origin + i/n1 a + j/n2 b), each cut into two
/// triangles whose normal (q-p)x(r-p) points along a x b; all triangles in surface `surface`.
BodyMesh triangle_grid(const std::array<double, 3>& origin, const std::array<double, 3>& a,
                       const std::array<double, 3>& b, int n1, int n2);

/// Rotates `t` (keeping its orientation) so that its smallest node comes first.
std::array<int, 3> canonical_rotation(const std::array<int, 3>& t);

/// Sorts triangles by their canonical rotation (deterministic output).
void sort_triangles(std::vector<std::array<int, 3>>& tris);

}  // namespace emc::mesh::detail
