// docs/THEORY.md §6.6: bodies that overlap at t = 0, found by point-in-tetrahedron tests in the
// reference configuration (on the host, once): a slave node inside the deformable master body,
// or a node of the master surface inside the slave body.
#include "emcontact/contact/overlap.hpp"

#include <algorithm>
#include <cmath>

#include "emcontact/contact/active.hpp"
#include "kernels/facet.hpp"

namespace emc::contact {

namespace {

/// A uniform grid of boxes (6 numbers each: lo, hi) on the host: per cell the items whose box
/// overlaps it, in increasing order (CSR). At most 64 cells per direction.
class BoxBins {
 public:
  explicit BoxBins(const std::vector<std::array<double, 6>>& boxes) {
    double ext = 0;
    for (int i = 0; i < 3; ++i) {
      lo_[i] = 1e300;
      hi_[i] = -1e300;
    }
    for (const auto& b : boxes)
      for (int i = 0; i < 3; ++i) {
        lo_[i] = std::min(lo_[i], b[i]);
        hi_[i] = std::max(hi_[i], b[3 + i]);
        ext += (b[3 + i] - b[i]) / 3;
      }
    h_ = boxes.empty() ? 1.0 : std::max(ext / boxes.size(), 1e-300);
    for (int i = 0; i < 3; ++i) h_ = std::max(h_, (hi_[i] - lo_[i]) / 64);
    for (int i = 0; i < 3; ++i)
      dims_[i] = boxes.empty() ? 1 : static_cast<int>(std::floor((hi_[i] - lo_[i]) / h_)) + 1;
    std::vector<std::vector<int>> cells(std::size_t(dims_[0]) * dims_[1] * dims_[2]);
    for (std::size_t k = 0; k < boxes.size(); ++k) {
      int a[3], b[3];
      for (int i = 0; i < 3; ++i) {
        a[i] = index(boxes[k][i], i);
        b[i] = index(boxes[k][3 + i], i);
      }
      for (int z = a[2]; z <= b[2]; ++z)
        for (int y = a[1]; y <= b[1]; ++y)
          for (int x = a[0]; x <= b[0]; ++x) cells[cell(x, y, z)].push_back(static_cast<int>(k));
    }
    start_.push_back(0);
    for (const auto& c : cells) {
      items_.insert(items_.end(), c.begin(), c.end());
      start_.push_back(static_cast<int>(items_.size()));
    }
  }
  /// fn(item) for the items of the cell holding y (none outside the grid).
  template <class F>
  void near(const double y[3], F fn) const {
    int d[3];
    for (int i = 0; i < 3; ++i) {
      if (!(y[i] >= lo_[i] && y[i] <= hi_[i])) return;
      d[i] = index(y[i], i);
    }
    visit(cell(d[0], d[1], d[2]), fn);
  }
  /// fn(item) for the items of the cells at Chebyshev distance r from the cell of y (clamped
  /// to the grid); false when that ring lies wholly outside the grid. Every point of a cell of
  /// a later ring is at least r h from y when y is in the grid.
  template <class F>
  bool ring(const double y[3], int r, F fn) const {
    int c[3];
    for (int i = 0; i < 3; ++i) c[i] = index(y[i], i);
    bool any = false;
    for (int z = std::max(c[2] - r, 0); z <= std::min(c[2] + r, dims_[2] - 1); ++z)
      for (int y1 = std::max(c[1] - r, 0); y1 <= std::min(c[1] + r, dims_[1] - 1); ++y1) {
        // the whole row on the ring's two faces in z and y, else its two ends in x
        const bool face = std::abs(z - c[2]) == r || std::abs(y1 - c[1]) == r;
        for (int x = c[0] - r; x <= c[0] + r; x += face || r == 0 ? 1 : 2 * r) {
          if (x < 0 || x >= dims_[0]) continue;
          any = true;
          visit(cell(x, y1, z), fn);
        }
      }
    return any;
  }
  double h() const { return h_; }

 private:
  double lo_[3], hi_[3], h_ = 1;
  int dims_[3] = {1, 1, 1};
  std::vector<int> start_, items_;

  int index(double v, int i) const {
    const double t = (v - lo_[i]) / h_;
    return t < 1 ? 0 : std::min(dims_[i] - 1, static_cast<int>(t));
  }
  std::size_t cell(int x, int y, int z) const {
    return (std::size_t(z) * dims_[1] + y) * dims_[0] + x;
  }
  template <class F>
  void visit(std::size_t c, F& fn) const {
    for (int k = start_[c]; k < start_[c + 1]; ++k) fn(items_[k]);
  }
};

const double* at(const std::vector<double>& x, int n) {
  return &x[3 * std::size_t(n)];
}

std::array<double, 6> box_of(const std::vector<double>& x, const int* nodes, int count) {
  std::array<double, 6> b = {1e300, 1e300, 1e300, -1e300, -1e300, -1e300};
  for (int a = 0; a < count; ++a)
    for (int i = 0; i < 3; ++i) {
      b[i] = std::min(b[i], at(x, nodes[a])[i]);
      b[3 + i] = std::max(b[3 + i], at(x, nodes[a])[i]);
    }
  return b;
}

double det3(const double a[3], const double b[3], const double c[3]) {
  return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
         a[2] * (b[0] * c[1] - b[1] * c[0]);
}

/// Whether y lies in tet t (global node ids) up to 1e-12 in barycentric terms.
bool in_tet(const std::vector<double>& x, const int* t, const double y[3]) {
  double e[3][3], r[3];
  for (int i = 0; i < 3; ++i) {
    for (int a = 0; a < 3; ++a) e[a][i] = at(x, t[a + 1])[i] - at(x, t[0])[i];
    r[i] = y[i] - at(x, t[0])[i];
  }
  const double v = det3(e[0], e[1], e[2]);
  if (!(v != 0)) return false;
  const double l1 = det3(r, e[1], e[2]) / v, l2 = det3(e[0], r, e[2]) / v,
               l3 = det3(e[0], e[1], r) / v;
  const double tol = -1e-12;
  return l1 >= tol && l2 >= tol && l3 >= tol && 1 - l1 - l2 - l3 >= tol;
}

/// The distance from y to triangle f (global node ids): its closest point (kernels::facet_clamp).
double distance_to(const std::vector<double>& x, const std::array<int, 3>& f, const double y[3]) {
  double xm[3][3], xi[2], gap;
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i < 3; ++i) xm[a][i] = at(x, f[a])[i];
  const kernels::FacetMetric m = kernels::facet_metric(xm);
  double d2 = 0;
  if (kernels::facet_cpp(y, xm, m, xi, gap)) {
    kernels::facet_clamp(m, xi);
    double N[3];
    kernels::facet_shape(xi, N);
    for (int i = 0; i < 3; ++i) {
      const double d = y[i] - N[0] * xm[0][i] - N[1] * xm[1][i] - N[2] * xm[2][i];
      d2 += d * d;
    }
    return std::sqrt(d2);
  }
  double best = 1e300;  // a degenerate triangle: its nodes
  for (int a = 0; a < 3; ++a) {
    d2 = 0;
    for (int i = 0; i < 3; ++i) d2 += (y[i] - xm[a][i]) * (y[i] - xm[a][i]);
    best = std::min(best, std::sqrt(d2));
  }
  return best;
}

}  // namespace

std::vector<double> depth_inside_body(const fem::Model& m, int b, const std::vector<int>& points,
                                      const std::vector<double>& x, double edge) {
  std::vector<double> out(points.size(), 0.0);
  const fem::Body& body = m.bodies[b];
  if (body.rigid || points.empty()) return out;
  std::vector<int> mine;  // the body's tets this rank owns
  std::vector<std::array<double, 6>> tet_boxes;
  for (int e = 0; e < m.owned_tets; ++e)
    if (m.body_of_tet[e] == b) {
      mine.push_back(e);
      tet_boxes.push_back(box_of(x, &m.tets[4 * std::size_t(e)], 4));
    }
  std::vector<std::array<int, 3>> surface;
  std::vector<std::array<double, 6>> tri_boxes;
  for (const auto& t : mesh::boundary_triangles(body.mesh)) {
    surface.push_back({body.node_begin + t[0], body.node_begin + t[1], body.node_begin + t[2]});
    tri_boxes.push_back(box_of(x, surface.back().data(), 3));
  }
  const BoxBins tets(tet_boxes), tris(tri_boxes);
  for (std::size_t p = 0; p < points.size(); ++p) {
    const double* y = at(x, points[p]);
    bool inside = false;
    tets.near(y,
              [&](int k) { inside = inside || in_tet(x, &m.tets[4 * std::size_t(mine[k])], y); });
    if (!inside) continue;
    // its depth: the distance to the body's boundary, by rings of cells around it
    double depth = 1e300;
    for (int r = 0;
         tris.ring(y, r, [&](int k) { depth = std::min(depth, distance_to(x, surface[k], y)); });
         ++r)
      if (depth <= r * tris.h()) break;
    if (!(depth > std::max(1e-9 * edge, gap_roundoff(edge, y)))) continue;  // on its boundary
    out[p] = depth;
  }
  return out;
}

Overlap overlap_of(const std::vector<int>& points, const std::vector<double>& depth) {
  Overlap out;
  for (std::size_t p = 0; p < points.size(); ++p) {
    if (!(depth[p] > 0)) continue;
    ++out.count;
    if (depth[p] > out.deepest) {
      out.deepest = depth[p];
      out.node = points[p];
    }
  }
  return out;
}

}  // namespace emc::contact
