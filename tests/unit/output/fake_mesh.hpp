#pragma once
// A fake structured tetrahedral mesh and fake fields, for output tests and timings: k^3 cubes of
// the unit cube, each split into 6 tetrahedra (Kuhn), so (k+1)^3 nodes and 6 k^3 tets.
#include <array>
#include <cmath>
#include <vector>

#include "emcontact/output/fields.hpp"

namespace emc::output::testing {

struct FakeMesh {
  std::vector<double> X;        // 3 per node
  std::vector<long long> tets;  // 4 per tet, 0-based
  std::vector<int> body;        // 1 per tet
  long long num_nodes() const { return static_cast<long long>(X.size() / 3); }
  long long num_tets() const { return static_cast<long long>(body.size()); }
};

inline FakeMesh make_fake_mesh(int k) {
  FakeMesh m;
  const int n = k + 1;
  auto id = [n](int i, int j, int l) { return (static_cast<long long>(l) * n + j) * n + i; };
  for (int l = 0; l < n; ++l) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        m.X.insert(m.X.end(), {double(i) / k, double(j) / k, double(l) / k});
      }
    }
  }
  // The 6 monotone paths from corner (0,0,0) to (1,1,1), one per axis permutation.
  static const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int l = 0; l < k; ++l) {
    for (int j = 0; j < k; ++j) {
      for (int i = 0; i < k; ++i) {
        for (const auto& p : perms) {
          std::array<int, 3> c = {i, j, l};
          m.tets.push_back(id(c[0], c[1], c[2]));
          for (int axis : p) {
            ++c[axis];
            m.tets.push_back(id(c[0], c[1], c[2]));
          }
          m.body.push_back(l < k / 2 ? 0 : 1);
        }
      }
    }
  }
  return m;
}

/// Fake fields at `step`: distinct, smooth values depending on node / tet index and step.
inline FieldFrame make_fake_frame(const FakeMesh& m, long step) {
  FieldFrame f;
  f.step = step;
  f.time = 0.1 * static_cast<double>(step);
  const auto n = static_cast<std::size_t>(m.num_nodes());
  f.displacement.resize(3 * n);
  f.velocity.resize(3 * n);
  for (std::size_t a = 0; a < 3 * n; ++a) {
    f.displacement[a] = 1e-3 * f.time * std::sin(m.X[a] * 3.0 + static_cast<double>(a % 3));
    f.velocity[a] = static_cast<double>(a) + 0.5 * static_cast<double>(step);
  }
  f.von_mises.resize(static_cast<std::size_t>(m.num_tets()));
  for (std::size_t e = 0; e < f.von_mises.size(); ++e) {
    f.von_mises[e] = 1e6 * static_cast<double>(e % 97) + static_cast<double>(step);
  }
  return f;
}

}  // namespace emc::output::testing
