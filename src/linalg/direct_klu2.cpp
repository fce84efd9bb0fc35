#include <Amesos2.hpp>

#include "emcontact/linalg/linear_solver.hpp"

namespace emc::linalg {

void solve_klu2(const Teuchos::RCP<const Matrix>& A, const Vector& b, Vector& x) {
  if (A->getComm()->getSize() > 1)
    throw InputError(
        "Solver/Linear/type: klu2 runs on one rank only (Debian's Amesos2 KLU2 gives wrong "
        "answers on 2+ ranks); allowed on N ranks: gmres, cg");
  auto xp = Teuchos::rcpFromRef(x);
  auto bp = Teuchos::rcpFromRef(b);
  auto solver = Amesos2::create<Matrix, MultiVector>("KLU2", A, xp, bp);
  solver->symbolicFactorization().numericFactorization().solve();
}

}  // namespace emc::linalg
