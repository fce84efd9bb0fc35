// The built-in meshes (Gmsh, OpenCASCADE) and the `Mesh` parameters.
//
// Volume and area bounds of the curved shapes: every boundary node lies on the exact surface,
// so a circle of radius r is replaced by chords of length h (about the target `size`, Gmsh
// allows some 40% more), subtending theta = h / r. A chord polygon misses the relative area
// 1 - sin(theta) / theta ~ theta^2 / 6 of the disk; a triangulated sphere misses about
// theta^2 / 4 of its volume. All tests below use theta <= 0.4 * 1.4 = 0.56 on the tightest
// curve, i.e. at most ~5% of the inner surface and much less of the volume (the chord errors of
// outer and inner surfaces partly cancel); the bounds are 3% (volumes) and 6% (areas).
#include <gtest/gtest.h>

#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <iostream>
#include <set>

#include "emcontact/error.hpp"
#include "emcontact/mesh/generate.hpp"
#include "mesh_test_util.hpp"

namespace emc::mesh::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// Properties every generated mesh has: positive tets, every node used, named surfaces that
/// partition the closed, outward boundary.
void expect_valid_generated(const BodyMesh& m, const std::set<std::string>& names) {
  EXPECT_NO_THROW(check_tets(m, "generated"));
  EXPECT_GT(min_volume(m), 0.0);
  std::vector<char> used(m.num_nodes(), 0);
  for (int n : m.tets) used[n] = 1;
  EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0) << "nodes not used by any tet";
  std::set<std::string> got;
  for (const auto& s : m.surfaces) {
    got.insert(s.first);
    EXPECT_FALSE(s.second.empty()) << s.first;
  }
  EXPECT_EQ(got, names);
  const auto boundary = boundary_triangles(m);
  EXPECT_TRUE(is_closed(boundary));
  EXPECT_EQ(all_named(m), unoriented(boundary)) << "named surfaces != boundary";
  for (const auto& s : m.surfaces) EXPECT_TRUE(std::is_sorted(s.second.begin(), s.second.end()));
}

/// Every triangle of `tris` has the unit normal `n` (flat faces).
void expect_normals(const BodyMesh& m, const std::vector<Tri>& tris, const Vec3& n) {
  for (const Tri& t : tris) ASSERT_NEAR(dot(unit_normal(m, t), n), 1.0, 1e-9);
}

/// Every boundary triangle's normal points away from the centroid (convex bodies).
void expect_outward_from_centroid(const BodyMesh& m) {
  const Vec3 c = body_centroid(m);
  for (const Tri& t : boundary_triangles(m)) {
    ASSERT_GT(dot(area_normal(m, t), sub(centroid(m, t), c)), 0.0);
  }
}

/// Sign of the normals' radial component (away from the axis through `c` along `a`).
void expect_radial_sign(const BodyMesh& m, const std::vector<Tri>& tris, const Vec3& c,
                        const Vec3& a, double sign) {
  for (const Tri& t : tris) {
    const Vec3 d = sub(centroid(m, t), c);
    const double z = dot(d, a);
    const Vec3 radial{d[0] - z * a[0], d[1] - z * a[1], d[2] - z * a[2]};
    ASSERT_GT(sign * dot(unit_normal(m, t), radial) / norm(radial), 0.9);
  }
}

// ---- parameters ----------------------------------------------------------------------------

TEST(MeshParameters, NamesAndDefaults) {
  const auto pl = valid_mesh_parameters();
  std::set<std::string> names;
  for (auto it = pl->begin(); it != pl->end(); ++it) names.insert(pl->name(it));
  EXPECT_EQ(names, (std::set<std::string>{"type", "file", "volume", "size", "lower corner",
                                          "upper corner", "center", "axis", "half width", "height",
                                          "radius", "inner radius", "outer radius"}));
  EXPECT_EQ(pl->get<std::string>("type"), "box");
  EXPECT_EQ(pl->get<std::string>("file"), "");
  EXPECT_EQ(pl->get<std::string>("volume"), "");
  EXPECT_EQ(pl->get<double>("size"), 0.1);
  EXPECT_EQ(pl->get<Teuchos::Array<double>>("lower corner"), arr(0, 0, 0));
  EXPECT_EQ(pl->get<Teuchos::Array<double>>("upper corner"), arr(1, 1, 1));
  EXPECT_EQ(pl->get<Teuchos::Array<double>>("center"), arr(0, 0, 0));
  EXPECT_EQ(pl->get<Teuchos::Array<double>>("axis"), arr(0, 0, 1));
  EXPECT_EQ(pl->get<double>("half width"), 1.0);
  EXPECT_EQ(pl->get<double>("height"), 0.1);
  EXPECT_EQ(pl->get<double>("radius"), 0.1);
  EXPECT_EQ(pl->get<double>("inner radius"), 0.05);
  EXPECT_EQ(pl->get<double>("outer radius"), 0.1);
  for (auto it = pl->begin(); it != pl->end(); ++it) {
    EXPECT_FALSE(pl->entry(it).docString().empty()) << pl->name(it);
  }
  EXPECT_FALSE(pl->getEntry("type").validator().is_null());
  EXPECT_FALSE(pl->getEntry("size").validator().is_null());
}

TEST(MeshParameters, ValidatorRefusesUnknownType) {
  Teuchos::ParameterList p = params("cube", 0.1);
  EXPECT_THROW(p.validateParameters(*valid_mesh_parameters()),
               Teuchos::Exceptions::InvalidParameterValue);
  const std::string msg = build_error(p);
  EXPECT_NE(msg.find("input.xml: Bodies/b/Mesh: "), std::string::npos) << msg;
  EXPECT_NE(msg.find("cube"), std::string::npos) << msg;
  EXPECT_NE(msg.find("hollow cylinder"), std::string::npos) << msg;  // lists the allowed ones
  EXPECT_EQ(msg.find("Throw number"), std::string::npos) << msg;     // no Teuchos preamble
}

TEST(MeshParameters, ValidatorRefusesNonPositiveSize) {
  const std::string msg = build_error(params("box", -0.1));
  EXPECT_NE(msg.find("size"), std::string::npos) << msg;
}

TEST(MeshParameters, InnerRadiusMustBeBelowOuterRadius) {
  for (const std::string type : {"hollow cylinder", "spherical shell"}) {
    Teuchos::ParameterList p = params(type, 0.1);
    p.set("inner radius", 0.2);
    p.set("outer radius", 0.2);
    const std::string msg = build_error(p);
    EXPECT_NE(msg.find("input.xml: Bodies/b/Mesh: parameter 'inner radius' (0.2) must be smaller "
                       "than 'outer radius' (0.2)"),
              std::string::npos)
        << type << ": " << msg;
  }
}

TEST(MeshParameters, BoxCornersAreChecked) {
  Teuchos::ParameterList p = params("box", 0.5);
  p.set("upper corner", arr(1, 0, 1));
  std::string msg = build_error(p);
  EXPECT_NE(msg.find("'upper corner' must exceed 'lower corner'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("y: 0 <= 0"), std::string::npos) << msg;
  p.set("upper corner", Teuchos::Array<double>(2, 1.0));
  msg = build_error(p);
  EXPECT_NE(msg.find("parameter 'upper corner' has 2 components; it must have 3"),
            std::string::npos)
      << msg;
}

TEST(MeshParameters, ZeroAxisIsRefused) {
  Teuchos::ParameterList p = params("cylinder", 0.05);
  p.set("axis", arr(0, 0, 0));
  EXPECT_NE(build_error(p).find("'axis' must be a nonzero vector"), std::string::npos);
}

TEST(MeshParameters, TooSmallSizeIsRefusedBeforeMeshing) {
  const std::string msg = build_error(params("box", 1e-4));
  EXPECT_NE(msg.find("'size' (0.0001) is too small"), std::string::npos) << msg;
}

// OpenCASCADE fails on a sliver without a reason: refused before Gmsh, naming the parameter.
TEST(MeshParameters, SliverIsRefusedBeforeGmsh) {
  Teuchos::ParameterList p = params("box", 0.1);
  p.set("upper corner", arr(1, 1e-9, 1));
  std::string msg = build_error(p);
  EXPECT_NE(msg.find("input.xml: Bodies/b/Mesh: parameter 'upper corner': the side along y "
                     "('upper corner' - 'lower corner') is 1e-09, below 1e-6 of the body's "
                     "largest extent 1"),
            std::string::npos)
      << msg;
  Teuchos::ParameterList c = params("cylinder", 0.1);
  c.set("height", 1e-8);
  EXPECT_NE(build_error(c).find("parameter 'height': the height is 1e-08"), std::string::npos)
      << build_error(c);
  Teuchos::ParameterList h = params("hollow cylinder", 0.1);
  h.set("inner radius", 0.1 - 1e-9);
  h.set("outer radius", 0.1);
  EXPECT_NE(build_error(h).find("parameter 'inner radius': the wall (outer radius - inner "
                                "radius) is 1e-09"),
            std::string::npos)
      << build_error(h);
}

// A volume Gmsh fills with no tetrahedra is refused, naming its size and radii (it was a
// rigid surface without a word).
TEST(MeshParameters, VolumeWithoutTetsIsRefused) {
  Teuchos::ParameterList p = params("spherical shell", 0.05);
  p.set("inner radius", 0.0999999);
  p.set("outer radius", 0.1);
  const std::string msg = build_error(p);
  EXPECT_NE(msg.find("input.xml: Bodies/b/Mesh: Gmsh made no tetrahedra of the spherical shell "
                     "of inner radius 0.0999999, outer radius 0.1 with size 0.05 (its thinnest "
                     "extent, 1e-07, is below 'size')"),
            std::string::npos)
      << msg;
}

TEST(MeshParameters, EstimatedTets) {
  Teuchos::ParameterList p = params("box", 0.1);
  EXPECT_NEAR(estimated_tets(p, "w"), 8.5 * 1.0 / 1e-3, 1e-9);
  EXPECT_EQ(estimated_tets(params("plane", 0.1), "w"), 0.0);
  EXPECT_EQ(estimated_tets(params("file", 0.1), "w"), 0.0);
  p.set("upper corner", arr(1, 0, 1));  // checked as build_mesh checks it
  EXPECT_THROW(estimated_tets(p, "w"), InputError);
}

TEST(MeshParameters, FileTypeNeedsExistingFile) {
  Teuchos::ParameterList p = params("file", 0.1);
  EXPECT_NE(build_error(p).find("parameter 'file' is empty"), std::string::npos);
  p.set("file", std::string("meshes/no_such_body.msh"));
  try {
    build_mesh(p, "/tmp/emc_no_such_dir", "input.xml: Bodies/b/Mesh");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'/tmp/emc_no_such_dir/meshes/no_such_body.msh' does "
                                         "not exist"),
              std::string::npos)
        << e.what();
  }
}

// ---- generated meshes ------------------------------------------------------------------------

TEST(GenerateBox, ExactVolumeFacesAndAreas) {
  Teuchos::ParameterList p = params("box", 0.25);
  p.set("lower corner", arr(-1, 0, 0.5));
  p.set("upper corner", arr(1, 0.5, 1.5));
  const BodyMesh m = build_mesh(p, "", "box");
  expect_valid_generated(m, {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"});
  EXPECT_NEAR(total_volume(m), 1.0, 1e-12);
  EXPECT_NEAR(area(m, m.surfaces.at("xmin")), 0.5, 1e-12);
  EXPECT_NEAR(area(m, m.surfaces.at("xmax")), 0.5, 1e-12);
  EXPECT_NEAR(area(m, m.surfaces.at("ymin")), 2.0, 1e-12);
  EXPECT_NEAR(area(m, m.surfaces.at("ymax")), 2.0, 1e-12);
  EXPECT_NEAR(area(m, m.surfaces.at("zmin")), 1.0, 1e-12);
  EXPECT_NEAR(area(m, m.surfaces.at("zmax")), 1.0, 1e-12);
  expect_normals(m, m.surfaces.at("xmin"), {-1, 0, 0});
  expect_normals(m, m.surfaces.at("xmax"), {1, 0, 0});
  expect_normals(m, m.surfaces.at("ymin"), {0, -1, 0});
  expect_normals(m, m.surfaces.at("ymax"), {0, 1, 0});
  expect_normals(m, m.surfaces.at("zmin"), {0, 0, -1});
  expect_normals(m, m.surfaces.at("zmax"), {0, 0, 1});
  expect_outward_from_centroid(m);
  for (int i : surface_nodes(m, "xmin", "box")) EXPECT_DOUBLE_EQ(m.X[3 * i], -1.0);
}

/// Number of nodes strictly inside the unit cube.
int nodes_inside_unit_cube(const BodyMesh& m) {
  int inside = 0;
  for (int i = 0; i < m.num_nodes(); ++i) {
    bool in = true;
    for (int d = 0; d < 3; ++d) in = in && m.X[3 * i + d] > 1e-9 && m.X[3 * i + d] < 1 - 1e-9;
    inside += in;
  }
  return inside;
}

TEST(GenerateBox, DefaultsGiveUnitCube) {
  const BodyMesh m = build_mesh(Teuchos::ParameterList("Mesh"), "", "box");
  EXPECT_NEAR(total_volume(m), 1.0, 1e-12);
  // The boundary nodes are exactly the nodes on the cube's faces.
  const std::size_t boundary_nodes = surface_nodes(m, "boundary", "box").size();
  EXPECT_EQ(static_cast<int>(boundary_nodes), m.num_nodes() - nodes_inside_unit_cube(m));
}

TEST(GenerateBox, IsDeterministic) {
  const BodyMesh a = build_mesh(params("box", 0.2), "", "box");
  const BodyMesh b = build_mesh(params("box", 0.2), "", "box");
  EXPECT_EQ(a.X, b.X);
  EXPECT_EQ(a.tets, b.tets);
  EXPECT_EQ(a.surfaces, b.surfaces);
}

TEST(GenerateCylinder, VolumeAreasAndNormalsOnTiltedAxis) {
  const double r = 0.2, h = 0.5;
  const Vec3 c{0.1, -0.2, 0.3};
  const Vec3 a{1 / std::sqrt(2.0), 1 / std::sqrt(2.0), 0};
  Teuchos::ParameterList p = params("cylinder", 0.05);  // theta = 0.25 on the circle
  p.set("center", arr(c[0], c[1], c[2]));
  p.set("axis", arr(2, 2, 0));  // normalized by build_mesh
  p.set("height", h);
  p.set("radius", r);
  const BodyMesh m = build_mesh(p, "", "cylinder");
  expect_valid_generated(m, {"bottom", "top", "outer"});
  const double v = kPi * r * r * h;
  EXPECT_LT(total_volume(m), v * (1 + 1e-12));  // inscribed: never larger
  EXPECT_NEAR(total_volume(m), v, 0.03 * v);
  EXPECT_NEAR(area(m, m.surfaces.at("bottom")), kPi * r * r, 0.06 * kPi * r * r);
  EXPECT_NEAR(area(m, m.surfaces.at("top")), kPi * r * r, 0.06 * kPi * r * r);
  EXPECT_NEAR(area(m, m.surfaces.at("outer")), 2 * kPi * r * h, 0.06 * 2 * kPi * r * h);
  expect_normals(m, m.surfaces.at("bottom"), {-a[0], -a[1], -a[2]});
  expect_normals(m, m.surfaces.at("top"), a);
  expect_radial_sign(m, m.surfaces.at("outer"), c, a, +1.0);
  expect_outward_from_centroid(m);
  for (int i : surface_nodes(m, "bottom", "cylinder")) {
    EXPECT_NEAR(dot(sub(point(m, i), c), a), 0.0, 1e-12);
  }
  std::cout << "cylinder r 0.2 h 0.5 size 0.05: " << m.num_tets() << " tets, volume error "
            << (total_volume(m) - v) / v << "\n";
}

TEST(GenerateHollowCylinder, VolumeAreasAndNormals) {
  const double ri = 0.1, ro = 0.2, h = 0.3;
  Teuchos::ParameterList p = params("hollow cylinder", 0.04);  // theta = 0.4 on the hole
  p.set("height", h);
  p.set("inner radius", ri);
  p.set("outer radius", ro);
  const BodyMesh m = build_mesh(p, "", "hollow cylinder");
  expect_valid_generated(m, {"bottom", "top", "outer", "inner"});
  const double v = kPi * (ro * ro - ri * ri) * h;
  EXPECT_NEAR(total_volume(m), v, 0.03 * v);
  const double ring = kPi * (ro * ro - ri * ri);
  EXPECT_NEAR(area(m, m.surfaces.at("bottom")), ring, 0.06 * ring);
  EXPECT_NEAR(area(m, m.surfaces.at("top")), ring, 0.06 * ring);
  EXPECT_NEAR(area(m, m.surfaces.at("outer")), 2 * kPi * ro * h, 0.06 * 2 * kPi * ro * h);
  EXPECT_NEAR(area(m, m.surfaces.at("inner")), 2 * kPi * ri * h, 0.06 * 2 * kPi * ri * h);
  const Vec3 c{0, 0, 0}, a{0, 0, 1};
  expect_normals(m, m.surfaces.at("bottom"), {0, 0, -1});
  expect_normals(m, m.surfaces.at("top"), {0, 0, 1});
  expect_radial_sign(m, m.surfaces.at("outer"), c, a, +1.0);
  expect_radial_sign(m, m.surfaces.at("inner"), c, a, -1.0);  // out of the body: to the axis
  for (int i : surface_nodes(m, "inner", "hollow cylinder")) {
    EXPECT_NEAR(std::hypot(m.X[3 * i], m.X[3 * i + 1]), ri, 1e-9);
  }
  std::cout << "hollow cylinder size 0.04: " << m.num_tets() << " tets, volume error "
            << (total_volume(m) - v) / v << "\n";
}

TEST(GenerateSphericalShell, VolumeAreasAndNormals) {
  const double ri = 0.2, ro = 0.4;
  const Vec3 c{1, 2, 3};
  Teuchos::ParameterList p = params("spherical shell", 0.06);  // theta = 0.3 on the inner sphere
  p.set("center", arr(c[0], c[1], c[2]));
  p.set("inner radius", ri);
  p.set("outer radius", ro);
  const BodyMesh m = build_mesh(p, "", "shell");
  expect_valid_generated(m, {"outer", "inner"});
  const double v = 4.0 / 3.0 * kPi * (ro * ro * ro - ri * ri * ri);
  EXPECT_NEAR(total_volume(m), v, 0.03 * v);
  EXPECT_NEAR(area(m, m.surfaces.at("outer")), 4 * kPi * ro * ro, 0.06 * 4 * kPi * ro * ro);
  EXPECT_NEAR(area(m, m.surfaces.at("inner")), 4 * kPi * ri * ri, 0.06 * 4 * kPi * ri * ri);
  for (const Tri& t : m.surfaces.at("outer")) {
    const Vec3 d = sub(centroid(m, t), c);
    ASSERT_GT(dot(unit_normal(m, t), d) / norm(d), 0.9);
  }
  for (const Tri& t : m.surfaces.at("inner")) {
    const Vec3 d = sub(centroid(m, t), c);
    ASSERT_LT(dot(unit_normal(m, t), d) / norm(d), -0.9);
  }
  for (int i : surface_nodes(m, "outer", "shell")) EXPECT_NEAR(norm(sub(point(m, i), c)), ro, 1e-9);
  std::cout << "spherical shell size 0.06: " << m.num_tets() << " tets, volume error "
            << (total_volume(m) - v) / v << "\n";
}

/// Tet counts of the spherical shell (inner 0.2, outer 0.4) for a few sizes, with timings;
/// checks each count within `tolerance` of the expected one (Gmsh 4.8, Debian 12).
void check_shell_counts(const std::vector<std::pair<double, int>>& size_and_count,
                        double tolerance) {
  for (const auto& [size, expected] : size_and_count) {
    Teuchos::ParameterList p = params("spherical shell", size);
    p.set("inner radius", 0.2);
    p.set("outer radius", 0.4);
    const BodyMesh m = build_mesh(p, "", "ball");
    const std::size_t nb = boundary_triangles(m).size();
    std::cout << "spherical shell 0.2/0.4 size " << size << ": " << m.num_tets() << " tets, "
              << m.num_nodes() << " nodes, " << nb << " boundary triangles\n";
    EXPECT_GT(min_volume(m), 0.0);
    EXPECT_NEAR(m.num_tets(), expected, tolerance * expected) << "size " << size;
  }
}

// The ball of the examples: size 0.0524 gives ~8200 tets (0.0523 jumps to ~9200, when the
// circles get one more segment); 0.026 gives ~65k.
TEST(GenerateSphericalShell, TetCountsForSizes) {
  check_shell_counts({{0.1, 1519}, {0.0524, 8154}, {0.026, 65433}}, 0.2);
}

// The ~500k-tet shell (about 17 s, mostly Gmsh's Delaunay): run with
// --gtest_also_run_disabled_tests.
TEST(GenerateSphericalShell, DISABLED_LargeShell) {
  check_shell_counts({{0.0129, 504826}}, 0.2);
}

}  // namespace
}  // namespace emc::mesh::test
