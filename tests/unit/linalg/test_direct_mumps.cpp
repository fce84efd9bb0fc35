// MUMPS behind DirectMumps and LinearSolver (type = mumps), on 1 and 2 ranks: a non-symmetric
// system is solved to round-off, the analysis is kept while the structure is the same and
// redone when it changes, reused factors serve as GMRES's preconditioner until a change of
// the matrix makes them too weak, and a singular matrix is a LinearSolveError naming INFOG.
#include <gtest/gtest.h>

#include <Tpetra_Core.hpp>
#include <cmath>

#include "emcontact/linalg/direct_mumps.hpp"
#include "emcontact/linalg/linear_solver.hpp"
#include "emcontact/linalg/parameters.hpp"
#include "stencil.hpp"

using namespace emc;
using emc::testing::relative_residual;
using emc::testing::stencil;

namespace {

constexpr GO kRows = 200;

/// Rows dealt out cyclically (row g on rank g mod size): not contiguous per rank, so the
/// gather to MUMPS's host and the scatter back are exercised.
Teuchos::RCP<const Map> cyclic_map(const Teuchos::RCP<const Comm>& comm) {
  std::vector<GO> mine;
  for (GO g = comm->getRank(); g < kRows; g += comm->getSize()) mine.push_back(g);
  return Teuchos::rcp(new Map(kRows, Teuchos::ArrayView<const GO>(mine), 0, comm));
}

/// The same graph object with its values scaled by (1 + eps sin(k)), entry k.
Teuchos::RCP<Matrix> perturbed(const Matrix& A, double eps) {
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

// A backward-stable LU leaves ||b - A x|| / ||b|| <= c n eps cond(A) with cond < 6 (above):
// 1e-13 is about 450 eps, far above that for these 200 rows and far below any real error.
constexpr double kRoundOff = 1e-13;

}  // namespace

TEST(DirectMumps, SolvesAndKeepsTheAnalysisWhileTheStructureIsTheSame) {
  auto comm = Tpetra::getDefaultComm();
  const auto map = cyclic_map(comm);
  Vector b(map), x(map);
  b.randomize();
  linalg::DirectMumps mumps(comm);

  const auto A1 = stencil(map, 1.0);
  mumps.factor(A1);
  mumps.solve(b, x);
  EXPECT_LT(relative_residual(*A1, x, b), kRoundOff);
  EXPECT_EQ(mumps.analyses(), 1);

  // new values on A1's graph object: no new analysis, and really A2's solution
  const auto A2 = perturbed(*A1, 0.4);
  mumps.factor(A2);
  mumps.solve(b, x);
  EXPECT_LT(relative_residual(*A2, x, b), kRoundOff);
  EXPECT_GT(relative_residual(*A1, x, b), 1e-3);
  EXPECT_EQ(mumps.analyses(), 1);

  // the same structure on another graph object: still no new analysis
  const auto A3 = stencil(map, 0.5);
  mumps.factor(A3);
  mumps.solve(b, x);
  EXPECT_LT(relative_residual(*A3, x, b), kRoundOff);
  EXPECT_EQ(mumps.analyses(), 1);

  // another structure (an extra far column per row): a new analysis
  const auto A4 = stencil(map, 1.0, 7);
  mumps.factor(A4);
  mumps.solve(b, x);
  EXPECT_LT(relative_residual(*A4, x, b), kRoundOff);
  EXPECT_EQ(mumps.analyses(), 2);
  EXPECT_EQ(mumps.factorisations(), 4);
}

TEST(DirectMumps, SingularMatrixIsALinearSolveErrorWithInfog) {
  auto comm = Tpetra::getDefaultComm();
  const auto map = cyclic_map(comm);
  // row i: e_i + e_{i+1 mod n}, except row 2 = row 1 = e_1 + e_2: exactly singular
  linalg::DirectMumps mumps(comm);
  auto B = Teuchos::rcp(new Matrix(map, 2));
  for (LO l = 0; l < static_cast<LO>(map->getNodeNumElements()); ++l) {
    const GO i = map->getGlobalElement(l);
    const GO cols[2] = {i == 2 ? 1 : i, i == 2 ? 2 : (i + 1) % kRows};
    const double vals[2] = {1.0, 1.0};
    B->insertGlobalValues(i, Teuchos::ArrayView<const GO>(cols, 2),
                          Teuchos::ArrayView<const double>(vals, 2));
  }
  B->fillComplete();
  try {
    mumps.factor(B);
    FAIL() << "a singular matrix was factored";
  } catch (const linalg::LinearSolveError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("INFOG(1) = -"), std::string::npos) << what;
    EXPECT_NE(what.find("singular"), std::string::npos) << what;
  }
}

TEST(LinearSolverMumps, ReusesTheFactorsWhileGmresConvergesWithThem) {
  auto comm = Tpetra::getDefaultComm();
  const auto map = cyclic_map(comm);
  auto linear = *linalg::valid_linear_parameters();
  linear.set("type", "mumps");
  linalg::LinearSolver solver(linear, comm);
  Vector b(map), x(map);
  b.randomize();
  const double tol = solver.tolerance();
  const double check = linear.get<double>("residual check factor") * tol;

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
