#include <Amesos2.hpp>

#include "emcontact/linalg/linear_solver.hpp"

namespace emc::linalg {

struct DirectKlu2::State {
  Teuchos::RCP<Amesos2::Solver<Matrix, MultiVector>> solver;
  Teuchos::RCP<const Graph> graph;  ///< held, so that its address cannot be reused
};

DirectKlu2::DirectKlu2() : s_(std::make_shared<State>()) {}

// KLU2's symbolic phase (the fill-reducing ordering) depends on the pattern only: it is kept
// while the matrix sits on the same graph object (the reduced matrix's graph is rebuilt only
// when the active set changes), and only the numeric factorisation is redone.
void DirectKlu2::solve(const Teuchos::RCP<const Matrix>& A, const Vector& b, Vector& x) {
  if (A->getComm()->getSize() > 1)
    throw InputError(
        "Solver/Linear/type: klu2 runs on one rank only (Debian's Amesos2 KLU2 gives wrong "
        "answers on 2+ ranks); allowed on N ranks: gmres, cg, mumps");
  auto xp = Teuchos::rcpFromRef(x);
  auto bp = Teuchos::rcpFromRef(b);
  if (!s_->solver.is_null() && A->getCrsGraph().get() == s_->graph.get()) {
    s_->solver->setA(A, Amesos2::SYMBFACT);
  } else {
    s_->solver = Amesos2::create<Matrix, MultiVector>("KLU2", A, xp, bp);
    s_->graph = A->getCrsGraph();
    s_->solver->symbolicFactorization();
    ++symbolic_;
  }
  s_->solver->numericFactorization();
  s_->solver->solve(xp.ptr(), bp.ptr());
}

}  // namespace emc::linalg
