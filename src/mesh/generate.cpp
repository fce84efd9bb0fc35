// Built-in meshes through Gmsh's OpenCASCADE kernel (box, cylinder, hollow cylinder, spherical
// shell), their named surfaces, the rigid surfaces (plane, rectangle: structured triangle
// grids), and the dispatch of a validated `Mesh` sublist.
#include "emcontact/mesh/generate.hpp"

#include <gmsh.h>

#include <Teuchos_Array.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <sstream>
#include <tuple>
#include <utility>

#include "emcontact/error.hpp"
#include "emcontact/input/echo.hpp"
#include "emcontact/input/files.hpp"
#include "emcontact/vec3.hpp"
#include "internal.hpp"

namespace emc::mesh {
namespace {

using Tri = std::array<int, 3>;

/// Every extent of a built-in volume (a box's side, a cylinder's height and radius, a wall's
/// thickness) must be at least this fraction of its largest one: OpenCASCADE merges points
/// closer than its tolerance of 1e-7 (of a body of size about 1), and fails on such a sliver
/// without a reason ("OpenCASCADE exception").
constexpr double kMinExtentRatio = 1e-6;

/// A built-in shape: how to create it in Gmsh, how to name its boundary triangles, its exact
/// volume (for the element count estimate) and its description in messages.
struct Shape {
  std::function<void()> add_to_gmsh;  ///< adds exactly one OCC volume to the current model
  std::function<std::string(const std::array<Vec3, 3>&)> surface_of;  ///< "" if unknown
  double volume = 0.0;
  std::string description;  ///< "spherical shell of inner radius 0.05, outer radius 0.1"
  double thinnest = 0.0;    ///< the smallest extent: side, height, radius or wall thickness
};

std::string str(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

std::string str(const Vec3& v) {
  return "{" + str(v[0]) + ", " + str(v[1]) + ", " + str(v[2]) + "}";
}

// ---- parameters -------------------------------------------------------------------------

/// The text of a Teuchos exception without its "file:line:", "Throw number = n" and "Throw
/// test that evaluated to true" paragraphs.
std::string teuchos_message(const std::string& what) {
  std::string msg;
  std::size_t begin = 0;
  while (begin < what.size()) {
    std::size_t end = what.find("\n\n", begin);
    if (end == std::string::npos) end = what.size();
    const std::string para = what.substr(begin, end - begin);
    const bool noise = para.rfind("Throw number", 0) == 0 || para.rfind("Throw test", 0) == 0 ||
                       (para.find('\n') == std::string::npos && !para.empty() &&
                        para.back() == ':' && para.find("pp:") != std::string::npos);
    if (!noise && para.find_first_not_of(" \n") != std::string::npos) {
      msg += (msg.empty() ? "" : "\n\n") + para;
    }
    begin = end + 2;
  }
  return msg.empty() ? what : msg;
}

/// A copy of `in` validated against valid_mesh_parameters(), defaults filled in.
Teuchos::ParameterList validated(const Teuchos::ParameterList& in, const std::string& where) {
  Teuchos::ParameterList p(in);
  try {
    p.validateParametersAndSetDefaults(*valid_mesh_parameters());
  } catch (const std::exception& e) {
    throw InputError(where + ": " + teuchos_message(e.what()));
  }
  return p;
}

double positive_param(const Teuchos::ParameterList& p, const std::string& name,
                      const std::string& where) {
  const double v = p.get<double>(name);
  if (!(v > 0.0) || !std::isfinite(v)) {
    throw InputError(where + ": parameter '" + name + "' is " + str(v) +
                     "; it must be a finite number > 0");
  }
  return v;
}

Vec3 point_param(const Teuchos::ParameterList& p, const std::string& name,
                 const std::string& where) {
  const auto& a = p.get<Teuchos::Array<double>>(name);
  if (a.size() != 3) {
    throw InputError(where + ": parameter '" + name + "' has " + std::to_string(a.size()) +
                     " components; it must have 3 (x, y, z), e.g. {0, 0, 0}");
  }
  for (double v : a) {
    if (!std::isfinite(v)) {
      throw InputError(where + ": parameter '" + name + "' has a non-finite component");
    }
  }
  return {a[0], a[1], a[2]};
}

/// The parameter `axis`, normalised; refuses a zero (or non-finite) vector.
Vec3 unit_axis(const Teuchos::ParameterList& p, const std::string& where) {
  const Vec3 axis = point_param(p, "axis", where);
  const double len = norm(axis);
  if (!(len > 0.0) || !std::isfinite(len)) {
    throw InputError(where + ": parameter 'axis' must be a nonzero vector");
  }
  return scaled(1.0 / len, axis);
}

/// Refuses `extent` (what it is: "the wall (outer radius - inner radius)") below
/// kMinExtentRatio of `largest`, naming `parameter`.
void check_extent(double extent, double largest, const std::string& parameter,
                  const std::string& what, const std::string& where) {
  if (extent >= kMinExtentRatio * largest) return;
  throw InputError(where + ": parameter '" + parameter + "': " + what + " is " + str(extent) +
                   ", below 1e-6 of the body's largest extent " + str(largest) +
                   ": Gmsh (OpenCASCADE) cannot mesh such a sliver; allowed: every extent at "
                   "least 1e-6 of the largest (and about 'size' or more, to get elements)");
}

/// `inner radius` and `outer radius`, with inner < outer and a wall of at least
/// kMinExtentRatio of the outer radius.
std::pair<double, double> radii_params(const Teuchos::ParameterList& p, const std::string& where) {
  const double ri = positive_param(p, "inner radius", where);
  const double ro = positive_param(p, "outer radius", where);
  if (!(ri < ro)) {
    throw InputError(where + ": parameter 'inner radius' (" + str(ri) +
                     ") must be smaller than 'outer radius' (" + str(ro) + ")");
  }
  check_extent(ro - ri, ro, "inner radius", "the wall (outer radius - inner radius)", where);
  return {ri, ro};
}

// ---- shapes -----------------------------------------------------------------------------

/// True if every node of `t` satisfies |f(node)| < tol.
template <class F>
bool all_near(const std::array<Vec3, 3>& t, const F& f, double tol) {
  return std::abs(f(t[0])) < tol && std::abs(f(t[1])) < tol && std::abs(f(t[2])) < tol;
}

Shape box_shape(const Teuchos::ParameterList& p, const std::string& where) {
  const Vec3 lo = point_param(p, "lower corner", where);
  const Vec3 hi = point_param(p, "upper corner", where);
  const char* axes = "xyz";
  Shape s;
  s.volume = 1.0;
  for (int d = 0; d < 3; ++d) {
    if (!(hi[d] > lo[d])) {
      const std::string component =
          std::string(1, axes[d]) + ": " + str(hi[d]) + " <= " + str(lo[d]);
      throw InputError(where + ": parameter 'upper corner' must exceed 'lower corner' in " +
                       "every component; " + component);
    }
    s.volume *= hi[d] - lo[d];
  }
  const Vec3 side = sub(hi, lo);
  const double largest = std::max({side[0], side[1], side[2]});
  for (int d = 0; d < 3; ++d)
    check_extent(side[d], largest, "upper corner",
                 std::string("the side along ") + axes[d] + " ('upper corner' - 'lower corner')",
                 where);
  s.description = "box from " + str(lo) + " to " + str(hi);
  s.thinnest = std::min({side[0], side[1], side[2]});
  s.add_to_gmsh = [lo, hi] {
    gmsh::model::occ::addBox(lo[0], lo[1], lo[2], hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  };
  const double tol = 1e-7 * norm(sub(hi, lo));
  s.surface_of = [lo, hi, tol](const std::array<Vec3, 3>& t) -> std::string {
    static const char* names[3][2] = {{"xmin", "xmax"}, {"ymin", "ymax"}, {"zmin", "zmax"}};
    for (int d = 0; d < 3; ++d) {
      const auto from_lo = [&](const Vec3& x) { return x[d] - lo[d]; };
      const auto from_hi = [&](const Vec3& x) { return x[d] - hi[d]; };
      if (all_near(t, from_lo, tol)) return names[d][0];
      if (all_near(t, from_hi, tol)) return names[d][1];
    }
    return "";
  };
  return s;
}

/// Solid (`hollow` false: parameter `radius`) or hollow (`inner/outer radius`) cylinder.
Shape cylinder_shape(const Teuchos::ParameterList& p, const std::string& where, bool hollow) {
  const Vec3 c = point_param(p, "center", where);
  const Vec3 a = unit_axis(p, where);
  const double h = positive_param(p, "height", where);
  double ri = 0.0, ro = 0.0;
  if (hollow) {
    std::tie(ri, ro) = radii_params(p, where);
  } else {
    ro = positive_param(p, "radius", where);
  }
  if (!hollow)
    check_extent(std::min(h, ro), std::max(h, ro), h < ro ? "height" : "radius",
                 h < ro ? "the height" : "the radius", where);
  if (hollow) check_extent(h, std::max(h, ro), "height", "the height", where);
  Shape s;
  s.volume = M_PI * (ro * ro - ri * ri) * h;
  s.description = hollow ? "hollow cylinder of height " + str(h) + ", inner radius " + str(ri) +
                               ", outer radius " + str(ro)
                         : "cylinder of height " + str(h) + ", radius " + str(ro);
  s.thinnest = std::min(h, hollow ? ro - ri : ro);
  s.add_to_gmsh = [c, a, h, ri, ro, hollow] {
    const int outer =
        gmsh::model::occ::addCylinder(c[0], c[1], c[2], h * a[0], h * a[1], h * a[2], ro);
    if (!hollow) return;
    // The hole overshoots both ends so that the cut has no coincident faces.
    const Vec3 b{c[0] - 0.1 * h * a[0], c[1] - 0.1 * h * a[1], c[2] - 0.1 * h * a[2]};
    const int inner = gmsh::model::occ::addCylinder(b[0], b[1], b[2], 1.2 * h * a[0],
                                                    1.2 * h * a[1], 1.2 * h * a[2], ri);
    gmsh::vectorpair out;
    std::vector<gmsh::vectorpair> map;
    gmsh::model::occ::cut({{3, outer}}, {{3, inner}}, out, map);
  };
  const double tol = 1e-7 * std::max(h, ro);
  s.surface_of = [c, a, h, ri, ro, hollow, tol](const std::array<Vec3, 3>& t) -> std::string {
    const auto height = [&](const Vec3& x) { return dot(sub(x, c), a); };
    if (all_near(t, height, tol)) return "bottom";
    const auto below_top = [&](const Vec3& x) { return height(x) - h; };
    if (all_near(t, below_top, tol)) return "top";
    double r = 0.0;  // mean distance of the nodes from the axis
    for (const Vec3& x : t) {
      const Vec3 d = sub(x, c);
      const double z = dot(d, a);
      r += norm({d[0] - z * a[0], d[1] - z * a[1], d[2] - z * a[2]}) / 3.0;
    }
    return hollow && r < 0.5 * (ri + ro) ? "inner" : "outer";
  };
  return s;
}

Shape shell_shape(const Teuchos::ParameterList& p, const std::string& where) {
  const Vec3 c = point_param(p, "center", where);
  const auto [ri, ro] = radii_params(p, where);
  Shape s;
  s.volume = 4.0 / 3.0 * M_PI * (ro * ro * ro - ri * ri * ri);
  s.description = "spherical shell of inner radius " + str(ri) + ", outer radius " + str(ro);
  s.thinnest = ro - ri;
  s.add_to_gmsh = [c, ri = ri, ro = ro] {
    const int outer = gmsh::model::occ::addSphere(c[0], c[1], c[2], ro);
    const int inner = gmsh::model::occ::addSphere(c[0], c[1], c[2], ri);
    gmsh::vectorpair out;
    std::vector<gmsh::vectorpair> map;
    gmsh::model::occ::cut({{3, outer}}, {{3, inner}}, out, map);
  };
  s.surface_of = [c, ri = ri, ro = ro](const std::array<Vec3, 3>& t) -> std::string {
    const double r = (norm(sub(t[0], c)) + norm(sub(t[1], c)) + norm(sub(t[2], c))) / 3.0;
    return r < 0.5 * (ri + ro) ? "inner" : "outer";
  };
  return s;
}

// ---- rigid surfaces (no tets) -------------------------------------------------------------

/// Type `plane`: the square of half side `half width` centred at `center`, normal `axis`.
BodyMesh plane_mesh(const Teuchos::ParameterList& p, double size, const std::string& where) {
  const Vec3 c = point_param(p, "center", where);
  const Vec3 n = unit_axis(p, where);
  const double hw = positive_param(p, "half width", where);
  if (!std::isfinite(2.0 * hw)) {
    throw InputError(where + ": parameter 'half width' (" + str(hw) + ") is too large");
  }
  // In-plane unit vectors t1, t2 with t1 x t2 = n; t1 from the coordinate axis least aligned
  // with n (n = +z gives t1 = +x, t2 = +y).
  int k = 0;
  for (int d = 1; d < 3; ++d) {
    if (std::abs(n[d]) < std::abs(n[k])) k = d;
  }
  Vec3 e{0.0, 0.0, 0.0};
  e[k] = 1.0;
  const Vec3 u = sub(e, scaled(dot(e, n), n));
  const Vec3 t1 = scaled(1.0 / norm(u), u);
  const Vec3 t2 = cross(n, t1);
  Vec3 origin{};
  for (int d = 0; d < 3; ++d) origin[d] = c[d] - hw * t1[d] - hw * t2[d];
  const auto cells = grid_cells(2.0 * hw, 2.0 * hw, size);
  return detail::triangle_grid(origin, scaled(2.0 * hw, t1), scaled(2.0 * hw, t2), cells[0],
                               cells[1]);
}

/// Type `rectangle`: axis-aligned, from `lower corner` to `upper corner` (equal in exactly one
/// component, the normal direction), normal +`axis` (parallel to that direction).
BodyMesh rectangle_mesh(const Teuchos::ParameterList& p, double size, const std::string& where) {
  const Vec3 lo = point_param(p, "lower corner", where);
  const Vec3 hi = point_param(p, "upper corner", where);
  const Vec3 extent = sub(hi, lo);
  int flat = -1, zeros = 0, positive = 0;
  for (int d = 0; d < 3; ++d) {
    if (extent[d] == 0.0) {
      flat = d;
      ++zeros;
    }
    if (extent[d] > 0.0 && std::isfinite(extent[d])) ++positive;
  }
  if (zeros != 1 || positive != 2) {
    throw InputError(where + ": type 'rectangle': 'upper corner' - 'lower corner' is " +
                     str(extent) +
                     "; it must be zero in exactly one component (the normal direction) and "
                     "positive in the other two");
  }
  const char* axes = "xyz";
  const Vec3 axis = point_param(p, "axis", where);
  const double len = norm(axis);
  const int q1 = (flat + 1) % 3, q2 = (flat + 2) % 3;  // e_q1 x e_q2 = e_flat
  if (!(len > 0.0) || !std::isfinite(len) || std::abs(axis[q1]) > 1e-12 * len ||
      std::abs(axis[q2]) > 1e-12 * len) {
    Vec3 plus{0.0, 0.0, 0.0}, minus{0.0, 0.0, 0.0};
    plus[flat] = 1.0;
    minus[flat] = -1.0;
    throw InputError(where + ": parameter 'axis' " + str(axis) +
                     " must be parallel to the rectangle's normal direction " + axes[flat] +
                     " (the component where 'upper corner' equals 'lower corner'): " + str(plus) +
                     " or " + str(minus));
  }
  Vec3 a{0.0, 0.0, 0.0}, b{0.0, 0.0, 0.0};
  a[q1] = extent[q1];
  b[q2] = extent[q2];
  if (axis[flat] < 0.0) std::swap(a, b);  // normal a x b along -e_flat
  const auto cells = grid_cells(norm(a), norm(b), size);
  return detail::triangle_grid(lo, a, b, cells[0], cells[1]);
}

// ---- meshing ----------------------------------------------------------------------------

/// Swaps two nodes of every tet the generator left with a negative volume.
void orient_positive(BodyMesh& m) {
  for (int e = 0; e < m.num_tets(); ++e) {
    if (tet_volume(m, e) < 0.0) std::swap(m.tets[4 * e + 2], m.tets[4 * e + 3]);
  }
}

/// Fills m.surfaces by naming every boundary triangle with `shape.surface_of`.
void name_surfaces(BodyMesh& m, const Shape& shape, const std::string& where) {
  for (const Tri& t : boundary_triangles(m)) {
    std::array<Vec3, 3> x{};
    for (int k = 0; k < 3; ++k) x[k] = {m.X[3 * t[k]], m.X[3 * t[k] + 1], m.X[3 * t[k] + 2]};
    const std::string name = shape.surface_of(x);
    if (name.empty()) {
      throw Error(where + ": internal error: a boundary triangle of the generated mesh " +
                  "lies on no face of the shape");
    }
    m.surfaces[name].push_back(t);  // boundary_triangles is sorted, so each surface is too
  }
}

/// About the number of tets of edge `size` that fill `shape` (8.5 regular tets per size^3).
double tets_estimate(const Shape& shape, double size) {
  return 8.5 * shape.volume / (size * size * size);
}

/// The tet mesh of `shape` with target edge length `size`.
BodyMesh generate(const Shape& shape, double size, const std::string& where) {
  const double estimate = tets_estimate(shape, size);
  if (estimate > kMaxTets) {
    throw InputError(where + ": parameter 'size' (" + str(size) + ") is too small for this " +
                     "body: about " + str(estimate) + " tetrahedra, the limit is " + str(kMaxTets));
  }
  detail::GmshSession session;
  BodyMesh m;
  // a wall thinner than the elements is the usual cause of a failure (Gmsh's own reason is
  // about its triangulation, e.g. "PLC Error: A segment and a facet intersect")
  const std::string thin =
      shape.thinnest < size ? " (its thinnest extent, " + str(shape.thinnest) + ", is below 'size')"
                            : "";
  detail::with_gmsh(
      where, "Gmsh failed to mesh the " + shape.description + " with size " + str(size) + thin,
      [&] {
        gmsh::model::add("body");
        shape.add_to_gmsh();
        gmsh::model::occ::synchronize();
        gmsh::option::setNumber("Mesh.MeshSizeMin", 0.0);
        gmsh::option::setNumber("Mesh.MeshSizeMax", size);
        gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
        gmsh::option::setNumber("Mesh.Optimize", 1);
        gmsh::model::mesh::generate(3);
        std::vector<std::size_t> used_tags;
        m = detail::body_from_gmsh(detail::gmsh_tets({}, where), used_tags);
      });
  if (m.num_tets() == 0)
    throw InputError(where + ": Gmsh made no tetrahedra of the " + shape.description +
                     " with size " + str(size) + thin +
                     "; allowed: a body whose every extent (side, height, wall thickness) is "
                     "about 'size' or more");
  orient_positive(m);
  check_tets(m, where + " (generated mesh)");
  name_surfaces(m, shape, where);
  return m;
}

/// Type `file`: resolves `file` against `input_dir` and reads it.
BodyMesh mesh_from_file(const Teuchos::ParameterList& p, const std::string& input_dir,
                        const std::string& where) {
  const std::string file = p.get<std::string>("file");
  if (file.empty()) {
    throw InputError(where + ": parameter 'file' is empty; type 'file' needs a Gmsh .msh " +
                     "4.1 file (relative to the input file's directory)");
  }
  std::filesystem::path path(file);
  if (path.is_relative() && !input_dir.empty()) path = std::filesystem::path(input_dir) / path;
  const std::string resolved = path.lexically_normal().string();
  std::error_code ec;
  if (!std::filesystem::exists(resolved, ec))
    throw InputError(where + ": parameter 'file': mesh file '" + input::echo(resolved) +
                     "' does not exist");
  try {  // a directory, FIFO or device: say which
    input::check_regular_file(resolved, "mesh file");
  } catch (const InputError& e) {
    throw InputError(where + ": parameter 'file': " + e.what());
  }
  return read_msh(resolved, p.get<std::string>("volume"), where);
}

}  // namespace

namespace {

/// The shape of a volume type (box, cylinder, hollow cylinder, spherical shell), its parameters
/// checked; false for the other types.
bool volume_shape(MeshType type, const Teuchos::ParameterList& p, const std::string& where,
                  Shape& shape) {
  switch (type) {
    case MeshType::box:
      shape = box_shape(p, where);
      return true;
    case MeshType::cylinder:
      shape = cylinder_shape(p, where, false);
      return true;
    case MeshType::hollow_cylinder:
      shape = cylinder_shape(p, where, true);
      return true;
    case MeshType::spherical_shell:
      shape = shell_shape(p, where);
      return true;
    default:
      return false;
  }
}

}  // namespace

double estimated_tets(const Teuchos::ParameterList& mesh_params, const std::string& where) {
  const Teuchos::ParameterList p = validated(mesh_params, where);
  const MeshType type = Teuchos::getIntegralValue<MeshType>(p, "type");
  Shape shape;
  if (type == MeshType::file || !volume_shape(type, p, where, shape)) return 0.0;
  return tets_estimate(shape, positive_param(p, "size", where));
}

BodyMesh build_mesh(const Teuchos::ParameterList& mesh_params, const std::string& input_dir,
                    const std::string& where) {
  const Teuchos::ParameterList p = validated(mesh_params, where);
  const MeshType type = Teuchos::getIntegralValue<MeshType>(p, "type");
  if (type == MeshType::file) return mesh_from_file(p, input_dir, where);
  const double size = positive_param(p, "size", where);
  Shape shape;
  if (volume_shape(type, p, where, shape)) return generate(shape, size, where);
  if (type == MeshType::plane) return plane_mesh(p, size, where);
  if (type == MeshType::rectangle) return rectangle_mesh(p, size, where);
  throw InputError(where + ": parameter 'type': not a shape");
}

}  // namespace emc::mesh
