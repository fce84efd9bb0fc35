// UMFPACK behind DirectUmfpack and LinearSolver (type = umfpack): the checks of
// direct_cases.hpp with the rows listed out of order (a non-symmetric system solved to
// round-off, the analysis kept while the structure is the same and redone when it changes,
// reused factors as GMRES's preconditioner until a change of the matrix makes them too weak), the
// solution agrees with MUMPS's, a singular matrix is a LinearSolveError naming UMFPACK's status,
// and on 2 ranks the input is refused with a message naming what is allowed.
#include <gtest/gtest.h>

#include <Tpetra_Core.hpp>

#include "direct_cases.hpp"
#include "emcontact/linalg/direct_mumps.hpp"
#include "emcontact/linalg/direct_umfpack.hpp"

using namespace emc;
using namespace emc::testing;

namespace {

/// All rows on this rank, listed in a scrambled order (row 37 k mod 200 at local k; 37 and 200
/// are coprime), so that local and global numbers differ.
Teuchos::RCP<const Map> scrambled_map(const Teuchos::RCP<const Comm>& comm) {
  std::vector<GO> mine;
  for (GO k = 0; k < kDirectRows; ++k) mine.push_back((37 * k) % kDirectRows);
  return Teuchos::rcp(new Map(kDirectRows, Teuchos::ArrayView<const GO>(mine), 0, comm));
}

#define ONE_RANK_ONLY(comm) \
  if ((comm)->getSize() > 1) GTEST_SKIP() << "UMFPACK runs on one rank"

}  // namespace

TEST(DirectUmfpack, SolvesAndKeepsTheAnalysisWhileTheStructureIsTheSame) {
  auto comm = Tpetra::getDefaultComm();
  ONE_RANK_ONLY(comm);
  linalg::DirectUmfpack umfpack(comm);
  check_solves_and_keeps_the_analysis(umfpack, scrambled_map(comm));
}

TEST(DirectUmfpack, AgreesWithMumps) {
  auto comm = Tpetra::getDefaultComm();
  ONE_RANK_ONLY(comm);
  const auto map = scrambled_map(comm);
  Vector b(map), xu(map), xm(map);
  b.randomize();
  const auto A = perturbed(*stencil(map, 1.0, 7), 0.3);
  linalg::DirectUmfpack umfpack(comm);
  linalg::DirectMumps mumps(comm);
  umfpack.factor(A);
  umfpack.solve(b, xu);
  mumps.factor(A);
  mumps.solve(b, xm);
  // two backward-stable solves of a system with cond < 6 agree to a few hundred eps
  xu.update(-1.0, xm, 1.0);
  EXPECT_LT(xu.norm2(), kRoundOff * xm.norm2());
}

TEST(DirectUmfpack, SingularMatrixIsALinearSolveErrorWithItsStatus) {
  auto comm = Tpetra::getDefaultComm();
  ONE_RANK_ONLY(comm);
  linalg::DirectUmfpack umfpack(comm);
  check_singular_is_refused(umfpack, scrambled_map(comm),
                            {"UMFPACK factorisation failed: status", "singular"});
}

TEST(LinearSolverUmfpack, ReusesTheFactorsWhileGmresConvergesWithThem) {
  auto comm = Tpetra::getDefaultComm();
  ONE_RANK_ONLY(comm);
  check_reuses_the_factors("umfpack", scrambled_map(comm));
}

TEST(LinearSolverUmfpack, MoreThanOneRankIsAnInputErrorNamingTheAlternatives) {
  auto comm = Tpetra::getDefaultComm();
  auto linear = *linalg::valid_linear_parameters();
  linear.set("type", "umfpack");
  if (comm->getSize() == 1) {
    EXPECT_NO_THROW(linalg::LinearSolver(linear, comm));
    return;
  }
  try {
    linalg::LinearSolver solver(linear, comm);
    FAIL() << "umfpack accepted on " << comm->getSize() << " ranks";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("Solver/Linear/type = umfpack"), std::string::npos) << what;
    EXPECT_NE(what.find("one rank"), std::string::npos) << what;
    EXPECT_NE(what.find("mumps"), std::string::npos) << what;
  }
}
