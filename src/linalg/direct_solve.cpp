// Solver/Linear/type = mumps or umfpack: when to factor anew. The Newton matrix changes a little
// from one iterate (and step) to the next, so the factors of an earlier matrix are a nearly exact
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
/// Flexible GMRES keeps the preconditioned basis Z = M^-1 V, so x = Z y costs no further solve
/// with M (plain right-preconditioned GMRES solves M x = V y at the end: one solve more per
/// call, and a fresh factorisation's whole solve is one iteration). Its test is the residual
/// it updates; the caller checks the true one.
int capped_gmres(const RCP<Matrix>& A, const RCP<Operator>& M, const Vector& b, Vector& x,
                 double tol, int cap, bool& converged) {
  using Problem = Belos::LinearProblem<double, MultiVector, Operator>;
  auto params = rcp(new Teuchos::ParameterList);
  params->set("Convergence Tolerance", tol);
  params->set("Maximum Iterations", cap);
  params->set("Num Blocks", cap);
  params->set("Maximum Restarts", 0);
  params->set("Flexible Gmres", true);
  params->set("Implicit Residual Scaling", "Norm of RHS");
  x.putScalar(0.0);
  auto problem = rcp(new Problem(A, Teuchos::rcpFromRef(x), Teuchos::rcpFromRef(b)));
  problem->setRightPrec(M);
  problem->setProblem();
  Belos::SolverFactory<double, MultiVector, Operator> factory;
  auto solver = factory.create("Block GMRES", params);
  solver->setProblem(problem);
  converged = solver->solve() == Belos::Converged;
  return solver->getNumIters();
}

}  // namespace

int gmres_on_factors(const RCP<Matrix>& A, const RCP<Operator>& M, const Vector& b, Vector& x,
                     double tol, int cap, bool refine_unconverged, bool& converged,
                     double& true_residual) {
  int its = capped_gmres(A, M, b, x, tol, cap, converged);
  true_residual = -1;
  // GMRES that stopped before its cap did not contract too slowly, even where the true residual
  // is above tol while the one it updates is below (the solves of an ill-conditioned matrix:
  // inputs/ball.xml with the factors of the step before and tol = 1e-12 stops at 2 iterations
  // with a true residual of 4.5e-10, and one correction gives 6e-16): it is corrected within
  // the rest of the cap, not refactored.
  const bool stopped_early = !converged && its < cap;
  if (!converged && !refine_unconverged && !stopped_early) return its;
  Vector r(b.getMap()), dx(b.getMap());
  const double bn = b.norm2();
  auto residual = [&] {
    A->apply(x, r);
    r.update(1.0, b, -1.0);
    return r.norm2();
  };
  double rn = residual();
  for (int round = 0; round < 2 && rn > tol * bn; ++round) {
    const int round_cap = refine_unconverged ? cap : cap - its;
    if (round_cap < 1) break;
    its += capped_gmres(A, M, r, dx, std::min(0.5, tol * bn / rn), round_cap, converged);
    x.update(1.0, dx, 1.0);
    rn = residual();
  }
  converged = rn <= tol * bn;
  true_residual = bn > 0 ? rn / bn : rn;
  return its;
}

void LinearSolver::direct_solve(const RCP<Matrix>& A, const Vector& b, Vector& x, SolveStats& st,
                                std::string& message) {
  // umfpack's is made by the constructor (it refuses 2+ ranks there); MUMPS's initialisation
  // waits for the first solve
  if (!direct_) direct_ = std::make_shared<DirectMumps>(A->getComm());
  const double tol = tol_;      // see above
  constexpr int fresh_cap = 5;  // fresh factors: 1 iteration, a few where they are inexact
  if (reuse_ && reuse_rate_ > 0 && !prec_.is_null()) {
    // the iterations the rate needs (1e-9: log(1e-10) / log(0.1) must give 10, not 11)
    const int cap =
        std::max(1, static_cast<int>(std::ceil(std::log(tol) / std::log(reuse_rate_) - 1e-9)));
    bool converged = false;
    st.iterations = gmres_on_factors(A, prec_, b, x, tol, cap, false, converged, st.true_residual);
    static const bool trace = std::getenv("EMC_MUMPS_TRACE") != nullptr;
    if (trace && A->getComm()->getRank() == 0)  // debugging aid, as in DirectMumps::factor
      std::fprintf(stderr, "%s: reused factors, %d GMRES iterations (at most %d), %s\n",
                   direct_->name(), st.iterations, cap, converged ? "converged" : "refactoring");
    if (converged) {
      message = std::string("GMRES with the ") + direct_->name() +
                " factors of an earlier matrix, " + std::to_string(st.iterations) + " iterations";
      return;
    }
  }
  direct_->factor(A);
  prec_ = direct_->as_operator();
  st.fresh_preconditioner = true;
  // GMRES on the fresh factors too: one iteration where the factors solve to the tolerance,
  // a few (iterative refinement) where the pivoting left them less accurate than that on an
  // ill-conditioned matrix (UMFPACK on the hollow cylinders: a plain solve left 1.8e-8)
  bool converged = false;
  st.iterations =
      gmres_on_factors(A, prec_, b, x, tol, fresh_cap, true, converged, st.true_residual);
  message = std::string(direct_->name()) + " direct solve, " + std::to_string(st.iterations) +
            " GMRES iterations on its factors";
}

}  // namespace emc::linalg
