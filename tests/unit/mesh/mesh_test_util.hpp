#pragma once
// Geometric helpers shared by the mesh unit tests.
#include <gtest/gtest.h>
#include <unistd.h>

#include <Teuchos_Array.hpp>
#include <Teuchos_ParameterList.hpp>
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "emcontact/error.hpp"
#include "emcontact/mesh/body_mesh.hpp"
#include "emcontact/mesh/generate.hpp"

namespace emc::mesh::test {

using Vec3 = std::array<double, 3>;
using Tri = std::array<int, 3>;

inline Vec3 point(const BodyMesh& m, int i) {
  return {m.X[3 * i], m.X[3 * i + 1], m.X[3 * i + 2]};
}
inline Vec3 sub(const Vec3& a, const Vec3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline double dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double norm(const Vec3& a) {
  return std::sqrt(dot(a, a));
}

/// (b-a)x(c-a): twice the area times the unit normal.
inline Vec3 area_normal(const BodyMesh& m, const Tri& t) {
  const Vec3 a = point(m, t[0]);
  return cross(sub(point(m, t[1]), a), sub(point(m, t[2]), a));
}

inline Vec3 unit_normal(const BodyMesh& m, const Tri& t) {
  const Vec3 n = area_normal(m, t);
  const double l = norm(n);
  return {n[0] / l, n[1] / l, n[2] / l};
}

inline Vec3 centroid(const BodyMesh& m, const Tri& t) {
  Vec3 c{0, 0, 0};
  for (int k = 0; k < 3; ++k) {
    for (int d = 0; d < 3; ++d) c[d] += m.X[3 * t[k] + d] / 3.0;
  }
  return c;
}

/// The volume-weighted centroid of the body.
inline Vec3 body_centroid(const BodyMesh& m) {
  Vec3 c{0, 0, 0};
  double v = 0.0;
  for (int e = 0; e < m.num_tets(); ++e) {
    const double ve = tet_volume(m, e);
    for (int k = 0; k < 4; ++k) {
      for (int d = 0; d < 3; ++d) c[d] += ve * m.X[3 * m.tets[4 * e + k] + d] / 4.0;
    }
    v += ve;
  }
  return {c[0] / v, c[1] / v, c[2] / v};
}

/// Sum of the tet volumes (Neumaier summation: exact to rounding for 1e5+ tets).
inline double total_volume(const BodyMesh& m) {
  double sum = 0.0, correction = 0.0;
  for (int e = 0; e < m.num_tets(); ++e) {
    const double v = tet_volume(m, e);
    const double t = sum + v;
    correction += std::abs(sum) >= std::abs(v) ? (sum - t) + v : (v - t) + sum;
    sum = t;
  }
  return sum + correction;
}

inline double min_volume(const BodyMesh& m) {
  double v = 1e300;
  for (int e = 0; e < m.num_tets(); ++e) v = std::min(v, tet_volume(m, e));
  return v;
}

inline double area(const BodyMesh& m, const std::vector<Tri>& tris) {
  double a = 0.0;
  for (const Tri& t : tris) a += 0.5 * norm(area_normal(m, t));
  return a;
}

/// True if the triangles form closed, consistently oriented surfaces: every directed edge
/// (a, b) occurs once and its reverse (b, a) occurs once, i.e. every edge is shared by exactly
/// two triangles that traverse it in opposite directions.
inline bool is_closed(const std::vector<Tri>& tris) {
  std::vector<std::pair<int, int>> edges;
  for (const Tri& t : tris) {
    for (int k = 0; k < 3; ++k) edges.emplace_back(t[k], t[(k + 1) % 3]);
  }
  std::sort(edges.begin(), edges.end());
  if (std::adjacent_find(edges.begin(), edges.end()) != edges.end()) return false;
  for (const auto& e : edges) {
    if (!std::binary_search(edges.begin(), edges.end(), std::make_pair(e.second, e.first))) {
      return false;
    }
  }
  return true;
}

/// Triangles as sorted node triples, sorted: for comparing sets regardless of orientation.
inline std::vector<Tri> unoriented(std::vector<Tri> tris) {
  for (Tri& t : tris) std::sort(t.begin(), t.end());
  std::sort(tris.begin(), tris.end());
  return tris;
}

/// The union of all named surfaces, sorted.
inline std::vector<Tri> all_named(const BodyMesh& m) {
  std::vector<Tri> all;
  for (const auto& s : m.surfaces) all.insert(all.end(), s.second.begin(), s.second.end());
  return unoriented(all);
}

inline Teuchos::Array<double> arr(double x, double y, double z) {
  return Teuchos::Array<double>(std::vector<double>{x, y, z});
}

/// Mesh parameters of a built-in `type` with element size `size`.
inline Teuchos::ParameterList params(const std::string& type, double size) {
  Teuchos::ParameterList p("Mesh");
  p.set("type", type);
  p.set("size", size);
  return p;
}

/// The error message of f(where) (a reader or generator call), or "" if it succeeds.
template <class F>
std::string input_error(F&& f, const std::string& where = "input.xml: Bodies/b/Mesh") {
  try {
    f(where);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

/// The error message of build_mesh(p), or "" if it succeeds.
inline std::string build_error(const Teuchos::ParameterList& p,
                               const std::string& where = "input.xml: Bodies/b/Mesh") {
  return input_error([&](const std::string& w) { build_mesh(p, "", w); }, where);
}

/// The error message of read_msh(file, volume), or "" if it succeeds.
inline std::string read_error(const std::string& file, const std::string& volume = "") {
  return input_error([&](const std::string& w) { read_msh(file, volume, w); });
}

/// A fresh scratch directory for one test (removed by the caller's ScratchDir destructor).
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& name)
      : path_(std::filesystem::temp_directory_path() /
              ("emc_test_mesh_" + name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::string dir() const { return path_.string(); }

 private:
  std::filesystem::path path_;
};

}  // namespace emc::mesh::test
