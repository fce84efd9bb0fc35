// Reading a Gmsh .msh file (format 4.1) through Gmsh's API: the tets of one physical volume
// (or all of them) and every physical surface, as named outward-oriented triangles.
#include <gmsh.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

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
    if (tets.element_tags.empty()) {
      throw InputError(file_where + ": no 4-node tetrahedra" +
                       (volume.empty() ? std::string() : " in physical volume '" + volume + "'") +
                       "; generate a 3D mesh (gmsh -3)");
    }
    std::vector<std::size_t> used_tags;
    m = detail::body_from_gmsh(tets, used_tags);
    check_tets(m, file_where, tets.element_tags);  // a user mesh is never silently fixed
    read_surfaces(m, used_tags);
  });
  return m;
}

}  // namespace emc::mesh
