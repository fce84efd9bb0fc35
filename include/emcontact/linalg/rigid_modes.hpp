#pragma once
// The near null space of 3D elasticity for algebraic multigrid: the six rigid-body modes (three
// translations, three rotations) built from node positions, on the dof map 3 n + c.
#include <Teuchos_RCP.hpp>

#include "emcontact/types.hpp"

namespace emc::linalg {

/// Six columns on positions' map: e_x, e_y, e_z, then the rotations about the x, y and z axes
/// through the centroid, (e_a x (x - centroid)). `positions` holds coordinate c of node n at
/// dof 3 n + c (every node's three dofs on the same rank). If `A` is given, rows of A with no
/// nonzero off-diagonal entry (eliminated dofs: Dirichlet dummies, contact slaves) get zeros.
Teuchos::RCP<MultiVector> rigid_body_modes(const Vector& positions, const Matrix* A = nullptr);

/// The node coordinates (3 columns) on the node map n = dof / 3, as MueLu's `Coordinates`.
Teuchos::RCP<MultiVector> node_coordinates(const Vector& positions);

}  // namespace emc::linalg
