// BodyMesh queries on hand-made meshes: volumes, element checks, boundary triangles, surfaces.
#include <gtest/gtest.h>

#include <iostream>

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
    EXPECT_NE(msg.find("where: element 2 is degenerate (volume 0, mean"), std::string::npos) << msg;
  }
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
