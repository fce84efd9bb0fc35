// Reading a Gmsh .msh file (format 4.1, ASCII or binary) with our own validating parser
// (msh_parser.hpp; Gmsh's reader crashes on malformed files): the tets of one physical volume
// (or all of them) and every physical surface, as named outward-oriented triangles; or, for a
// file with triangles and no tets, a rigid surface (triangles oriented as in the file).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "emcontact/error.hpp"
#include "emcontact/mesh/generate.hpp"
#include "src/mesh/internal.hpp"
#include "src/mesh/msh_parser.hpp"

namespace emc::mesh {
namespace {

using Tri = std::array<int, 3>;
using msh::MshData;

constexpr int kTriangle = 2;     ///< Gmsh's 3-node triangle
constexpr int kTetrahedron = 4;  ///< Gmsh's 4-node tetrahedron

/// The content of `file`; refuses a missing file or one that is not a regular file.
std::string read_file(const std::string& file, const std::string& where) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw InputError(where + ": mesh file '" + file + "' does not exist or is not a regular file");
  }
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in) throw InputError(where + ": cannot read the mesh file '" + file + "'");
  return text.str();
}

/// Name of a physical group; unnamed groups are called by their tag.
std::string physical_name(const MshData& d, int dim, int tag) {
  const auto it = d.physical_names.find({dim, tag});
  return it == d.physical_names.end() || it->second.empty() ? std::to_string(tag) : it->second;
}

/// The physical groups of dimension `dim` that hold an entity, sorted by tag.
std::vector<int> physical_groups(const MshData& d, int dim) {
  std::set<int> groups;
  for (const auto& e : d.entity_physicals) {
    if (e.first.first == dim) groups.insert(e.second.begin(), e.second.end());
  }
  return std::vector<int>(groups.begin(), groups.end());
}

/// The sorted entities of dimension `dim` in physical group `group`, or all of them if
/// `group` is 0.
std::vector<int> group_entities(const MshData& d, int dim, int group) {
  std::vector<int> entities;
  for (const auto& e : d.entity_physicals) {
    const std::vector<int>& p = e.second;
    if (e.first.first != dim) continue;
    if (group == 0 || std::find(p.begin(), p.end(), group) != p.end()) {
      entities.push_back(e.first.second);
    }
  }
  return entities;  // sorted: the map is
}

/// The sorted entities of the physical volume `volume`; throws listing the available names.
std::vector<int> volume_entities(const MshData& d, const std::string& volume,
                                 const std::string& where) {
  std::vector<int> entities;
  std::string names;
  for (int group : physical_groups(d, 3)) {
    const std::string name = physical_name(d, 3, group);
    names += (names.empty() ? "'" : ", '") + name + "'";
    if (name != volume) continue;
    const std::vector<int> tags = group_entities(d, 3, group);
    entities.insert(entities.end(), tags.begin(), tags.end());
  }
  if (entities.empty()) {
    throw InputError(where + ": no physical volume '" + volume + "' (parameter 'volume'); " +
                     (names.empty() ? "the file defines none, leave 'volume' empty to use all "
                                      "tetrahedra"
                                    : "the file defines " + names));
  }
  std::sort(entities.begin(), entities.end());
  entities.erase(std::unique(entities.begin(), entities.end()), entities.end());
  return entities;
}

/// The element tags and node tags of the elements of `type` in the entities of dimension `dim`
/// given, entity by entity, in file order within an entity.
detail::GmshTets elements_of(const MshData& d, int dim, int type, const std::vector<int>& entities) {
  detail::GmshTets out;
  for (int entity : entities) {
    for (const msh::ElementBlock& b : d.blocks) {
      if (b.dim != dim || b.entity != entity || b.type != type) continue;
      out.element_tags.insert(out.element_tags.end(), b.element_tags.begin(), b.element_tags.end());
      out.node_tags.insert(out.node_tags.end(), b.node_tags.begin(), b.node_tags.end());
    }
  }
  return out;
}

/// The first non-empty block of dimension `dim` in one of `entities` whose type is not `type`
/// (smallest entity first), or nullptr.
const msh::ElementBlock* other_type(const MshData& d, int dim, int type,
                                    const std::vector<int>& entities) {
  for (int entity : entities) {
    for (const msh::ElementBlock& b : d.blocks) {
      if (b.dim == dim && b.entity == entity && b.type != type && b.count > 0) return &b;
    }
  }
  return nullptr;
}

/// The 4-node tets of the given volume entities (all if `entities` is empty), entity by
/// entity. Refuses any other 3D element type in those entities.
detail::GmshTets volume_tets(const MshData& d, std::vector<int> entities,
                             const std::string& where) {
  if (entities.empty()) entities = group_entities(d, 3, 0);
  if (const msh::ElementBlock* b = other_type(d, 3, kTetrahedron, entities)) {
    throw InputError(where + ": volume " + std::to_string(b->entity) + " contains '" +
                     msh::element_type(b->type)->name +
                     "' elements; only 4-node tetrahedra (Gmsh element type 4) are supported");
  }
  return elements_of(d, 3, kTetrahedron, entities);
}

/// The 3-node triangles of physical surface `group` whose nodes all belong to the body.
std::vector<Tri> physical_triangles(const MshData& d, int group,
                                    const std::vector<std::size_t>& used_tags) {
  const detail::GmshTets t = elements_of(d, 2, kTriangle, group_entities(d, 2, group));
  std::vector<Tri> tris;
  for (std::size_t i = 0; i + 2 < t.node_tags.size(); i += 3) {
    Tri tri{};
    for (int k = 0; k < 3; ++k) tri[k] = detail::local_node(used_tags, t.node_tags[i + k]);
    if (tri[0] >= 0 && tri[1] >= 0 && tri[2] >= 0) tris.push_back(tri);
  }
  return tris;
}

/// Every physical surface's triangles on the body (re-oriented outward if `orient`), by
/// name; a surface with no triangle on the body is skipped. Sorted (deterministic).
void read_surfaces(const MshData& d, BodyMesh& m, const std::vector<std::size_t>& used_tags,
                   bool orient) {
  for (int group : physical_groups(d, 2)) {
    std::vector<Tri> tris = physical_triangles(d, group, used_tags);
    if (orient) tris = detail::orient_on_body(m, tris);
    if (tris.empty()) continue;
    std::vector<Tri>& named = m.surfaces[physical_name(d, 2, group)];
    named.insert(named.end(), tris.begin(), tris.end());
  }
  for (auto& s : m.surfaces) detail::sort_triangles(s.second);
}

/// Element tags and node tags (3 per triangle) of every 3-node triangle of the file; refuses
/// other 2D element types (quadrangles, curved triangles).
detail::GmshTets all_triangles(const MshData& d, const std::string& where) {
  const std::vector<int> surfaces = group_entities(d, 2, 0);
  const msh::ElementBlock* other = nullptr;
  for (const msh::ElementBlock& b : d.blocks) {
    if (b.dim == 2 && b.type != kTriangle && b.count > 0 && (!other || b.type < other->type)) {
      other = &b;
    }
  }
  if (other) {
    throw InputError(where + ": the surface mesh contains '" +
                     msh::element_type(other->type)->name +
                     "' elements; a rigid surface supports only 3-node triangles (Gmsh element "
                     "type 2)");
  }
  return elements_of(d, 2, kTriangle, surfaces);
}

/// Refuses a triangle of zero (or below 1e-12 of the mean) area: its normal is undefined.
void check_triangles(const BodyMesh& m, const std::vector<Tri>& tris,
                     const std::vector<std::size_t>& element_tags, const std::string& where) {
  std::vector<double> areas(tris.size());
  double mean = 0.0;
  for (std::size_t e = 0; e < tris.size(); ++e) {
    double a[3], b[3];
    for (int d = 0; d < 3; ++d) {
      a[d] = m.X[3 * tris[e][1] + d] - m.X[3 * tris[e][0] + d];
      b[d] = m.X[3 * tris[e][2] + d] - m.X[3 * tris[e][0] + d];
    }
    const double n[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                         a[0] * b[1] - a[1] * b[0]};
    areas[e] = 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    mean += areas[e] / static_cast<double>(tris.size());
  }
  for (std::size_t e = 0; e < tris.size(); ++e) {
    if (areas[e] > 1e-12 * mean) continue;  // also catches NaN
    std::ostringstream msg;
    msg << where << ": element " << element_tags[e] << " is a degenerate triangle (area "
        << areas[e] << ", mean " << mean
        << "); every triangle of a rigid surface must have an area above 1e-12 of the mean";
    throw InputError(msg.str());
  }
}

/// The rigid surface of a file without tets: the nodes of its triangles, every physical
/// surface by name and `surface` (all triangles), all as oriented in the file. Empty (no
/// nodes) if the file has no triangles.
BodyMesh rigid_surface(const MshData& d, const std::string& where) {
  const detail::GmshTets t = all_triangles(d, where);
  BodyMesh m;
  if (t.element_tags.empty()) return m;
  std::vector<std::size_t> used_tags;
  m.X = detail::node_coordinates(t.node_tags, d.node_tags, d.coords, used_tags);
  std::vector<Tri> all(t.element_tags.size());
  for (std::size_t e = 0; e < all.size(); ++e) {
    for (int k = 0; k < 3; ++k) all[e][k] = detail::local_node(used_tags, t.node_tags[3 * e + k]);
  }
  check_triangles(m, all, t.element_tags, where);
  read_surfaces(d, m, used_tags, false);
  m.surfaces["surface"] = std::move(all);  // always all triangles (replaces a group "surface")
  detail::sort_triangles(m.surfaces["surface"]);
  return m;
}

/// The mesh of parsed file `d` (see read_msh).
BodyMesh mesh_of(const MshData& d, const std::string& volume, const std::string& where) {
  const std::vector<int> entities =
      volume.empty() ? std::vector<int>() : volume_entities(d, volume, where);
  const detail::GmshTets tets = volume_tets(d, entities, where);
  if (tets.element_tags.empty() && volume.empty()) {
    BodyMesh m = rigid_surface(d, where);
    if (m.num_nodes() > 0) return m;
    throw InputError(where +
                     ": no 4-node tetrahedra and no triangles; generate a 3D mesh (gmsh -3) "
                     "for a deformable body, or a surface mesh of triangles (gmsh -2) for a "
                     "rigid surface");
  }
  if (tets.element_tags.empty()) {
    throw InputError(where + ": no 4-node tetrahedra in physical volume '" + volume +
                     "'; generate a 3D mesh (gmsh -3)");
  }
  std::vector<std::size_t> used_tags;
  BodyMesh m = detail::body_from_tags(tets, d.node_tags, d.coords, used_tags);
  check_tets(m, where, tets.element_tags);  // a user mesh is never silently fixed
  read_surfaces(d, m, used_tags, true);
  return m;
}

}  // namespace

BodyMesh read_msh(const std::string& file, const std::string& volume, const std::string& where) {
  const std::string text = read_file(file, where);
  const std::string file_where = where + ": '" + file + "'";
  return mesh_of(msh::parse_msh(text, file_where), volume, file_where);
}

}  // namespace emc::mesh
