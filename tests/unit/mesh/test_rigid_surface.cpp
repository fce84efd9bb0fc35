// Rigid surface bodies (meshes without tets): the generators `plane` and `rectangle`, and
// triangles-only .msh files (written with the Gmsh API, and by hand).
#include <gmsh.h>
#include <gtest/gtest.h>

#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <fstream>
#include <set>

#include "emcontact/error.hpp"
#include "emcontact/mesh/generate.hpp"
#include "mesh_test_util.hpp"

namespace emc::mesh::test {
namespace {

/// The error message of build_mesh(p) for the body `floor`, or "".
std::string floor_error(const Teuchos::ParameterList& p) {
  return build_error(p, "input.xml: Bodies/floor/Mesh");
}

std::vector<int> all_nodes(const BodyMesh& m) {
  std::vector<int> v(m.num_nodes());
  for (int i = 0; i < m.num_nodes(); ++i) v[i] = i;
  return v;
}

/// What every rigid surface has: no tets, one surface `surface` covering every node, nothing
/// for the tet queries, deterministic sorted triangles.
void expect_rigid(const BodyMesh& m) {
  EXPECT_TRUE(is_rigid(m));
  EXPECT_EQ(m.num_tets(), 0);
  EXPECT_NO_THROW(check_tets(m, "rigid"));
  EXPECT_TRUE(boundary_triangles(m).empty());
  ASSERT_EQ(m.surfaces.count("surface"), 1u);
  const auto& tris = m.surfaces.at("surface");
  EXPECT_TRUE(std::is_sorted(tris.begin(), tris.end()));
  EXPECT_EQ(surface_nodes(m, "surface", "rigid"), all_nodes(m));
  EXPECT_EQ(surface_nodes(m, "boundary", "rigid"), all_nodes(m));
}

/// Every triangle's unit normal (b-a)x(c-a) is `n` (to 1e-12).
void expect_normals(const BodyMesh& m, const std::vector<Tri>& tris, const Vec3& n) {
  for (const Tri& t : tris) {
    const Vec3 u = unit_normal(m, t);
    for (int d = 0; d < 3; ++d) ASSERT_NEAR(u[d], n[d], 1e-12) << d;
  }
}

// ---- plane -----------------------------------------------------------------------------------

TEST(RigidPlane, DefaultsAreTheUnitHalfWidthSquareAtZNormalZ) {
  const BodyMesh m = build_mesh(params("plane", 0.25), "", "plane");
  expect_rigid(m);
  EXPECT_EQ(m.surfaces.size(), 1u);
  EXPECT_EQ(m.num_nodes(), 9 * 9);  // 2 / 0.25 = 8 squares per side
  EXPECT_EQ(m.surfaces.at("surface").size(), 2u * 8 * 8);
  EXPECT_NEAR(area(m, m.surfaces.at("surface")), 4.0, 4e-15);
  expect_normals(m, m.surfaces.at("surface"), {0, 0, 1});
  for (int i = 0; i < m.num_nodes(); ++i) {
    EXPECT_EQ(m.X[3 * i + 2], 0.0);
    EXPECT_LE(std::abs(m.X[3 * i]), 1.0);
    EXPECT_LE(std::abs(m.X[3 * i + 1]), 1.0);
  }
}

TEST(RigidPlane, TiltedAxisIsNormalisedAndCentred) {
  Teuchos::ParameterList p = params("plane", 0.1);
  p.set("center", arr(1, -1, 2));
  p.set("axis", arr(1, 2, 2));  // length 3
  p.set("half width", 0.5);
  const BodyMesh m = build_mesh(p, "", "plane");
  expect_rigid(m);
  EXPECT_EQ(m.num_nodes(), 11 * 11);
  EXPECT_EQ(m.surfaces.at("surface").size(), 200u);
  EXPECT_NEAR(area(m, m.surfaces.at("surface")), 1.0, 1e-13);
  const Vec3 n{1.0 / 3, 2.0 / 3, 2.0 / 3}, c{1, -1, 2};
  expect_normals(m, m.surfaces.at("surface"), n);
  Vec3 mean{0, 0, 0};
  for (int i = 0; i < m.num_nodes(); ++i) {
    const Vec3 d = sub(point(m, i), c);
    EXPECT_NEAR(dot(d, n), 0.0, 1e-14);                      // in the plane
    EXPECT_LE(norm(d), 0.5 * std::sqrt(2.0) * (1 + 1e-14));  // inside the square
    for (int k = 0; k < 3; ++k) mean[k] += d[k] / m.num_nodes();
  }
  EXPECT_LT(norm(mean), 1e-14);  // centred at `center`
}

TEST(RigidPlane, NegativeAxisFlipsTheNormals) {
  Teuchos::ParameterList p = params("plane", 0.5);
  p.set("axis", arr(0, 0, -3));
  const BodyMesh m = build_mesh(p, "", "plane");
  expect_normals(m, m.surfaces.at("surface"), {0, 0, -1});
  EXPECT_NEAR(area(m, m.surfaces.at("surface")), 4.0, 4e-15);
  p.set("axis", arr(-1, 0, 0));
  expect_normals(build_mesh(p, "", "plane"), m.surfaces.at("surface"), {-1, 0, 0});
}

TEST(RigidPlane, SizeAboveTheSquareGivesTwoTriangles) {
  Teuchos::ParameterList p = params("plane", 5.0);
  const BodyMesh m = build_mesh(p, "", "plane");
  EXPECT_EQ(m.num_nodes(), 4);
  EXPECT_EQ(m.surfaces.at("surface").size(), 2u);
  EXPECT_NEAR(area(m, m.surfaces.at("surface")), 4.0, 4e-15);
}

TEST(RigidPlane, HugeHalfWidthIsCappedAt200By200Squares) {
  Teuchos::ParameterList p = params("plane", 1e-3);
  p.set("half width", 1e3);
  const BodyMesh m = build_mesh(p, "", "plane");
  EXPECT_EQ(m.num_nodes(), 201 * 201);
  EXPECT_EQ(m.surfaces.at("surface").size(), 2u * 200 * 200);
  EXPECT_NEAR(area(m, m.surfaces.at("surface")), 4e6, 4e6 * 1e-12);
  expect_normals(m, m.surfaces.at("surface"), {0, 0, 1});
}

TEST(RigidPlane, BadParametersAreRefused) {
  Teuchos::ParameterList p = params("plane", 0.1);
  p.set("axis", arr(0, 0, 0));
  EXPECT_NE(floor_error(p).find("'axis' must be a nonzero vector"), std::string::npos);
  p = params("plane", 0.1);
  p.set("half width", -1.0);
  EXPECT_NE(floor_error(p).find("half width"), std::string::npos) << floor_error(p);
}

TEST(RigidPlane, GridCellsAreCappedForAnyAspectRatio) {
  for (const auto& [l1, l2, h] : std::vector<std::array<double, 3>>{
           {1e6, 1e-3, 1e-3}, {2.0, 2.0, 1e-9}, {1.0, 1.0, 0.1}, {1e300, 1e300, 1e-300}}) {
    const auto n = grid_cells(l1, l2, h);
    EXPECT_GE(n[0], 1);
    EXPECT_GE(n[1], 1);
    EXPECT_LE(static_cast<double>(n[0]) * n[1], 40000.0) << l1 << " " << l2 << " " << h;
  }
  EXPECT_EQ(grid_cells(1.0, 1.0, 0.1), (std::array<int, 2>{10, 10}));
  EXPECT_EQ(grid_cells(2.0, 2.0, 1e-9), (std::array<int, 2>{200, 200}));
}

// ---- rectangle -------------------------------------------------------------------------------

TEST(RigidRectangle, HorizontalWithDefaultAxis) {
  Teuchos::ParameterList p = params("rectangle", 0.25);
  p.set("lower corner", arr(0, 0, 0.5));
  p.set("upper corner", arr(2, 1, 0.5));
  const BodyMesh m = build_mesh(p, "", "rect");
  expect_rigid(m);
  EXPECT_EQ(m.num_nodes(), 9 * 5);
  EXPECT_EQ(m.surfaces.at("surface").size(), 2u * 8 * 4);
  EXPECT_NEAR(area(m, m.surfaces.at("surface")), 2.0, 2e-15);
  expect_normals(m, m.surfaces.at("surface"), {0, 0, 1});
  for (int i = 0; i < m.num_nodes(); ++i) EXPECT_EQ(m.X[3 * i + 2], 0.5);
  p.set("axis", arr(0, 0, -1));
  const BodyMesh down = build_mesh(p, "", "rect");
  expect_normals(down, down.surfaces.at("surface"), {0, 0, -1});
  EXPECT_NEAR(area(down, down.surfaces.at("surface")), 2.0, 2e-15);
}

TEST(RigidRectangle, EveryOrientation) {
  const char* names = "xyz";
  for (int d = 0; d < 3; ++d) {
    for (double sign : {1.0, -1.0}) {
      Teuchos::ParameterList p = params("rectangle", 0.5);
      Vec3 lo{-1, 0, 1}, hi{1, 2, 4};
      hi[d] = lo[d];
      p.set("lower corner", arr(lo[0], lo[1], lo[2]));
      p.set("upper corner", arr(hi[0], hi[1], hi[2]));
      Vec3 n{0, 0, 0};
      n[d] = sign;
      p.set("axis", arr(2 * n[0], 2 * n[1], 2 * n[2]));
      const BodyMesh m = build_mesh(p, "", "rect");
      SCOPED_TRACE(std::string(1, names[d]) + (sign > 0 ? "+" : "-"));
      expect_rigid(m);
      double expected = 1.0;
      int cells = 1;
      for (int k = 0; k < 3; ++k) {
        if (k == d) continue;
        expected *= hi[k] - lo[k];
        cells *= static_cast<int>(std::ceil((hi[k] - lo[k]) / 0.5));
      }
      EXPECT_EQ(m.surfaces.at("surface").size(), 2u * cells);
      EXPECT_NEAR(area(m, m.surfaces.at("surface")), expected, 1e-14 * expected);
      expect_normals(m, m.surfaces.at("surface"), n);
      for (int i = 0; i < m.num_nodes(); ++i) {
        for (int k = 0; k < 3; ++k) {
          EXPECT_GE(m.X[3 * i + k], lo[k]);
          EXPECT_LE(m.X[3 * i + k], hi[k]);
        }
      }
    }
  }
}

TEST(RigidRectangle, BadCornersAndAxisAreRefused) {
  Teuchos::ParameterList p = params("rectangle", 0.1);  // default corners: a unit box
  std::string msg = floor_error(p);
  EXPECT_NE(msg.find("input.xml: Bodies/floor/Mesh: type 'rectangle': 'upper corner' - 'lower "
                     "corner' is {1, 1, 1}; it must be zero in exactly one component"),
            std::string::npos)
      << msg;
  p.set("upper corner", arr(1, 0, 0));  // a segment
  EXPECT_NE(floor_error(p).find("is {1, 0, 0}; it must be zero in exactly one"), std::string::npos)
      << floor_error(p);
  p.set("upper corner", arr(1, -1, 0));  // negative extent
  EXPECT_NE(floor_error(p).find("positive in the other two"), std::string::npos);
  p.set("upper corner", arr(0, 1, 1));  // normal x, default axis z
  msg = floor_error(p);
  EXPECT_NE(msg.find("parameter 'axis' {0, 0, 1} must be parallel to the rectangle's normal "
                     "direction x"),
            std::string::npos)
      << msg;
  EXPECT_NE(msg.find("{1, 0, 0} or {-1, 0, 0}"), std::string::npos) << msg;
  p.set("axis", arr(1, 0.1, 0));  // not parallel
  EXPECT_NE(floor_error(p).find("must be parallel"), std::string::npos);
  p.set("axis", arr(0, 0, 0));
  EXPECT_NE(floor_error(p).find("must be parallel"), std::string::npos);
  p.set("axis", arr(-1, 0, 0));
  EXPECT_EQ(floor_error(p), "");
}

// Through the validator of Mesh/type, as the input schema reads it.
TEST(RigidTypes, OnlyPlaneAndRectangleAreRigidTypes) {
  for (const char* t :
       {"plane", "rectangle", "box", "cylinder", "hollow cylinder", "spherical shell", "file"}) {
    Teuchos::ParameterList p;
    p.set("type", std::string(t));
    p.validateParametersAndSetDefaults(*valid_mesh_parameters());
    const bool rigid = std::string(t) == "plane" || std::string(t) == "rectangle";
    EXPECT_EQ(is_rigid_surface_type(Teuchos::getIntegralValue<MeshType>(p, "type")), rigid) << t;
  }
}

// ---- triangles-only .msh files ---------------------------------------------------------------

/// What the test asked Gmsh to write: the triangles (Gmsh node tags, 3 each) of the physical
/// surfaces "up" ([0,1]x[0,1] at z = 0) and "down" ([1,2]x[0,1] at z = 0, mesh reversed), and
/// every node's coordinates.
struct WrittenSurface {
  std::vector<std::size_t> up, down;
  std::map<std::size_t, Vec3> coords;
};

WrittenSurface write_surface_msh(const std::string& file, bool binary = false) {
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::model::add("rigid");
  const int up = gmsh::model::occ::addRectangle(0, 0, 0, 1, 1);
  const int down = gmsh::model::occ::addRectangle(1, 0, 0, 1, 1);
  gmsh::model::occ::synchronize();
  gmsh::model::setPhysicalName(2, gmsh::model::addPhysicalGroup(2, {up}, 1), "up");
  gmsh::model::setPhysicalName(2, gmsh::model::addPhysicalGroup(2, {down}, 2), "down");
  gmsh::model::mesh::setReverse(2, down);
  gmsh::option::setNumber("Mesh.MeshSizeMax", 0.3);
  gmsh::model::mesh::generate(2);
  WrittenSurface w;
  std::vector<std::size_t> tags, node_tags;
  gmsh::model::mesh::getElementsByType(2, tags, w.up, up);
  std::vector<std::size_t> tags2;
  gmsh::model::mesh::getElementsByType(2, tags2, w.down, down);
  std::vector<double> xyz, params;
  gmsh::model::mesh::getNodes(node_tags, xyz, params, -1, -1, false, false);
  for (std::size_t i = 0; i < node_tags.size(); ++i) {
    w.coords[node_tags[i]] = {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
  }
  gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
  gmsh::option::setNumber("Mesh.Binary", binary ? 1 : 0);
  gmsh::write(file);
  gmsh::finalize();
  return w;
}

/// A triangle by its node coordinates, in order.
using Points = std::array<Vec3, 3>;

Vec3 centroid_of(const Points& t) {
  return {(t[0][0] + t[1][0] + t[2][0]) / 3, (t[0][1] + t[1][1] + t[2][1]) / 3,
          (t[0][2] + t[1][2] + t[2][2]) / 3};
}

/// Every triangle of `expected` is in `got` with the same orientation, and nothing else: the
/// triangles are matched by their centroid and compared up to a rotation of their nodes (the
/// coordinates to 1e-12: Gmsh writes 16 digits).
void expect_same_oriented(const std::vector<Points>& got, const std::vector<Points>& expected) {
  ASSERT_EQ(got.size(), expected.size());
  for (const Points& e : expected) {
    const Vec3 c = centroid_of(e);
    const auto it = std::find_if(got.begin(), got.end(), [&](const Points& g) {
      return norm(sub(centroid_of(g), c)) < 1e-12;
    });
    ASSERT_NE(it, got.end());
    bool rotation = false;
    for (int k = 0; k < 3 && !rotation; ++k) {
      rotation = true;
      for (int i = 0; i < 3; ++i)
        rotation = rotation && norm(sub((*it)[(i + k) % 3], e[i])) < 1e-12;
    }
    ASSERT_TRUE(rotation) << "a triangle was re-oriented";
  }
}

std::vector<Points> points(const BodyMesh& m, const std::vector<Tri>& tris) {
  std::vector<Points> out;
  for (const Tri& t : tris) out.push_back({point(m, t[0]), point(m, t[1]), point(m, t[2])});
  return out;
}

std::vector<Points> points(const WrittenSurface& w, const std::vector<std::size_t>& nodes) {
  std::vector<Points> out;
  for (std::size_t i = 0; i + 2 < nodes.size(); i += 3)
    out.push_back({w.coords.at(nodes[i]), w.coords.at(nodes[i + 1]), w.coords.at(nodes[i + 2])});
  return out;
}

TEST(RigidMsh, TrianglesOnlyFileWrittenByGmshIsARigidSurface) {
  ScratchDir dir("rigid_msh");
  const std::string file = dir.file("floor.msh");
  const WrittenSurface w = write_surface_msh(file);
  const BodyMesh m = read_msh(file, "", "test");
  expect_rigid(m);
  EXPECT_EQ(m.surfaces.size(), 3u);  // up, down, surface
  ASSERT_EQ(m.surfaces.count("up"), 1u);
  ASSERT_EQ(m.surfaces.count("down"), 1u);
  EXPECT_EQ(m.surfaces.at("up").size() + m.surfaces.at("down").size(),
            m.surfaces.at("surface").size());
  std::set<std::size_t> nodes;  // the nodes of the triangles, no others
  for (const auto& t : {w.up, w.down}) nodes.insert(t.begin(), t.end());
  EXPECT_EQ(static_cast<std::size_t>(m.num_nodes()), nodes.size());
  // Same oriented triangles as written (not re-oriented).
  expect_same_oriented(points(m, m.surfaces.at("up")), points(w, w.up));
  expect_same_oriented(points(m, m.surfaces.at("down")), points(w, w.down));
  EXPECT_NEAR(area(m, m.surfaces.at("up")), 1.0, 1e-14);
  EXPECT_NEAR(area(m, m.surfaces.at("surface")), 2.0, 1e-14);
  // Gmsh meshes the OCC rectangle with normal +z; the reversed one has -z.
  const double up_z = unit_normal(m, m.surfaces.at("up")[0])[2];
  EXPECT_NEAR(std::abs(up_z), 1.0, 1e-12);
  expect_normals(m, m.surfaces.at("up"), {0, 0, up_z});
  expect_normals(m, m.surfaces.at("down"), {0, 0, -up_z});
  // Through build_mesh (type file), and a `volume` is still required to exist.
  Teuchos::ParameterList p("Mesh");
  p.set("type", std::string("file"));
  p.set("file", std::string("floor.msh"));
  EXPECT_EQ(build_mesh(p, dir.dir(), "input.xml: Bodies/floor/Mesh").surfaces, m.surfaces);
  try {
    read_msh(file, "solid", "input.xml: Bodies/floor/Mesh");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no physical volume 'solid'"), std::string::npos)
        << e.what();
  }
}

TEST(RigidMsh, BinaryTrianglesOnlyFileGivesTheSameSurfaceAsAscii) {
  ScratchDir dir("rigid_binary");
  write_surface_msh(dir.file("ascii.msh"));
  write_surface_msh(dir.file("binary.msh"), true);
  const BodyMesh a = read_msh(dir.file("ascii.msh"), "", "test");
  const BodyMesh b = read_msh(dir.file("binary.msh"), "", "test");
  expect_rigid(b);
  EXPECT_EQ(b.surfaces, a.surfaces);
  ASSERT_EQ(b.X.size(), a.X.size());
  for (std::size_t i = 0; i < a.X.size(); ++i) EXPECT_NEAR(b.X[i], a.X[i], 1e-15);  // 16 digits
}

void write_text(const std::string& file, const std::string& text) {
  std::ofstream(file) << text;
}

/// A hand-written .msh 4.1 file: nodes 1..5, the elements `elements` ($Elements body).
std::string flat_msh(const std::string& elements) {
  return "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
         "$PhysicalNames\n1\n2 1 \"side\"\n$EndPhysicalNames\n"
         "$Entities\n0 1 1 0\n"
         "1 0 0 0 0 1 1 0 0\n"
         "1 0 0 0 0 1 1 1 1 0\n"
         "$EndEntities\n"
         "$Nodes\n1 5 1 5\n2 1 0 5\n1\n2\n3\n4\n5\n"
         "0 0 0\n1 0 0\n0 1 0\n0 0 1\n0 0 -1\n$EndNodes\n"
         "$Elements\n" +
         elements + "$EndElements\n";
}

TEST(RigidMsh, HandWrittenTriangleKeepsItsOrientation) {
  ScratchDir dir("rigid_hand");
  // One triangle (nodes 1, 3, 4: normal +x as written); nodes 2 and 5 are unused.
  write_text(dir.file("flat.msh"), flat_msh("1 1 1 1\n2 1 2 1\n1 1 3 4\n"));
  const BodyMesh m = read_msh(dir.file("flat.msh"), "", "test");
  expect_rigid(m);
  ASSERT_EQ(m.num_nodes(), 3);
  EXPECT_EQ(m.X, (std::vector<double>{0, 0, 0, 0, 1, 0, 0, 0, 1}));
  EXPECT_EQ(m.surfaces.at("side"), (std::vector<Tri>{{0, 1, 2}}));
  EXPECT_EQ(m.surfaces.at("surface"), (std::vector<Tri>{{0, 1, 2}}));
  expect_normals(m, m.surfaces.at("side"), {1, 0, 0});
  // Written the other way round (1, 4, 3): normal -x, kept.
  write_text(dir.file("flipped.msh"), flat_msh("1 1 1 1\n2 1 2 1\n1 1 4 3\n"));
  const BodyMesh f = read_msh(dir.file("flipped.msh"), "", "test");
  expect_normals(f, f.surfaces.at("side"), {-1, 0, 0});
}

TEST(RigidMsh, FileWithoutTetsOrTrianglesAndDegenerateTrianglesAreRefused) {
  ScratchDir dir("rigid_bad");
  // Only a line element (on curve 1): neither tets nor triangles.
  write_text(dir.file("line.msh"), flat_msh("1 1 1 1\n1 1 1 1\n1 1 2\n"));
  std::string msg = read_error(dir.file("line.msh"));
  EXPECT_NE(msg.find("no 4-node tetrahedra and no triangles"), std::string::npos) << msg;
  EXPECT_NE(msg.find("gmsh -2"), std::string::npos) << msg;
  // A triangle with all three nodes on a line.
  write_text(dir.file("degenerate.msh"), flat_msh("1 2 1 2\n2 1 2 2\n1 1 3 4\n2 1 2 1\n"));
  msg = read_error(dir.file("degenerate.msh"));
  EXPECT_NE(msg.find("element 2 is a degenerate triangle"), std::string::npos) << msg;
  // A quadrangle.
  write_text(dir.file("quad.msh"), flat_msh("1 1 1 1\n2 1 3 1\n1 1 2 3 4\n"));
  msg = read_error(dir.file("quad.msh"));
  EXPECT_NE(msg.find("only 3-node triangles"), std::string::npos) << msg;
  // A triangle on a node the file does not have, and one with a missing node.
  write_text(dir.file("ref.msh"), flat_msh("1 1 1 1\n2 1 2 1\n1 1 3 6\n"));
  msg = read_error(dir.file("ref.msh"));
  EXPECT_NE(msg.find("ref.msh': line 30 ($Elements): element 1 refers to node 6, which is not "
                     "in $Nodes"),
            std::string::npos)
      << msg;
  write_text(dir.file("short.msh"), flat_msh("1 1 1 1\n2 1 2 1\n1 1 3\n"));
  msg = read_error(dir.file("short.msh"));
  EXPECT_NE(msg.find("line 30 ($Elements): expected a node tag of the element"), std::string::npos)
      << msg;
}

}  // namespace
}  // namespace emc::mesh::test
