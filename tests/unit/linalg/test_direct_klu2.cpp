// Amesos2 KLU2 behind DirectKlu2: a new matrix on the same graph object keeps the symbolic
// factorisation and is solved with its own values (a stale factorisation would leave a residual
// of the size of the change); a matrix on another graph gets a new symbolic factorisation.
#include <gtest/gtest.h>

#include <Tpetra_Core.hpp>
#include <cmath>

#include "emcontact/linalg/linear_solver.hpp"
#include "stencil.hpp"

using namespace emc;
using emc::testing::relative_residual;
using emc::testing::stencil;

namespace {

constexpr int kRows = 40;

}  // namespace

TEST(DirectKlu2, KeepsTheSymbolicFactorisationOnTheSameGraph) {
  auto comm = Tpetra::getDefaultComm();
  auto map = Teuchos::rcp(new Map(kRows, 0, comm));
  Vector b(map), x(map);
  b.randomize();
  linalg::DirectKlu2 klu2;

  const auto A1 = stencil(map, 1.0);
  klu2.solve(A1, b, x);
  EXPECT_LT(relative_residual(*A1, x, b), 1e-14);
  EXPECT_EQ(klu2.symbolic_factorisations(), 1);

  // new values on A1's graph object
  const auto v1 = A1->getLocalMatrixDevice().values;
  typename Matrix::local_matrix_device_type::values_type::non_const_type v2("v2", v1.extent(0));
  Kokkos::deep_copy(v2, v1);  // a copy: A1 keeps its values
  auto h2 = Kokkos::create_mirror_view(v2);
  Kokkos::deep_copy(h2, v2);
  for (std::size_t k = 0; k < h2.extent(0); ++k) h2(k) *= 1.0 + 0.4 * std::sin(double(k));
  Kokkos::deep_copy(v2, h2);
  auto A2 = Teuchos::rcp(new Matrix(A1->getCrsGraph(), v2));
  A2->fillComplete(A1->getDomainMap(), A1->getRangeMap());
  klu2.solve(A2, b, x);
  EXPECT_LT(relative_residual(*A2, x, b), 1e-14);
  EXPECT_GT(relative_residual(*A1, x, b), 1e-3);  // really A2's solution
  EXPECT_EQ(klu2.symbolic_factorisations(), 1);

  // the same pattern on another graph object: a new symbolic factorisation
  const auto A3 = stencil(map, 0.5);
  klu2.solve(A3, b, x);
  EXPECT_LT(relative_residual(*A3, x, b), 1e-14);
  EXPECT_EQ(klu2.symbolic_factorisations(), 2);
}
