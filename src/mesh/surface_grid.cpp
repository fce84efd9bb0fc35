// Rigid surfaces on a structured grid (types `plane` and `rectangle`): no Gmsh needed, the
// triangles are oriented by construction.
#include <algorithm>
#include <cmath>

#include "emcontact/mesh/generate.hpp"
#include "internal.hpp"

namespace emc::mesh {
namespace {

/// ceil(l / h), at least 1, as a double (no integer overflow for a tiny h).
double cells_along(double l, double h) {
  return std::max(1.0, std::ceil(l / h));
}

}  // namespace

std::array<int, 2> grid_cells(double l1, double l2, double size) {
  double h = size;
  if (cells_along(l1, h) * cells_along(l2, h) > kMaxGridCells) {
    // Larger cells: start from the cell of area l1 l2 / max, grow by 1% until it fits.
    h = std::max(h, std::sqrt(l1) * std::sqrt(l2 / kMaxGridCells));
    while (cells_along(l1, h) * cells_along(l2, h) > kMaxGridCells) h *= 1.01;
  }
  return {static_cast<int>(cells_along(l1, h)), static_cast<int>(cells_along(l2, h))};
}

}  // namespace emc::mesh

namespace emc::mesh::detail {

BodyMesh triangle_grid(const std::array<double, 3>& origin, const std::array<double, 3>& a,
                       const std::array<double, 3>& b, int n1, int n2) {
  BodyMesh m;
  m.X.reserve(3 * static_cast<std::size_t>(n1 + 1) * static_cast<std::size_t>(n2 + 1));
  for (int j = 0; j <= n2; ++j) {
    const double t = static_cast<double>(j) / n2;
    for (int i = 0; i <= n1; ++i) {
      const double s = static_cast<double>(i) / n1;
      for (int d = 0; d < 3; ++d) m.X.push_back(origin[d] + s * a[d] + t * b[d]);
    }
  }
  const auto id = [n1](int i, int j) { return j * (n1 + 1) + i; };
  std::vector<std::array<int, 3>>& tris = m.surfaces["surface"];
  tris.reserve(2 * static_cast<std::size_t>(n1) * static_cast<std::size_t>(n2));
  for (int j = 0; j < n2; ++j) {
    for (int i = 0; i < n1; ++i) {
      // (p10 - p00) x (p11 - p00) = a x (a + b) / (n1 n2) ~ a x b, and likewise for the other.
      tris.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      tris.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  sort_triangles(tris);
  return m;
}

}  // namespace emc::mesh::detail
