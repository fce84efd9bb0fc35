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

/// The points (geometry node ids into x, 3 coordinates each) that lie inside deformable body b
/// of m: in one of its tets and farther from its boundary triangles than the round-off
/// max(1e-9 edge, gap_roundoff) (a point on the boundary, as on flush faces, is not inside).
/// A rigid body has no inside.
Overlap inside_body(const fem::Model& m, int b, const std::vector<int>& points,
                    const std::vector<double>& x, double edge);

}  // namespace emc::contact
