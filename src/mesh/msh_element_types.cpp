// Gmsh's element types the .msh parser knows: dimension, number of nodes and Gmsh's name
// (as gmsh::model::mesh::getElementProperties gives them, Gmsh 4.8).
#include <algorithm>

#include "msh_parser.hpp"

namespace emc::mesh::msh {

const std::vector<ElementType>& element_types() {
  static const std::vector<ElementType> types = {
      {1, 1, 2, "Line 2"},           {2, 2, 3, "Triangle 3"},       {3, 2, 4, "Quadrilateral 4"},
      {4, 3, 4, "Tetrahedron 4"},    {5, 3, 8, "Hexahedron 8"},     {6, 3, 6, "Prism 6"},
      {7, 3, 5, "Pyramid 5"},        {8, 1, 3, "Line 3"},           {9, 2, 6, "Triangle 6"},
      {10, 2, 9, "Quadrilateral 9"}, {11, 3, 10, "Tetrahedron 10"}, {12, 3, 27, "Hexahedron 27"},
      {13, 3, 18, "Prism 18"},       {14, 3, 14, "Pyramid 14"},     {15, 0, 1, "Point"},
      {16, 2, 8, "Quadrilateral 8"}, {17, 3, 20, "Hexahedron 20"},  {18, 3, 15, "Prism 15"},
      {19, 3, 13, "Pyramid 13"},     {20, 2, 9, "Triangle 9"},      {21, 2, 10, "Triangle 10"},
      {22, 2, 12, "Triangle 12"},    {23, 2, 15, "Triangle 15"},    {24, 2, 15, "Triangle 15I"},
      {25, 2, 21, "Triangle 21"},    {26, 1, 4, "Line 4"},          {27, 1, 5, "Line 5"},
      {28, 1, 6, "Line 6"},          {29, 3, 20, "Tetrahedron 20"}, {30, 3, 35, "Tetrahedron 35"},
      {31, 3, 56, "Tetrahedron 56"}, {32, 3, 22, "Tetrahedron 22"}, {33, 3, 28, "Tetrahedron 28"},
      {92, 3, 64, "Hexahedron 64"},  {93, 3, 125, "Hexahedron 125"}};
  return types;
}

const ElementType* element_type(int type) {
  const std::vector<ElementType>& types = element_types();
  const auto it = std::find_if(types.begin(), types.end(),
                               [type](const ElementType& t) { return t.type == type; });
  return it == types.end() ? nullptr : &*it;
}

}  // namespace emc::mesh::msh
