#include "emcontact/linalg/rigid_modes.hpp"

#include <array>
#include <stdexcept>
#include <vector>

namespace emc::linalg {
namespace {

using Teuchos::RCP;
using Teuchos::rcp;

/// The centroid of the positions over all ranks (it only centres the rotations, so that their
/// columns are far from parallel to the translations: a better conditioned tentative basis).
std::array<double, 3> centroid(const Vector& positions) {
  const auto x = positions.getLocalViewHost(Tpetra::Access::ReadOnly);
  double local[4] = {0, 0, 0, 0};
  const size_t n = x.extent(0);
  for (size_t i = 0; i < n; ++i) local[i % 3] += x(i, 0);
  local[3] = static_cast<double>(n / 3);
  double global[4];
  Teuchos::reduceAll(*positions.getMap()->getComm(), Teuchos::REDUCE_SUM, 4, local, global);
  const double nodes = global[3] > 0 ? global[3] : 1;
  return {global[0] / nodes, global[1] / nodes, global[2] / nodes};
}

/// True for each local row of A whose off-diagonal entries are all zero.
std::vector<bool> decoupled_rows(const Matrix& A) {
  const auto lcl = A.getLocalMatrixHost();
  const auto& rows = A.getRowMap();
  const auto& cols = A.getColMap();
  std::vector<bool> out(lcl.numRows(), false);
  for (LO i = 0; i < lcl.numRows(); ++i) {
    const auto row = lcl.row(i);
    const GO gi = rows->getGlobalElement(i);
    bool coupled = false;
    for (LO k = 0; k < row.length && !coupled; ++k)
      coupled = row.value(k) != 0 && cols->getGlobalElement(row.colidx(k)) != gi;
    out[i] = !coupled;
  }
  return out;
}

}  // namespace

RCP<MultiVector> rigid_body_modes(const Vector& positions, const Matrix* A) {
  const auto c = centroid(positions);
  auto modes = rcp(new MultiVector(positions.getMap(), 6));
  std::vector<bool> skip;
  if (A) skip = decoupled_rows(*A);
  {
    const auto x = positions.getLocalViewHost(Tpetra::Access::ReadOnly);
    auto m = modes->getLocalViewHost(Tpetra::Access::OverwriteAll);
    const size_t n = x.extent(0);
    const auto& map = *positions.getMap();
    for (size_t node = 0; node + 2 < n; node += 3) {
      if (map.getGlobalElement(static_cast<LO>(node)) % 3 != 0)
        throw std::logic_error(
            "rigid_body_modes: the dofs of a node are not 3 n, 3 n + 1, 3 n + 2");
      const double r[3] = {x(node, 0) - c[0], x(node + 1, 0) - c[1], x(node + 2, 0) - c[2]};
      for (int d = 0; d < 3; ++d) {  // dof d of this node
        const size_t i = node + d;
        for (int j = 0; j < 6; ++j) m(i, j) = 0;
        if (A && skip[i]) continue;
        m(i, d) = 1;
        // component d of e_a x r: r_{a2} for a = a1, -r_{a1} for a = a2 (cyclic d, a1, a2)
        const int a1 = (d + 1) % 3, a2 = (d + 2) % 3;
        m(i, 3 + a1) = r[a2];
        m(i, 3 + a2) = -r[a1];
      }
    }
  }
  return modes;
}

RCP<MultiVector> node_coordinates(const Vector& positions) {
  const auto& dofs = positions.getMap();
  const size_t n = dofs->getNodeNumElements() / 3;
  std::vector<GO> nodes(n);
  for (size_t k = 0; k < n; ++k) nodes[k] = dofs->getGlobalElement(static_cast<LO>(3 * k)) / 3;
  const auto invalid = Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid();
  auto map = rcp(new Map(invalid, Teuchos::ArrayView<const GO>(nodes), 0, dofs->getComm()));
  auto coords = rcp(new MultiVector(map, 3));
  const auto x = positions.getLocalViewHost(Tpetra::Access::ReadOnly);
  auto out = coords->getLocalViewHost(Tpetra::Access::OverwriteAll);
  for (size_t k = 0; k < n; ++k)
    for (int d = 0; d < 3; ++d) out(k, d) = x(3 * k + d, 0);
  return coords;
}

}  // namespace emc::linalg
