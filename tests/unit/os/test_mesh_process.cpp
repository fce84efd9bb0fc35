// The meshes built in a child process (src/os/mesh_process.cpp): what the child builds arrives
// whole, its memory is not the parent's, and its failures are reported as the parent's errors.
#include <gtest/gtest.h>

#include <csignal>
#include <cstring>
#include <string>
#include <vector>

#include "emcontact/error.hpp"
#include "emcontact/os/memory.hpp"
#include "emcontact/os/mesh_process.hpp"

namespace emc::os {
namespace {

mesh::BodyMesh two_tets(double shift) {
  mesh::BodyMesh m;
  m.X = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
  for (double& x : m.X) x += shift;
  m.tets = {0, 1, 2, 3, 1, 2, 3, 4};
  m.surfaces["bottom"] = {{0, 2, 1}};
  m.surfaces["top"] = {{1, 2, 4}, {2, 3, 4}};
  return m;
}

bool same(const mesh::BodyMesh& a, const mesh::BodyMesh& b) {
  return a.X == b.X && a.tets == b.tets && a.surfaces == b.surfaces;
}

TEST(MeshProcess, TheChildsMeshesArriveWhole) {
  std::vector<mesh::BodyMesh> want = {two_tets(0), mesh::BodyMesh{}, two_tets(0.5)};
  want[1].X = {0, 0, 0, 1, 0, 0, 0, 1, 0};  // a rigid surface: no tets
  want[1].surfaces["surface"] = {{0, 1, 2}};
  const auto got = build_in_child_process([&] { return want; });
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t b = 0; b < want.size(); ++b) EXPECT_TRUE(same(got[b], want[b])) << b;
}

TEST(MeshProcess, ALargeMeshArrivesWhole) {  // more than a pipe's buffer (64 kB)
  mesh::BodyMesh m;
  for (int k = 0; k < 3 * 400000; ++k) m.X.push_back(1e-3 * k);
  for (int k = 0; k < 4 * 300000; ++k) m.tets.push_back(k % 400000);
  const auto got = build_in_child_process([&] { return std::vector<mesh::BodyMesh>{m}; });
  ASSERT_EQ(got.size(), 1u);
  EXPECT_TRUE(same(got[0], m));
}

// The child touches 400 MiB (a mesher's peak) and returns a small mesh: the parent's peak
// resident size grows by far less (the pipe's data and the mesh: well under 50 MiB).
TEST(MeshProcess, TheChildsMemoryIsNotTheParents) {
  const double before = peak_resident_bytes();
  const auto got = build_in_child_process([] {
    std::vector<char> peak(std::size_t(400) << 20);
    std::memset(peak.data(), 1, peak.size());
    volatile char sink = peak[peak.size() / 2];
    (void)sink;
    return std::vector<mesh::BodyMesh>{two_tets(0)};
  });
  EXPECT_EQ(got.size(), 1u);
  EXPECT_LT(peak_resident_bytes() - before, 50.0 * (1 << 20));
}

TEST(MeshProcess, AnErrorInTheChildIsThrownWithItsMessage) {
  try {
    build_in_child_process([]() -> std::vector<mesh::BodyMesh> {
      throw InputError("in.xml: Bodies/a/Mesh: the mesh file has no tetrahedra");
    });
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "in.xml: Bodies/a/Mesh: the mesh file has no tetrahedra");
  }
}

TEST(MeshProcess, AKilledChildIsNamedWithItsSignal) {
  try {
    build_in_child_process([]() -> std::vector<mesh::BodyMesh> {
      std::raise(SIGKILL);  // as the kernel's out-of-memory killer would
      return {};
    });
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("killed by signal 9"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("out-of-memory killer"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace emc::os
