#pragma once
// Bodies that overlap at the start (docs/THEORY.md §6.6): points inside a deformable body,
// found by point-in-tetrahedron tests in the reference configuration (host, once).
#include <vector>

#include "emcontact/fem/model.hpp"

namespace emc::contact {

struct Overlap {
  int count = 0;       ///< points inside the body beyond round-off
  double deepest = 0;  ///< the largest distance of one of them to the body's boundary
  int node = -1;       ///< that point
};

/// For each of the points (geometry node ids into x, 3 coordinates each): its depth inside
/// deformable body b of m, its distance to the body's boundary triangles, when it lies in one of
/// the body's tets this rank owns (fem::distribute) and farther from the boundary than the
/// round-off max(1e-9 edge, gap_roundoff) (a point on the boundary, as on flush faces, is not
/// inside); else 0. A rigid body has no inside. A point's depth is the largest over the ranks.
std::vector<double> depth_inside_body(const fem::Model& m, int b, const std::vector<int>& points,
                                      const std::vector<double>& x, double edge);

/// The points with a depth > 0, the deepest of them.
Overlap overlap_of(const std::vector<int>& points, const std::vector<double>& depth);

}  // namespace emc::contact
