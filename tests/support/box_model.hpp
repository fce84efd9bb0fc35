#pragma once
// A structured one-body model for tests and benchmarks (no mesh generator, no MPI).
#include "emcontact/fem/model.hpp"
#include "kernels/tet4.hpp"

namespace emc::test {

/// A structured box of n^3 cubes split into 6 tets each (Kuhn), as a one-body model.
inline emc::fem::Model box_model(int n) {
  emc::fem::Model m;
  auto id = [n](int i, int j, int l) { return (l * (n + 1) + j) * (n + 1) + i; };
  for (int l = 0; l <= n; ++l)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i)
        m.X.insert(m.X.end(), {double(i) / n, double(j) / n, double(l) / n});
  const int perm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int l = 0; l < n; ++l)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (const auto& p : perm) {
          int c[3] = {i, j, l};
          int v[4];
          v[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[p[s]];
            v[s + 1] = id(c[0], c[1], c[2]);
          }
          double x[4][3];
          for (int a = 0; a < 4; ++a)
            for (int q = 0; q < 3; ++q) x[a][q] = m.X[3 * v[a] + q];
          if (emc::kernels::tet_volume(x) < 0) std::swap(v[1], v[2]);
          m.tets.insert(m.tets.end(), v, v + 4);
        }
  m.body_of_tet.assign(m.num_tets(), 0);
  emc::fem::Body b;
  b.name = "box";
  b.node_end = m.num_nodes();
  b.tet_end = m.num_tets();
  b.young = 1e6;
  b.poisson = 0.3;
  b.density = 1000;
  m.bodies.push_back(b);
  m.fixed.assign(m.num_nodes(), 0);
  m.global_tets = m.owned_tets = m.num_tets();
  emc::fem::body_geometry(m, 0);
  return m;
}

}  // namespace emc::test
