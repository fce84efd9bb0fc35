// MUMPS behind DirectMumps and LinearSolver (type = mumps), on 1 and 2 ranks: the checks of
// direct_cases.hpp (a non-symmetric system solved to round-off, the analysis kept while the
// structure is the same and redone when it changes, reused factors as GMRES's preconditioner
// until a change of the matrix makes them too weak), and a singular matrix is a
// LinearSolveError naming INFOG.
#include <gtest/gtest.h>

#include <Tpetra_Core.hpp>

#include "direct_cases.hpp"
#include "emcontact/linalg/direct_mumps.hpp"

using namespace emc;
using namespace emc::testing;

namespace {

/// Rows dealt out cyclically (row g on rank g mod size): not contiguous per rank, so the
/// gather to MUMPS's host and the scatter back are exercised.
Teuchos::RCP<const Map> cyclic_map(const Teuchos::RCP<const Comm>& comm) {
  std::vector<GO> mine;
  for (GO g = comm->getRank(); g < kDirectRows; g += comm->getSize()) mine.push_back(g);
  return Teuchos::rcp(new Map(kDirectRows, Teuchos::ArrayView<const GO>(mine), 0, comm));
}

}  // namespace

TEST(DirectMumps, SolvesAndKeepsTheAnalysisWhileTheStructureIsTheSame) {
  auto comm = Tpetra::getDefaultComm();
  linalg::DirectMumps mumps(comm);
  check_solves_and_keeps_the_analysis(mumps, cyclic_map(comm));
}

TEST(DirectMumps, SingularMatrixIsALinearSolveErrorWithInfog) {
  auto comm = Tpetra::getDefaultComm();
  linalg::DirectMumps mumps(comm);
  check_singular_is_refused(mumps, cyclic_map(comm), {"INFOG(1) = -", "singular"});
}

TEST(LinearSolverMumps, ReusesTheFactorsWhileGmresConvergesWithThem) {
  check_reuses_the_factors("mumps", cyclic_map(Tpetra::getDefaultComm()));
}

// linalg::gmres_on_factors with factors of a matrix 1% off (A M^-1 = I + O(1e-2)): two GMRES
// iterations leave about 1e-4, short of 1e-10; unrefined that is reported unconverged, refined
// the corrections for the true residual reach 1e-10, and the residual reported is the true one.
TEST(GmresOnFactors, CorrectsForTheTrueResidualWhereTheFactorsAreInexact) {
  auto comm = Tpetra::getDefaultComm();
  const auto map = cyclic_map(comm);
  const auto A = stencil(map, 1.0);
  linalg::DirectMumps mumps(comm);
  mumps.factor(perturbed(*A, 1e-2));
  const auto M = mumps.as_operator();
  Vector b(map), x(map);
  b.randomize();
  constexpr double tol = 1e-10;
  constexpr int cap = 2;
  bool converged = true;
  double true_residual = 0;

  int its = linalg::gmres_on_factors(A, M, b, x, tol, cap, false, converged, true_residual);
  EXPECT_FALSE(converged);
  EXPECT_EQ(its, cap);
  EXPECT_EQ(true_residual, -1.0);
  EXPECT_GT(relative_residual(*A, x, b), tol);

  its = linalg::gmres_on_factors(A, M, b, x, tol, cap, true, converged, true_residual);
  EXPECT_TRUE(converged);
  EXPECT_GT(its, cap);  // the corrections ran
  EXPECT_LE(true_residual, tol);
  EXPECT_NEAR(true_residual, relative_residual(*A, x, b), 1e-15);
}
