#pragma once
// Small non-symmetric test matrices for the direct solvers' tests (tests only).
#include <vector>

#include "emcontact/types.hpp"

namespace emc::testing {

/// A non-symmetric convection-diffusion stencil on the rows of `map` (columns i-2 .. i+1, and
/// i+width when width > 1), off-diagonals scaled by s. Row sums of |off-diagonal| are at most
/// 0.65 + 1.3 + 0.6 + 0.3 = 2.85 < 4: strictly diagonally dominant, so
/// ||A^-1||_inf <= 1 / (4 - 2.85) and cond_inf(A) <= 6.85 / 1.15 < 6.
inline Teuchos::RCP<Matrix> stencil(const Teuchos::RCP<const Map>& map, double s, GO width = 1) {
  const GO rows = static_cast<GO>(map->getGlobalNumElements());
  auto A = Teuchos::rcp(new Matrix(map, 5));
  for (LO l = 0; l < static_cast<LO>(map->getNodeNumElements()); ++l) {
    const GO i = map->getGlobalElement(l);
    std::vector<GO> cols;
    std::vector<double> vals;
    for (GO j = i - 2; j <= i + 1; ++j)
      if (j >= 0 && j < rows) {
        cols.push_back(j);
        vals.push_back(j == i ? 4.0 : s * (j < i ? -1.3 : -0.6) / double(i - j > 0 ? i - j : 1));
      }
    if (width > 1 && i + width < rows) {
      cols.push_back(i + width);
      vals.push_back(0.3 * s);
    }
    A->insertGlobalValues(i, Teuchos::ArrayView<const GO>(cols),
                          Teuchos::ArrayView<const double>(vals));
  }
  A->fillComplete();
  return A;
}

/// ||b - A x|| / ||b||.
inline double relative_residual(const Matrix& A, const Vector& x, const Vector& b) {
  Vector r(b.getMap());
  A.apply(x, r);
  r.update(1.0, b, -1.0);
  return r.norm2() / b.norm2();
}

}  // namespace emc::testing
