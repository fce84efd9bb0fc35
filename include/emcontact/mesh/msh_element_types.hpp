#pragma once
// The Gmsh element types the mesh module's .msh parser knows (and skips, except 3-node
// triangles and 4-node tets).
#include <vector>

namespace emc::mesh::msh {

/// One of Gmsh's element types: its number, dimension, number of nodes and Gmsh's name.
struct ElementType {
  int type;
  int dim;
  int num_nodes;
  const char* name;
};

/// The element type `type`, or nullptr if the parser does not know it.
const ElementType* element_type(int type);

/// The element types the parser knows (Gmsh's linear and high-order lines, triangles,
/// quadrangles, tets, hexahedra, prisms and pyramids up to order 5, and points).
const std::vector<ElementType>& element_types();

}  // namespace emc::mesh::msh
