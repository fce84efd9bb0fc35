// Reading a Gmsh .msh file (format 4.1) through Gmsh's API: the tets of one physical volume
// (or all of them) and every physical surface, as named outward-oriented triangles; or, for a
// file with triangles and no tets, a rigid surface (triangles oriented as in the file).
#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "emcontact/error.hpp"
#include "emcontact/mesh/generate.hpp"
#include "src/mesh/internal.hpp"

namespace emc::mesh {
namespace {

using Tri = std::array<int, 3>;

/// Refuses a missing file or one that is not a .msh file (Gmsh would also open CAD files and
/// .geo scripts, or silently ignore a missing file).
void check_msh_file(const std::string& file, const std::string& where) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw InputError(where + ": mesh file '" + file + "' does not exist or is not a regular file");
  }
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line) && line.find_first_not_of(" \t\r") == std::string::npos) {
  }
  if (line.rfind("$MeshFormat", 0) != 0) {
    throw InputError(where + ": '" + file +
                     "' is not a Gmsh .msh file (it must start with $MeshFormat; write format "
                     "4.1, e.g. gmsh -3 -format msh41 body.geo)");
  }
}

/// Name of a physical group; unnamed groups are called by their tag.
std::string physical_name(int dim, int tag) {
  std::string name;
  gmsh::model::getPhysicalName(dim, tag, name);
  return name.empty() ? std::to_string(tag) : name;
}

/// The sorted entities of the physical volume `volume`; throws listing the available names.
std::vector<int> volume_entities(const std::string& volume, const std::string& where) {
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, 3);
  std::vector<int> entities;
  std::string names;
  for (const auto& g : groups) {
    const std::string name = physical_name(3, g.second);
    names += (names.empty() ? "'" : ", '") + name + "'";
    if (name != volume) continue;
    std::vector<int> tags;
    gmsh::model::getEntitiesForPhysicalGroup(3, g.second, tags);
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

/// The 3-node triangles of physical surface `tag` whose nodes all belong to the body.
std::vector<Tri> physical_triangles(int tag, const std::vector<std::size_t>& used_tags) {
  std::vector<int> entities;
  gmsh::model::getEntitiesForPhysicalGroup(2, tag, entities);
  std::vector<Tri> tris;
  for (int entity : entities) {
    std::vector<std::size_t> element_tags, node_tags;
    gmsh::model::mesh::getElementsByType(2, element_tags, node_tags, entity);
    for (std::size_t i = 0; i + 2 < node_tags.size(); i += 3) {
      Tri t{};
      for (int k = 0; k < 3; ++k) t[k] = detail::local_node(used_tags, node_tags[i + k]);
      if (t[0] >= 0 && t[1] >= 0 && t[2] >= 0) tris.push_back(t);
    }
  }
  return tris;
}

/// Every physical surface with triangles on the body, oriented outward, by name. Surfaces of
/// other volumes of the same file (no triangle on this body) are skipped.
void read_surfaces(BodyMesh& m, const std::vector<std::size_t>& used_tags) {
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, 2);
  for (const auto& g : groups) {
    const std::vector<Tri> tris =
        detail::orient_on_body(m, physical_triangles(g.second, used_tags));
    if (tris.empty()) continue;
    std::vector<Tri>& named = m.surfaces[physical_name(2, g.second)];
    named.insert(named.end(), tris.begin(), tris.end());
  }
  for (auto& s : m.surfaces) detail::sort_triangles(s.second);
}

/// Gmsh element tags and node tags (3 per triangle) of every 3-node triangle of the model;
/// refuses other 2D element types (quadrangles, curved triangles).
detail::GmshTets all_triangles(const std::string& where) {
  std::vector<int> types;
  gmsh::model::mesh::getElementTypes(types, 2, -1);
  for (int type : types) {
    if (type == 2) continue;
    std::string name;
    int dim, order, num_nodes, num_primary;
    std::vector<double> local_coords;
    gmsh::model::mesh::getElementProperties(type, name, dim, order, num_nodes, local_coords,
                                            num_primary);
    throw InputError(where + ": the surface mesh contains '" + name +
                     "' elements; a rigid surface supports only 3-node triangles (Gmsh element "
                     "type 2)");
  }
  detail::GmshTets t;  // triangles here, not tets
  gmsh::model::mesh::getElementsByType(2, t.element_tags, t.node_tags, -1);
  return t;
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
BodyMesh rigid_surface(const std::string& where) {
  const detail::GmshTets t = all_triangles(where);
  BodyMesh m;
  if (t.element_tags.empty()) return m;
  std::vector<std::size_t> used_tags;
  m.X = detail::gmsh_node_coordinates(t.node_tags, used_tags);
  std::vector<Tri> all(t.element_tags.size());
  for (std::size_t e = 0; e < all.size(); ++e) {
    for (int k = 0; k < 3; ++k) all[e][k] = detail::local_node(used_tags, t.node_tags[3 * e + k]);
  }
  check_triangles(m, all, t.element_tags, where);
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, 2);
  for (const auto& g : groups) {
    const std::vector<Tri> tris = physical_triangles(g.second, used_tags);
    if (tris.empty()) continue;
    std::vector<Tri>& named = m.surfaces[physical_name(2, g.second)];
    named.insert(named.end(), tris.begin(), tris.end());
  }
  m.surfaces["surface"] = std::move(all);  // always all triangles (replaces a group "surface")
  for (auto& s : m.surfaces) detail::sort_triangles(s.second);
  return m;
}

}  // namespace

BodyMesh read_msh(const std::string& file, const std::string& volume, const std::string& where) {
  check_msh_file(file, where);
  const std::string file_where = where + ": '" + file + "'";
  detail::GmshSession session;
  BodyMesh m;
  detail::with_gmsh(file_where, "Gmsh cannot read the file", [&] {
    gmsh::open(file);
    const std::vector<int> entities =
        volume.empty() ? std::vector<int>() : volume_entities(volume, file_where);
    const detail::GmshTets tets = detail::gmsh_tets(entities, file_where);
    if (tets.element_tags.empty() && volume.empty()) {
      m = rigid_surface(file_where);
      if (m.num_nodes() > 0) return;
      throw InputError(file_where +
                       ": no 4-node tetrahedra and no triangles; generate a 3D mesh (gmsh -3) "
                       "for a deformable body, or a surface mesh of triangles (gmsh -2) for a "
                       "rigid surface");
    }
    if (tets.element_tags.empty()) {
      throw InputError(file_where + ": no 4-node tetrahedra in physical volume '" + volume +
                       "'; generate a 3D mesh (gmsh -3)");
    }
    std::vector<std::size_t> used_tags;
    m = detail::body_from_gmsh(tets, used_tags);
    check_tets(m, file_where, tets.element_tags);  // a user mesh is never silently fixed
    read_surfaces(m, used_tags);
  });
  return m;
}

}  // namespace emc::mesh
