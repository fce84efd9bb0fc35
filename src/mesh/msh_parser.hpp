#pragma once
// Private to the mesh module: a strict, validating parser of Gmsh .msh 4.1 files (ASCII and
// little-endian binary, data-size 8). It reads $MeshFormat, $PhysicalNames, $Entities, $Nodes
// and $Elements, skips other sections, and refuses anything malformed with an InputError naming
// the file, the line (ASCII) or byte (binary), the section and what is allowed.
#include <cstddef>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "emcontact/mesh/msh_element_types.hpp"

namespace emc::mesh::msh {

/// The elements of one type in one entity, in file order. Node tags are kept (num_nodes per
/// element) for the types read_msh uses, 3-node triangles and 4-node tets, only.
struct ElementBlock {
  int dim = 0;
  int entity = 0;
  int type = 0;
  std::size_t count = 0;
  std::vector<std::size_t> element_tags;
  std::vector<std::size_t> node_tags;
};

/// What read_msh needs of a .msh file, validated: every element node exists, every block's
/// entity exists, tags are unique and within the declared ranges, coordinates are finite.
struct MshData {
  using DimTag = std::pair<int, int>;
  std::map<DimTag, std::string> physical_names;         ///< (dim, physical tag) -> name
  std::map<DimTag, std::vector<int>> entity_physicals;  ///< (dim, entity tag) -> physical tags
  std::vector<std::size_t> node_tags;                   ///< sorted, unique
  std::vector<double> coords;                           ///< 3 per node, in node_tags order
  std::vector<ElementBlock> blocks;                     ///< in file order
  /// (dim, entity tag) -> indices in `blocks` of the entity's blocks, in file order.
  std::map<DimTag, std::vector<std::size_t>> entity_blocks;
  /// (dim, physical tag) -> sorted entity tags of the physical group (from entity_physicals).
  std::map<DimTag, std::vector<int>> group_entities;
};

/// Parses the .msh 4.1 file whose content is `text`; `where` ("<where>: '<file>'") prefixes
/// every error.
MshData parse_msh(const std::string& text, const std::string& where);

}  // namespace emc::mesh::msh
