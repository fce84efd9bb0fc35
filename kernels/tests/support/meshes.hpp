#pragma once
// Host-built geometry for the kernel library's tests and benchmarks: a box of tets, triangulated
// surfaces (a bumpy sheet, a sphere), query points near them, random displacements, and their
// copies into Views.
#include <Kokkos_Core.hpp>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "kernels/tet4.hpp"

namespace emc::kernels::test {

/// A box [0,1]^3 of n^3 cubes split into 6 tets each (Kuhn), positively oriented: 4 node ids
/// per tet into X (3 coordinates per node).
struct Box {
  std::vector<int> tets;
  std::vector<double> X;
  explicit Box(int n) {
    auto id = [n](int i, int j, int l) { return (l * (n + 1) + j) * (n + 1) + i; };
    for (int l = 0; l <= n; ++l)
      for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i)
          X.insert(X.end(), {double(i) / n, double(j) / n, double(l) / n});
    const int perm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (int l = 0; l < n; ++l)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
          for (const auto& p : perm) {
            int c[3] = {i, j, l}, v[4];
            v[0] = id(c[0], c[1], c[2]);
            for (int s = 0; s < 3; ++s) {
              ++c[p[s]];
              v[s + 1] = id(c[0], c[1], c[2]);
            }
            double x[4][3];
            for (int a = 0; a < 4; ++a)
              for (int q = 0; q < 3; ++q) x[a][q] = X[3 * v[a] + q];
            if (tet_volume(x) < 0) std::swap(v[1], v[2]);
            tets.insert(tets.end(), v, v + 4);
          }
  }
  int num_tets() const { return static_cast<int>(tets.size() / 4); }
  int num_nodes() const { return static_cast<int>(X.size() / 3); }
};

/// n values uniform in [-amp, amp] (seeded).
inline std::vector<double> random_values(std::size_t n, double amp, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-amp, amp);
  std::vector<double> v(n);
  for (double& x : v) x = d(rng);
  return v;
}

/// A bumpy triangulated sheet z = amp sin(kx x) cos(ky y) on [0,1]^2, n x n squares cut in two.
struct Sheet {
  std::vector<std::array<int, 3>> facets;
  std::vector<double> x;
  double amp, kx, ky;
  Sheet(int n, double amp_ = 0.1, double kx_ = 3, double ky_ = 2) : amp(amp_), kx(kx_), ky(ky_) {
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        const double px = double(i) / n, py = double(j) / n;
        x.insert(x.end(), {px, py, z(px, py)});
      }
    auto id = [n](int i, int j) { return j * (n + 1) + i; };
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        facets.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        facets.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      }
  }
  double z(double px, double py) const { return amp * std::sin(kx * px) * std::cos(ky * py); }
  /// count points over [lo, hi]^2 within dz of the sheet; every fourth on a grid line of
  /// spacing 1/snap, every eighth on a grid vertex (ties between facets).
  std::vector<double> near_points(int count, unsigned seed, double lo, double hi, double dz,
                                  int snap) const {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> d(lo, hi), ddz(-dz, dz);
    std::vector<double> y;
    for (int t = 0; t < count; ++t) {
      double p[2] = {d(rng), d(rng)};
      if (snap > 0 && t % 4 == 0) {
        p[0] = std::round(p[0] * snap) / snap;
        if (t % 8 == 0) p[1] = std::round(p[1] * snap) / snap;
      }
      y.insert(y.end(), {p[0], p[1], z(p[0], p[1]) + ddz(rng)});
    }
    return y;
  }
};

/// A sphere of radius r about c, nt x 2nt latitude-longitude quads cut in two (the poles'
/// triangles repeat a node: degenerate facets): every orientation of the normal.
inline void sphere(int nt, double r, const double c[3], std::vector<std::array<int, 3>>& facets,
                   std::vector<double>& x) {
  const double pi = std::acos(-1.0);
  const int np = 2 * nt;
  for (int j = 0; j <= nt; ++j)
    for (int i = 0; i < np; ++i) {
      const double th = pi * j / nt, ph = 2 * pi * i / np;
      x.insert(x.end(), {c[0] + r * std::sin(th) * std::cos(ph),
                         c[1] + r * std::sin(th) * std::sin(ph), c[2] + r * std::cos(th)});
    }
  auto id = [np](int i, int j) { return j * np + i % np; };
  for (int j = 0; j < nt; ++j)
    for (int i = 0; i < np; ++i) {
      facets.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      facets.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
}

/// A copy of n rows of N values into a (row-major) View of MemorySpace.
template <class T, int N, class MemorySpace>
Kokkos::View<T* [N], Kokkos::LayoutRight, MemorySpace> rows(const T* data, std::size_t n,
                                                            const std::string& label) {
  Kokkos::View<T* [N], Kokkos::LayoutRight, MemorySpace> v(label, n);
  Kokkos::deep_copy(
      v,
      Kokkos::View<const T* [N], Kokkos::LayoutRight, Kokkos::HostSpace, Kokkos::MemoryUnmanaged>(
          data, n));
  return v;
}

}  // namespace emc::kernels::test
