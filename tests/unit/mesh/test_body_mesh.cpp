// BodyMesh queries on hand-made meshes: volumes, element checks, boundary triangles, surfaces.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "emcontact/error.hpp"
#include "emcontact/mesh/body_mesh.hpp"
#include "mesh_test_util.hpp"

namespace emc::mesh::test {
namespace {

/// Two unit right tets sharing the face z = 0: {0,1,2,3} above, {0,2,1,4} below.
BodyMesh two_tets() {
  BodyMesh m;
  m.X = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1};
  m.tets = {0, 1, 2, 3, 0, 2, 1, 4};
  return m;
}

/// The unit cube [0,n]^3 cut into n^3 cells of 6 Kuhn tets each (a conforming mesh).
BodyMesh kuhn_cube(int n) {
  BodyMesh m;
  const auto id = [n](int i, int j, int k) { return (k * (n + 1) + j) * (n + 1) + i; };
  for (int k = 0; k <= n; ++k) {
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) {
        for (double x : {i, j, k}) m.X.push_back(x);
      }
    }
  }
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        for (const auto& p : perms) {
          int c[3] = {i, j, k};
          std::array<int, 4> t{id(i, j, k), 0, 0, 0};
          for (int s = 0; s < 3; ++s) {
            ++c[p[s]];
            t[s + 1] = id(c[0], c[1], c[2]);
          }
          if ((p[0] + 1) % 3 != p[1]) std::swap(t[2], t[3]);  // odd permutation: fix the sign
          m.tets.insert(m.tets.end(), t.begin(), t.end());
        }
      }
    }
  }
  return m;
}

TEST(BodyMesh, TetVolumeIsSignedSixthOfTripleProduct) {
  BodyMesh m = two_tets();
  EXPECT_DOUBLE_EQ(tet_volume(m, 0), 1.0 / 6.0);
  EXPECT_DOUBLE_EQ(tet_volume(m, 1), 1.0 / 6.0);
  std::swap(m.tets[2], m.tets[3]);
  EXPECT_DOUBLE_EQ(tet_volume(m, 0), -1.0 / 6.0);
  EXPECT_EQ(m.num_nodes(), 5);
  EXPECT_EQ(m.num_tets(), 2);
}

TEST(BodyMesh, CheckTetsAcceptsValidMesh) {
  EXPECT_NO_THROW(check_tets(two_tets(), "here"));
}

TEST(BodyMesh, CheckTetsRefusesInvertedTetWithOneBasedId) {
  BodyMesh m = two_tets();
  std::swap(m.tets[5], m.tets[6]);  // tet 2 (1-based) inverted
  try {
    check_tets(m, "input.xml: Bodies/b/Mesh");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("input.xml: Bodies/b/Mesh: element 2 is inverted (volume -0.166667)"),
              std::string::npos)
        << msg;
    EXPECT_NE(msg.find("positive volume"), std::string::npos) << msg;
  }
}

TEST(BodyMesh, CheckTetsNamesElementByGivenId) {
  BodyMesh m = two_tets();
  std::swap(m.tets[5], m.tets[6]);
  try {
    check_tets(m, "f.msh", {17, 42});
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("f.msh: element 42 is inverted"), std::string::npos)
        << e.what();
  }
}

TEST(BodyMesh, CheckTetsRefusesDegenerateTet) {
  BodyMesh m = two_tets();
  m.X[14] = 0.0;  // node 4 moves into the plane z = 0: tet 2 is flat
  try {
    check_tets(m, "where");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("where: element 2 is degenerate (volume 0, median"), std::string::npos)
        << msg;
  }
}

/// The InputError message of f(), "" if none.
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

/// The 0-based index of node (i, j, k) of kuhn_cube(n).
int cube_node(int n, int i, int j, int k) {
  return (k * (n + 1) + j) * (n + 1) + i;
}

TEST(BodyMesh, ValidMeshPassesEveryCheck) {
  const BodyMesh m = kuhn_cube(3);
  EXPECT_EQ(error_of([&] { check_tets(m, "w"); }), "");
  EXPECT_EQ(error_of([&] { check_nodes(m, "w", {}); }), "");
  EXPECT_EQ(error_of([&] { check_distinct_tets(m, "w", {}); }), "");
}

// One node far away makes its tets huge: the others are not degenerate (the median volume, not
// the mean, is the scale), the huge ones are flat, and check_nodes names the node itself.
TEST(BodyMesh, FarNodeIsNamedAndNormalElementsAreNotBlamed) {
  BodyMesh m = kuhn_cube(3);
  const int far = cube_node(3, 3, 3, 3);
  m.X[3 * far] = 1e15;
  std::string msg = error_of([&] { check_tets(m, "w"); });
  ASSERT_NE(msg.find(" is flat"), std::string::npos) << msg;
  const int e = std::stoi(msg.substr(msg.find("element ") + 8)) - 1;
  EXPECT_NE(std::find(&m.tets[4 * e], &m.tets[4 * e] + 4, far), &m.tets[4 * e] + 4)
      << "element " << e + 1 << " does not hold the far node: " << msg;
  msg = error_of([&] { check_nodes(m, "w", {}); });
  EXPECT_NE(msg.find("w: node " + std::to_string(far + 1) +
                     " lies 1e+15 from the mesh's median "
                     "node position, more than 1e9 times the median longest edge"),
            std::string::npos)
      << msg;
  m.X[3 * far] = 1e308;  // beyond kMaxCoordinate, named by its id
  msg = error_of([&] { check_nodes(m, "w", std::vector<std::size_t>(m.num_nodes(), 77)); });
  EXPECT_NE(msg.find("w: node 77 has the coordinate x = 1e+308; coordinates must be finite "
                     "numbers of magnitude at most 1e30"),
            std::string::npos)
      << msg;
}

TEST(BodyMesh, SquashedMeshIsFlat) {
  BodyMesh m = kuhn_cube(2);
  for (int n = 0; n < m.num_nodes(); ++n) m.X[3 * n + 2] *= 1e-9;
  const std::string msg = error_of([&] { check_tets(m, "w"); });
  EXPECT_NE(msg.find("w: element 1 is flat (its volume is "), std::string::npos) << msg;
  EXPECT_NE(msg.find("every tetrahedron must reach 1e-6 of it"), std::string::npos) << msg;
  for (int n = 0; n < m.num_nodes(); ++n) m.X[3 * n + 2] *= 1e4;  // 1e-5: thin, but solvable
  EXPECT_EQ(error_of([&] { check_tets(m, "w"); }), "");
}

TEST(BodyMesh, RepeatedTetIsRefusedNamingBothElements) {
  BodyMesh m = kuhn_cube(2);
  const int n = m.num_tets();
  const int* t = &m.tets[4 * 5];
  const std::vector<int> again{t[1], t[0], t[3], t[2]};  // the same nodes, an even permutation
  m.tets.insert(m.tets.end(), again.begin(), again.end());
  std::vector<std::size_t> ids(n + 1);
  for (int e = 0; e <= n; ++e) ids[e] = 100 + e;
  EXPECT_EQ(error_of([&] { check_tets(m, "w", ids); }), "");  // a valid tet on its own
  const std::string msg = error_of([&] { check_distinct_tets(m, "w", ids); });
  EXPECT_NE(msg.find("w: elements 105 and " + std::to_string(100 + n) + " have the same 4 nodes"),
            std::string::npos)
      << msg;
}

TEST(BodyMesh, SecondCopyOnOtherNodesIsRefused) {
  BodyMesh m = kuhn_cube(2);
  const int nodes = m.num_nodes(), tets = m.num_tets();
  m.X.insert(m.X.end(), m.X.begin(), m.X.end());
  for (int k = 0; k < 4 * tets; ++k) m.tets.push_back(m.tets[k] + nodes);
  EXPECT_EQ(error_of([&] { check_tets(m, "w"); }), "");
  const std::string msg = error_of([&] { check_distinct_tets(m, "w", {}); });
  ASSERT_NE(msg.find(" lie on the same 4 points through different nodes"), std::string::npos)
      << msg;
  int a = 0, b = 0;  // a tet and its copy
  ASSERT_EQ(std::sscanf(msg.c_str(), "w: elements %d and %d", &a, &b), 2) << msg;
  EXPECT_EQ(b - a, tets) << msg;
  // a crack (nodes doubled along a face, no tet repeated) is not refused
  BodyMesh crack = two_tets();
  crack.X.insert(crack.X.end(), {0, 0, 0});  // node 5: a copy of node 0 for the lower tet
  crack.tets[4] = 5;
  EXPECT_EQ(error_of([&] { check_distinct_tets(crack, "w", {}); }), "");
}

TEST(BodyMesh, BoundaryOfOneTetIsItsFourOutwardFaces) {
  BodyMesh m;
  m.X = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  m.tets = {0, 1, 2, 3};
  const auto b = boundary_triangles(m);
  ASSERT_EQ(b.size(), 4u);
  const Vec3 c{0.25, 0.25, 0.25};
  for (const Tri& t : b) EXPECT_GT(dot(area_normal(m, t), sub(centroid(m, t), c)), 0.0);
  EXPECT_TRUE(is_closed(b));
  EXPECT_NEAR(area(m, b), 1.5 + std::sqrt(3.0) / 2.0, 1e-14);
}

TEST(BodyMesh, BoundaryOrientationDoesNotDependOnTetOrientation) {
  BodyMesh m = two_tets();
  const auto expected = boundary_triangles(m);
  std::swap(m.tets[0], m.tets[1]);  // invert both tets: the boundary is geometric
  std::swap(m.tets[4], m.tets[5]);
  EXPECT_EQ(boundary_triangles(m), expected);
}

TEST(BodyMesh, BoundaryExcludesSharedFaceAndIsSorted) {
  const BodyMesh m = two_tets();
  const auto b = boundary_triangles(m);
  ASSERT_EQ(b.size(), 6u);
  EXPECT_TRUE(std::is_sorted(b.begin(), b.end()));
  for (const Tri& t : b) {
    EXPECT_EQ(t[0], *std::min_element(t.begin(), t.end()));  // canonical rotation
    EXPECT_NE(unoriented({t})[0], (Tri{0, 1, 2}));           // the shared face
    EXPECT_GT(dot(area_normal(m, t), sub(centroid(m, t), Vec3{0.2, 0.2, 0})), 0.0);
  }
  EXPECT_TRUE(is_closed(b));
}

TEST(BodyMesh, BoundaryOfLargeStructuredCubeIsFastAndClosed) {
  const int n = 30;  // 162000 tets
  const BodyMesh m = kuhn_cube(n);
  ASSERT_GT(min_volume(m), 0.0);
  EXPECT_NEAR(total_volume(m), double(n) * n * n, 1e-12 * n * n * n);
  const auto b = boundary_triangles(m);  // (its speed is measured in perf/, not here)
  EXPECT_EQ(b.size(), 12u * n * n);
  EXPECT_TRUE(is_closed(b));
  EXPECT_NEAR(area(m, b), 6.0 * n * n, 1e-6);
  const Vec3 c{n / 2.0, n / 2.0, n / 2.0};
  for (const Tri& t : b) ASSERT_GT(dot(area_normal(m, t), sub(centroid(m, t), c)), 0.0);
}

TEST(BodyMesh, SurfaceNodesOfNamedSurfaceAndBoundary) {
  BodyMesh m = two_tets();
  m.surfaces["side"] = {{0, 4, 2}, {0, 3, 2}};
  EXPECT_EQ(surface_nodes(m, "side", "w"), (std::vector<int>{0, 2, 3, 4}));
  EXPECT_EQ(surface_nodes(m, "boundary", "w"), (std::vector<int>{0, 1, 2, 3, 4}));
}

TEST(BodyMesh, SurfaceNodesRefusesUnknownNameListingAvailableOnes) {
  BodyMesh m = two_tets();
  m.surfaces["side"] = {{0, 4, 2}};
  try {
    surface_nodes(m, "top", "input.xml: Dirichlet/fix");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("input.xml: Dirichlet/fix: unknown surface 'top'"), std::string::npos);
    EXPECT_NE(msg.find("'side'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'boundary'"), std::string::npos) << msg;
  }
}

}  // namespace
}  // namespace emc::mesh::test
