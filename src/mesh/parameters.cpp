// The valid parameters of a body's `Mesh` sublist (defaults, validators, doc strings). Array
// lengths and cross-parameter conditions are checked by build_mesh; the app's input schema
// (emcontact/app/input_schema.hpp) puts it in each body's template.
#include <Teuchos_Array.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <limits>
#include <map>

#include "emcontact/mesh/generate.hpp"

namespace emc::mesh {
namespace {

/// Validator of a strictly positive double (the smallest normal double is the inclusive min).
Teuchos::RCP<const Teuchos::ParameterEntryValidator> positive() {
  return Teuchos::rcp(new Teuchos::EnhancedNumberValidator<double>(
      std::numeric_limits<double>::min(), std::numeric_limits<double>::max()));
}

void set_positive(Teuchos::ParameterList& pl, const std::string& name, double value,
                  const std::string& doc) {
  pl.set(name, value, doc + " (> 0)", positive());
}

void set_point(Teuchos::ParameterList& pl, const std::string& name, double x, double y, double z,
               const std::string& doc) {
  pl.set(name, Teuchos::Array<double>(Teuchos::tuple(x, y, z)), doc + " (3 components: x, y, z)");
}

}  // namespace

Teuchos::RCP<const Teuchos::ParameterList> valid_mesh_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("Mesh"));
  Teuchos::setStringToIntegralParameter<MeshType>(
      "type", "box",
      "Shape of the body: a built-in Gmsh mesh ('box', 'cylinder', 'hollow cylinder', "
      "'spherical shell'), a rigid surface ('plane', 'rectangle': triangles only, fixed in "
      "space) or a Gmsh .msh 4.1 file ('file'). Each type reads only the parameters named with "
      "it below ('size' with every type but 'file'); a parameter of another type is refused (not "
      "one the input file gives for its own type when --set changes the type). "
      "A built-in volume must give tetrahedra: every extent (side, height, radius, wall "
      "thickness) at least 1e-6 of its largest and about 'size' or more",
      Teuchos::tuple<std::string>("box", "cylinder", "hollow cylinder", "spherical shell", "plane",
                                  "rectangle", "file"),
      Teuchos::tuple<std::string>(
          "axis-aligned box between 'lower corner' and 'upper corner'; surfaces xmin, xmax, "
          "ymin, ymax, zmin, zmax",
          "solid cylinder ('center' of the base disk, 'axis', 'height', 'radius'); surfaces "
          "bottom, top, outer",
          "hollow cylinder ('center', 'axis', 'height', 'inner radius', 'outer radius'); "
          "surfaces bottom, top, outer, inner",
          "spherical shell ('center', 'inner radius', 'outer radius'); surfaces outer, inner",
          "rigid square ('center', normal 'axis', 'half width'), a grid of triangles of edge "
          "about 'size' (at most 200 x 200 squares, larger ones if 'size' is too small), "
          "normals along +'axis'; surface 'surface'",
          "rigid axis-aligned rectangle from 'lower corner' to 'upper corner' (equal in exactly "
          "one component, the normal direction), a grid of triangles of edge about 'size', "
          "normals along +'axis' (parallel to the normal direction); surface 'surface'",
          "Gmsh .msh 4.1 file ('file', 'volume'); surfaces: its physical surfaces. A file with "
          "triangles and no tetrahedra is a rigid surface: triangles oriented as in the file, "
          "surfaces: its physical surfaces and 'surface' (all triangles)"),
      Teuchos::tuple<MeshType>(MeshType::box, MeshType::cylinder, MeshType::hollow_cylinder,
                               MeshType::spherical_shell, MeshType::plane, MeshType::rectangle,
                               MeshType::file),
      pl.get());
  pl->set("file", std::string(""),
          "Gmsh .msh 4.1 file (type 'file'), relative to the input file's directory; its "
          "physical surfaces become the named surfaces. A file with triangles and no "
          "tetrahedra is a rigid surface: its triangles are used as oriented in the file, and "
          "the surface 'surface' holds all of them");
  pl->set("volume", std::string(""),
          "Physical volume of 'file' to use (type 'file'); empty: all 4-node tetrahedra (or, "
          "in a file without tetrahedra, all triangles: a rigid surface)");
  set_positive(*pl, "size", 0.1,
               "Target element edge length of the built-in meshes (tetrahedra, or the "
               "triangles of 'plane' and 'rectangle')");
  set_point(*pl, "lower corner", 0.0, 0.0, 0.0,
            "Lower corner of the box (type 'box') or of the rectangle (type 'rectangle')");
  set_point(*pl, "upper corner", 1.0, 1.0, 1.0,
            "Upper corner of the box (type 'box'), above 'lower corner' in every component; of "
            "the rectangle (type 'rectangle'), equal to 'lower corner' in exactly one component "
            "(the normal direction) and above it in the other two");
  set_point(*pl, "center", 0.0, 0.0, 0.0,
            "Center of the base disk (cylinders, surface 'bottom'), of the sphere (spherical "
            "shell) or of the square (plane)");
  set_point(*pl, "axis", 0.0, 0.0, 1.0,
            "Direction of the cylinder axis, from 'bottom' to 'top'; for 'plane' and "
            "'rectangle' the normal of the surface, pointing to the side contact happens on "
            "(not normalized, nonzero)");
  set_positive(*pl, "half width", 1.0,
               "Half the side of the square of type 'plane' (its extent from 'center' along "
               "both in-plane directions); the square is cut into at most 200 x 200 squares of "
               "two triangles (larger than 'size' if needed). A rigid surface may be at most 1e6 "
               "times the size of the deformable bodies (bounding box diagonals)");
  set_positive(*pl, "height", 0.1, "Cylinder height along 'axis'");
  set_positive(*pl, "radius", 0.1, "Radius of the solid cylinder (type 'cylinder')");
  set_positive(*pl, "inner radius", 0.05,
               "Inner radius ('hollow cylinder', 'spherical shell'), below 'outer radius'");
  set_positive(*pl, "outer radius", 0.1,
               "Outer radius ('hollow cylinder', 'spherical shell'), above 'inner radius'");
  return pl;
}

std::vector<std::string> types_reading(const std::string& parameter) {
  const std::vector<std::string> generated = {
      "box", "cylinder", "hollow cylinder", "spherical shell", "plane", "rectangle"};
  static const std::map<std::string, std::vector<std::string>> table = {
      {"file", {"file"}},
      {"volume", {"file"}},
      {"size", generated},
      {"lower corner", {"box", "rectangle"}},
      {"upper corner", {"box", "rectangle"}},
      {"center", {"cylinder", "hollow cylinder", "spherical shell", "plane"}},
      {"axis", {"cylinder", "hollow cylinder", "plane", "rectangle"}},
      {"half width", {"plane"}},
      {"height", {"cylinder", "hollow cylinder"}},
      {"radius", {"cylinder"}},
      {"inner radius", {"hollow cylinder", "spherical shell"}},
      {"outer radius", {"hollow cylinder", "spherical shell"}}};
  const auto it = table.find(parameter);
  return it == table.end() ? std::vector<std::string>() : it->second;
}

bool is_rigid_surface_type(MeshType type) {
  return type == MeshType::plane || type == MeshType::rectangle;
}

}  // namespace emc::mesh
