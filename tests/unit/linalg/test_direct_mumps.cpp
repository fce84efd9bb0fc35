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

/// The stencil A on cyclic rows, MUMPS's factors of A with entry k scaled by 1 + eps sin(k),
/// and a random right-hand side b.
struct PerturbedFactors {
  Teuchos::RCP<const Map> map = cyclic_map(Tpetra::getDefaultComm());
  Teuchos::RCP<Matrix> A = stencil(map, 1.0);
  linalg::DirectMumps mumps{Tpetra::getDefaultComm()};
  Vector b{map}, x{map};
  explicit PerturbedFactors(double eps) {
    mumps.factor(perturbed(*A, eps));
    b.randomize();
  }
};

/// M's solves with a relative error of `noise` that differs from call to call, as the solves
/// of an ill-conditioned matrix have (round-off of eps cond(A), not a fixed linear operator).
class NoisyInverse : public Operator {
 public:
  NoisyInverse(Teuchos::RCP<const Operator> M, double noise) : M_(std::move(M)), noise_(noise) {}
  Teuchos::RCP<const Map> getDomainMap() const override { return M_->getDomainMap(); }
  Teuchos::RCP<const Map> getRangeMap() const override { return M_->getRangeMap(); }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp mode = Teuchos::NO_TRANS,
             double alpha = 1.0, double beta = 0.0) const override {
    M_->apply(X, Y, mode, alpha, beta);
    auto y = Y.getLocalViewHost(Tpetra::Access::ReadWrite);
    ++calls_;
    for (std::size_t k = 0; k < y.extent(0); ++k)
      y(k, 0) *= 1.0 + noise_ * std::sin(1000.0 * calls_ + double(k));
  }

 private:
  Teuchos::RCP<const Operator> M_;
  double noise_;
  mutable int calls_ = 0;
};

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
  PerturbedFactors f(1e-2);
  const auto& A = f.A;
  const auto M = f.mumps.as_operator();
  auto &b = f.b, &x = f.x;
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

// GMRES stops before its cap when the residual it updates has met tol and the true one has not:
// the solves of an ill-conditioned matrix carry a round-off that differs from call to call
// (eps cond(A); inputs/ball.xml with the factors of the step before: 2 iterations, true residual
// 4.5e-10 against tol 1e-12). That is no slow contraction: the correction for the true residual
// reaches tol within the rest of the cap. A cap used up unconverged is still reported
// unconverged (the factors are renewed).
TEST(GmresOnFactors, CorrectsAnEarlyStopWithinTheCap) {
  PerturbedFactors f(1e-7);
  const auto& A = f.A;
  const Teuchos::RCP<Operator> M = Teuchos::rcp(new NoisyInverse(f.mumps.as_operator(), 1e-9));
  auto &b = f.b, &x = f.x;
  constexpr double tol = 1e-12;
  bool converged = false;
  double true_residual = 0;

  int its = linalg::gmres_on_factors(A, M, b, x, tol, 12, false, converged, true_residual);
  EXPECT_TRUE(converged);
  EXPECT_LE(its, 12);
  EXPECT_LE(true_residual, tol);
  EXPECT_NEAR(true_residual, relative_residual(*A, x, b), 1e-15);

  its = linalg::gmres_on_factors(A, M, b, x, tol, 1, false, converged, true_residual);
  EXPECT_FALSE(converged);
  EXPECT_EQ(its, 1);
  EXPECT_EQ(true_residual, -1.0);
}
