#pragma once
// The checks every sparse direct solver behind linalg::DirectSolver passes (tests only; used by
// test_direct_mumps and test_direct_umfpack): a non-symmetric system solved to round-off, the
// analysis kept while the structure is the same and redone when it changes, a singular matrix
// refused, and LinearSolver's reuse of the factors as GMRES's preconditioner.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "emcontact/linalg/direct_solver.hpp"
#include "emcontact/linalg/linear_solver.hpp"
#include "emcontact/linalg/parameters.hpp"
#include "stencil.hpp"

namespace emc::testing {

constexpr GO kDirectRows = 200;

// A backward-stable LU leaves ||b - A x|| / ||b|| <= c n eps cond(A) with cond < 6 (stencil.hpp):
// 1e-13 is about 450 eps, far above that for these 200 rows and far below any real error.
constexpr double kRoundOff = 1e-13;

/// The same graph object with its values scaled by (1 + eps sin(k)), entry k.
inline Teuchos::RCP<Matrix> perturbed(const Matrix& A, double eps) {
  const auto v1 = A.getLocalMatrixDevice().values;
  typename Matrix::local_matrix_device_type::values_type::non_const_type v2("v2", v1.extent(0));
  auto h2 = Kokkos::create_mirror_view(v2);
  Kokkos::deep_copy(h2, v1);
  for (std::size_t k = 0; k < h2.extent(0); ++k) h2(k) *= 1.0 + eps * std::sin(double(k));
  Kokkos::deep_copy(v2, h2);
  auto B = Teuchos::rcp(new Matrix(A.getCrsGraph(), v2));
  B->fillComplete(A.getDomainMap(), A.getRangeMap());
  return B;
}

/// Four factorisations: A1, new values on A1's graph, the same structure on another graph
/// (no new analysis for either), another structure (a new analysis).
inline void check_solves_and_keeps_the_analysis(linalg::DirectSolver& solver,
                                                const Teuchos::RCP<const Map>& map) {
  Vector b(map), x(map);
  b.randomize();
  const auto A1 = stencil(map, 1.0);
  solver.factor(A1);
  solver.solve(b, x);
  EXPECT_LT(relative_residual(*A1, x, b), kRoundOff);
  EXPECT_EQ(solver.analyses(), 1);

  // new values on A1's graph object: no new analysis, and really A2's solution
  const auto A2 = perturbed(*A1, 0.4);
  solver.factor(A2);
  solver.solve(b, x);
  EXPECT_LT(relative_residual(*A2, x, b), kRoundOff);
  EXPECT_GT(relative_residual(*A1, x, b), 1e-3);
  EXPECT_EQ(solver.analyses(), 1);

  // the same structure on another graph object: still no new analysis
  const auto A3 = stencil(map, 0.5);
  solver.factor(A3);
  solver.solve(b, x);
  EXPECT_LT(relative_residual(*A3, x, b), kRoundOff);
  EXPECT_EQ(solver.analyses(), 1);

  // another structure (an extra far column per row): a new analysis
  const auto A4 = stencil(map, 1.0, 7);
  solver.factor(A4);
  solver.solve(b, x);
  EXPECT_LT(relative_residual(*A4, x, b), kRoundOff);
  EXPECT_EQ(solver.analyses(), 2);
  EXPECT_EQ(solver.factorisations(), 4);

  // the factors as an operator: y = 2 (LU)^-1 b + 3 y0
  const auto M = solver.as_operator();
  Vector y(map), y0(map);
  y0.randomize();
  Tpetra::deep_copy(y, y0);
  M->apply(b, y, Teuchos::NO_TRANS, 2.0, 3.0);
  y.update(-2.0, x, -3.0, y0, 1.0);
  EXPECT_LT(y.norm2(), kRoundOff * x.norm2());
}

/// Row i: e_i + e_{i+1 mod n}, except row 2 = row 1 = e_1 + e_2: exactly singular. Factoring it
/// throws LinearSolveError whose message holds each of `expected`.
inline void check_singular_is_refused(linalg::DirectSolver& solver,
                                      const Teuchos::RCP<const Map>& map,
                                      const std::vector<std::string>& expected) {
  auto B = Teuchos::rcp(new Matrix(map, 2));
  for (LO l = 0; l < static_cast<LO>(map->getNodeNumElements()); ++l) {
    const GO i = map->getGlobalElement(l);
    const GO cols[2] = {i == 2 ? 1 : i, i == 2 ? 2 : (i + 1) % kDirectRows};
    const double vals[2] = {1.0, 1.0};
    B->insertGlobalValues(i, Teuchos::ArrayView<const GO>(cols, 2),
                          Teuchos::ArrayView<const double>(vals, 2));
  }
  B->fillComplete();
  try {
    solver.factor(B);
    FAIL() << "a singular matrix was factored";
  } catch (const linalg::LinearSolveError& e) {
    const std::string what = e.what();
    for (const auto& s : expected) EXPECT_NE(what.find(s), std::string::npos) << what;
  }
  EXPECT_FALSE(solver.factored());
}

/// LinearSolver with Solver/Linear/type = `type`: a fresh factorisation, a 1e-3 change solved
/// by GMRES on the old factors, a change of order one factored anew.
inline void check_reuses_the_factors(const std::string& type, const Teuchos::RCP<const Map>& map) {
  auto linear = *linalg::valid_linear_parameters();
  linear.set("type", type);
  linalg::LinearSolver solver(linear, map->getComm());
  EXPECT_TRUE(solver.direct());
  Vector b(map), x(map);
  b.randomize();
  const double check = linear.get<double>("residual check factor") * solver.tolerance();

  auto A1 = stencil(map, 1.0);
  auto st = solver.solve(A1, b, x);
  EXPECT_TRUE(st.fresh_preconditioner);
  EXPECT_LT(relative_residual(*A1, x, b), kRoundOff);

  // a 1e-3 change: the old factors leave I - A M^-1 of norm ~1e-3, so GMRES gains ~3 digits
  // per iteration, well within the reuse rate (0.1): no new factorisation
  auto A2 = perturbed(*A1, 1e-3);
  st = solver.solve(A2, b, x);
  EXPECT_FALSE(st.fresh_preconditioner);
  EXPECT_GE(st.iterations, 1);
  EXPECT_LT(relative_residual(*A2, x, b), check);

  // a change of order one (off-diagonals scaled by -1): the old factors are far off and
  // GMRES gains less than a digit per iteration: factored anew, solved to round-off
  auto A3 = stencil(map, -1.0);
  st = solver.solve(A3, b, x);
  EXPECT_TRUE(st.fresh_preconditioner);
  EXPECT_LT(relative_residual(*A3, x, b), kRoundOff);
}

}  // namespace emc::testing
