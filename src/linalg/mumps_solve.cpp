// Solver/Linear/type = mumps: when to factor anew. The Newton matrix changes a little from one
// iterate (and step) to the next, so the factors of an earlier matrix are a nearly exact
// preconditioner: GMRES with them needs a few triangular solves instead of a factorisation.
// They are kept while that GMRES reduces the residual by at least `factorisation reuse rate`
// per iteration on average: it gets the iterations that rate needs for the tolerance, and
// when it has not converged in them the matrix is factored anew and solved directly.
// The reused factors solve to the input's tolerance (Solver/Linear/tolerance), not to the
// looser one adaptive Newton asks for: a direct solve is exact, and solving looser costs
// Newton iterations and energy accuracy (perf/README.md, "MUMPS") for few GMRES iterations.
#include <BelosSolverFactory_Tpetra.hpp>
#include <BelosTpetraAdapter.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "emcontact/linalg/direct_mumps.hpp"
#include "emcontact/linalg/linear_solver.hpp"

namespace emc::linalg {
namespace {

using Teuchos::RCP;
using Teuchos::rcp;

/// GMRES from x = 0, right-preconditioned by M, at most `cap` iterations (no restart).
int capped_gmres(const RCP<Matrix>& A, const RCP<Operator>& M, const Vector& b, Vector& x,
                 double tol, int cap, bool& converged) {
  using Problem = Belos::LinearProblem<double, MultiVector, Operator>;
  auto params = rcp(new Teuchos::ParameterList);
  params->set("Convergence Tolerance", tol);
  params->set("Maximum Iterations", cap);
  params->set("Num Blocks", cap);
  params->set("Maximum Restarts", 0);
  params->set("Implicit Residual Scaling", "Norm of RHS");
  params->set("Explicit Residual Scaling", "Norm of RHS");
  x.putScalar(0.0);
  auto problem = rcp(new Problem(A, Teuchos::rcpFromRef(x), Teuchos::rcpFromRef(b)));
  problem->setRightPrec(M);
  problem->setProblem();
  Belos::SolverFactory<double, MultiVector, Operator> factory;
  auto solver = factory.create("GMRES", params);
  solver->setProblem(problem);
  converged = solver->solve() == Belos::Converged;
  return solver->getNumIters();
}

}  // namespace

void LinearSolver::mumps_solve(const RCP<Matrix>& A, const Vector& b, Vector& x, SolveStats& st,
                               std::string& message) {
  if (!mumps_) mumps_ = std::make_shared<DirectMumps>(A->getComm());
  const double tol = tol_;  // see above
  if (reuse_ && reuse_rate_ > 0 && !prec_.is_null()) {
    // the iterations the rate needs (1e-9: log(1e-10) / log(0.1) must give 10, not 11)
    const int cap =
        std::max(1, static_cast<int>(std::ceil(std::log(tol) / std::log(reuse_rate_) - 1e-9)));
    bool converged = false;
    st.iterations = capped_gmres(A, prec_, b, x, tol, cap, converged);
    static const bool trace = std::getenv("EMC_MUMPS_TRACE") != nullptr;
    if (trace && A->getComm()->getRank() == 0)  // debugging aid, as in DirectMumps::factor
      std::fprintf(stderr, "mumps: reused factors, %d GMRES iterations (at most %d), %s\n",
                   st.iterations, cap, converged ? "converged" : "refactoring");
    if (converged) {
      message = "GMRES with the MUMPS factors of an earlier matrix, " +
                std::to_string(st.iterations) + " iterations";
      return;
    }
  }
  mumps_->factor(A);
  prec_ = mumps_->as_operator();
  st.fresh_preconditioner = true;
  mumps_->solve(b, x);
  message = "MUMPS direct solve";
}

}  // namespace emc::linalg
