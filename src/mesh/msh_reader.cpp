// Reading a Gmsh .msh file (format 4.1, ASCII or binary) with our own validating parser
// (msh_parser.hpp; Gmsh's reader crashes on malformed files): the tets of one physical volume
// (or all of them) and every physical surface, as named outward-oriented triangles; or, for a
// file with triangles and no tets, a rigid surface (triangles oriented as in the file).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "emcontact/error.hpp"
#include "emcontact/input/echo.hpp"
#include "emcontact/mesh/generate.hpp"
#include "emcontact/vec3.hpp"
#include "internal.hpp"
#include "msh_parser.hpp"

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
    throw InputError(where + ": mesh file '" + input::echo(file) +
                     "' does not exist or is not a regular file");
  }
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in) throw InputError(where + ": cannot read the mesh file '" + input::echo(file) + "'");
  return text.str();
}

/// Name of a physical group; unnamed groups are called by their tag.
std::string physical_name(const MshData& d, int dim, int tag) {
  const auto it = d.physical_names.find({dim, tag});
  return it == d.physical_names.end() || it->second.empty() ? std::to_string(tag) : it->second;
}

/// The physical groups of dimension `dim` that hold an entity, sorted by tag.
std::vector<int> physical_groups(const MshData& d, int dim) {
  std::vector<int> groups;
  for (const auto& g : d.group_entities) {
    if (g.first.first == dim) groups.push_back(g.first.second);
  }
  return groups;
}

/// The sorted entities of dimension `dim` in physical group `group`, or all of them if
/// `group` is 0.
std::vector<int> group_entities(const MshData& d, int dim, int group) {
  if (group != 0) {
    const auto it = d.group_entities.find({dim, group});
    return it == d.group_entities.end() ? std::vector<int>() : it->second;
  }
  std::vector<int> entities;
  for (const auto& e : d.entity_physicals) {
    if (e.first.first == dim) entities.push_back(e.first.second);  // sorted: the map is
  }
  return entities;
}

/// The element blocks of entity `entity` of dimension `dim`, in file order.
std::vector<const msh::ElementBlock*> entity_blocks(const MshData& d, int dim, int entity) {
  std::vector<const msh::ElementBlock*> out;
  const auto it = d.entity_blocks.find({dim, entity});
  if (it == d.entity_blocks.end()) return out;
  for (std::size_t b : it->second) out.push_back(&d.blocks[b]);
  return out;
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
detail::GmshTets elements_of(const MshData& d, int dim, int type,
                             const std::vector<int>& entities) {
  detail::GmshTets out;
  for (int entity : entities) {
    for (const msh::ElementBlock* b : entity_blocks(d, dim, entity)) {
      if (b->type != type) continue;
      out.element_tags.insert(out.element_tags.end(), b->element_tags.begin(),
                              b->element_tags.end());
      out.node_tags.insert(out.node_tags.end(), b->node_tags.begin(), b->node_tags.end());
    }
  }
  return out;
}

/// The first non-empty block of dimension `dim` in one of `entities` whose type is not `type`
/// (smallest entity first), or nullptr.
const msh::ElementBlock* other_type(const MshData& d, int dim, int type,
                                    const std::vector<int>& entities) {
  for (int entity : entities) {
    for (const msh::ElementBlock* b : entity_blocks(d, dim, entity)) {
      if (b->type != type && b->count > 0) return b;
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

/// detail::orient_on_body for each triangle of `tris`, with one face search for all: its
/// outward orientation, itself on an internal face, or {-1, -1, -1} if it is no face of the
/// body. (orient_on_body keeps the order and drops exactly the triangles whose node set is no
/// face, so a dropped triangle never has the node set of the next kept one.)
std::vector<Tri> orient_each(const BodyMesh& m, const std::vector<Tri>& tris) {
  const std::vector<Tri> kept = detail::orient_on_body(m, tris);
  const auto key = [](Tri t) {
    std::sort(t.begin(), t.end());
    return t;
  };
  std::vector<Tri> out(tris.size(), Tri{-1, -1, -1});
  for (std::size_t i = 0, j = 0; i < tris.size() && j < kept.size(); ++i) {
    if (key(tris[i]) == key(kept[j])) out[i] = kept[j++];
  }
  return out;
}

/// The 3-node triangles of every surface entity whose nodes all belong to the body (node
/// indices of `m`), oriented outward on the body if `orient`, by entity tag.
std::map<int, std::vector<Tri>> entity_triangles(const MshData& d, const BodyMesh& m,
                                                 const std::vector<std::size_t>& used_tags,
                                                 bool orient) {
  std::vector<Tri> tris;
  std::vector<int> owners;
  for (int entity : group_entities(d, 2, 0)) {
    const detail::GmshTets t = elements_of(d, 2, kTriangle, {entity});
    for (std::size_t i = 0; i + 2 < t.node_tags.size(); i += 3) {
      Tri tri{};
      for (int k = 0; k < 3; ++k) tri[k] = detail::local_node(used_tags, t.node_tags[i + k]);
      if (tri[0] < 0 || tri[1] < 0 || tri[2] < 0) continue;
      tris.push_back(tri);
      owners.push_back(entity);
    }
  }
  if (orient) tris = orient_each(m, tris);
  std::map<int, std::vector<Tri>> out;
  for (std::size_t i = 0; i < tris.size(); ++i) {
    if (tris[i][0] >= 0) out[owners[i]].push_back(tris[i]);
  }
  return out;
}

/// Refuses physical surfaces that hold, in all, over 16 times the triangles on the body (plus
/// 10^6): entities in very many groups would exhaust the memory.
void check_surface_sizes(const MshData& d, const std::map<int, std::vector<Tri>>& by_entity,
                         const std::string& where) {
  std::size_t on_body = 0, total = 0;
  for (const auto& e : by_entity) on_body += e.second.size();
  for (int group : physical_groups(d, 2)) {
    for (int entity : group_entities(d, 2, group)) {
      const auto it = by_entity.find(entity);
      if (it != by_entity.end()) total += it->second.size();
    }
  }
  if (total <= 16 * on_body + 1000000) return;
  throw InputError(where + ": the physical surfaces hold " + std::to_string(total) +
                   " triangles in all, more than 16 times the " + std::to_string(on_body) +
                   " triangles on the body (plus 10^6); is a surface in that many groups?");
}

/// Every physical surface's triangles on the body (re-oriented outward if `orient`), by
/// name; a surface with no triangle on the body is skipped. Sorted (deterministic).
void read_surfaces(const MshData& d, BodyMesh& m, const std::vector<std::size_t>& used_tags,
                   bool orient, const std::string& where) {
  const std::map<int, std::vector<Tri>> by_entity = entity_triangles(d, m, used_tags, orient);
  check_surface_sizes(d, by_entity, where);
  for (int group : physical_groups(d, 2)) {
    std::vector<Tri> tris;
    for (int entity : group_entities(d, 2, group)) {
      const auto it = by_entity.find(entity);
      if (it != by_entity.end()) tris.insert(tris.end(), it->second.begin(), it->second.end());
    }
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

/// Refuses a triangle of zero (or at most 1e-12 of the median) area: its normal is undefined.
void check_triangles(const BodyMesh& m, const std::vector<Tri>& tris,
                     const std::vector<std::size_t>& element_tags, const std::string& where) {
  std::vector<double> areas(tris.size());
  for (std::size_t e = 0; e < tris.size(); ++e) {
    Vec3 a, b;
    for (int d = 0; d < 3; ++d) {
      a[d] = m.X[3 * tris[e][1] + d] - m.X[3 * tris[e][0] + d];
      b[d] = m.X[3 * tris[e][2] + d] - m.X[3 * tris[e][0] + d];
    }
    areas[e] = 0.5 * norm(cross(a, b));
  }
  std::vector<double> sorted = areas;
  const auto mid = sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2);
  std::nth_element(sorted.begin(), mid, sorted.end());
  const double median = sorted.empty() ? 0.0 : *mid;
  for (std::size_t e = 0; e < tris.size(); ++e) {
    if (areas[e] > 1e-12 * median && std::isfinite(areas[e])) continue;  // also catches NaN
    std::ostringstream msg;
    msg << where << ": element " << element_tags[e] << " is a degenerate triangle (area "
        << areas[e] << ", median " << median
        << "); every triangle of a rigid surface must have a finite area above 1e-12 of the "
           "median";
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
  check_nodes(m, where, used_tags);
  check_triangles(m, all, t.element_tags, where);
  read_surfaces(d, m, used_tags, false, where);
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
  check_nodes(m, where, used_tags);
  check_tets(m, where, tets.element_tags);  // a user mesh is never silently fixed
  check_distinct_tets(m, where, tets.element_tags);
  read_surfaces(d, m, used_tags, true, where);
  return m;
}

}  // namespace

BodyMesh read_msh(const std::string& file, const std::string& volume, const std::string& where) {
  const std::string text = read_file(file, where);
  const std::string file_where = where + ": '" + input::echo(file) + "'";
  return mesh_of(msh::parse_msh(text, file_where), volume, file_where);
}

}  // namespace emc::mesh
