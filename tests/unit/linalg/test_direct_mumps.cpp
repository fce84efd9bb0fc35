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
