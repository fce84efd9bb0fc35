#include "emcontact/linalg/linear_solver.hpp"

#include <BelosSolverFactory_Tpetra.hpp>
#include <BelosTpetraAdapter.hpp>
#include <Teuchos_TimeMonitor.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>

namespace emc::linalg {

using Teuchos::RCP;
using Teuchos::rcp;

LinearSolver::LinearSolver(const Teuchos::ParameterList& linear, RCP<const Comm> comm,
                           const std::string& file)
    : type_(linear.get<std::string>("type")),
      prec_type_(linear.get<std::string>("preconditioner")),
      tol_(linear.get<double>("tolerance")),
      check_factor_(linear.get<double>("residual check factor")),
      max_iters_(linear.get<int>("max iterations")),
      reuse_(linear.get<bool>("reuse preconditioner")),
      reuse_rate_(linear.get<double>("factorisation reuse rate")) {
  if (linear.isSublist("Belos")) belos_ = linear.sublist("Belos");
  if (linear.isSublist("Ifpack2")) ifpack2_ = linear.sublist("Ifpack2");
  if (linear.isSublist("MueLu")) muelu_ = linear.sublist("MueLu");
  if (type_ == "klu2" && comm->getSize() > 1)
    throw InputError(
        "Solver/Linear/type = klu2 runs on one rank only (Debian's Amesos2 KLU2 is wrong on "
        "2+ ranks); allowed on " +
        std::to_string(comm->getSize()) + " ranks: gmres, cg");
  if (type_ != "klu2" && type_ != "mumps") check_pass_through(comm, file);
}

std::string LinearSolver::description() const {
  if (type_ == "klu2") return "Amesos2 KLU2";
  if (type_ == "mumps") return "MUMPS";
  return "Belos " + std::string(type_ == "cg" ? "CG" : "GMRES") + " + " + prec_type_;
}

void LinearSolver::build_preconditioner(const RCP<Matrix>& A, std::vector<std::string>* unused) {
  Teuchos::TimeMonitor t(*Teuchos::TimeMonitor::getNewTimer("emcontact: preconditioner"));
  if (prec_type_ == "none")
    prec_ = Teuchos::null;
  else if (prec_type_ == "muelu")
    prec_ = make_muelu(A, muelu_);
  else
    prec_ = make_ifpack2(prec_type_, A, ifpack2_, unused);
}

RCP<Teuchos::ParameterList> LinearSolver::belos_parameters(double tol) const {
  auto params = rcp(new Teuchos::ParameterList);
  params->set("Convergence Tolerance", tol);
  params->set("Maximum Iterations", max_iters_);
  if (type_ == "gmres") {
    params->set("Num Blocks", std::min(max_iters_, 300));
    params->set("Maximum Restarts", std::max(1, max_iters_ / 300 + 1));
  }
  params->set("Implicit Residual Scaling", "Norm of RHS");
  params->set("Explicit Residual Scaling", "Norm of RHS");
  params->setParameters(belos_);
  return params;
}

int LinearSolver::belos_solve(const RCP<Matrix>& A, const Vector& b, Vector& x, double tol,
                              bool& converged, std::string& message) {
  using Problem = Belos::LinearProblem<double, MultiVector, Operator>;
  auto params = belos_parameters(tol);
  x.putScalar(0.0);
  auto problem = rcp(new Problem(A, Teuchos::rcpFromRef(x), Teuchos::rcpFromRef(b)));
  if (!prec_.is_null()) problem->setRightPrec(prec_);
  problem->setProblem();
  Belos::SolverFactory<double, MultiVector, Operator> factory;
  auto solver = factory.create(type_ == "cg" ? "CG" : "GMRES", params);
  solver->setProblem(problem);
  const Belos::ReturnType ret = solver->solve();
  converged = ret == Belos::Converged;
  char buf[160];
  std::snprintf(buf, sizeof buf, "Belos %s returned %s after %d iterations (achieved %.3g)",
                type_ == "cg" ? "CG" : "GMRES", converged ? "Converged" : "Unconverged",
                solver->getNumIters(), solver->achievedTol());
  message = buf;
  return solver->getNumIters();
}

SolveStats LinearSolver::solve(const RCP<Matrix>& A, const Vector& b, Vector& x, double tol) {
  try {
    return checked_solve(A, b, x, tol);
  } catch (const LinearSolveError&) {
    throw;
  } catch (const std::exception& e) {  // Belos, Ifpack2, MueLu, Amesos2: a failed solve
    prec_ = Teuchos::null;
    throw LinearSolveError("linear solver (" + description() + ") failed: " + one_line(e.what()));
  }
}

SolveStats LinearSolver::checked_solve(const RCP<Matrix>& A, const Vector& b, Vector& x,
                                       double tol) {
  SolveStats st;
  tol = std::max(tol, tol_);
  const double decades = std::max(1.0, -std::log10(tol));
  std::string message;
  if (type_ == "klu2") {
    klu2_.solve(A, b, x);
    message = "Amesos2 KLU2 direct solve";
  } else if (type_ == "mumps") {
    mumps_solve(A, b, x, st, message);  // to tol_: exact like a direct solve
  } else {
    if (prec_.is_null() || !reuse_) {
      build_preconditioner(A);
      st.fresh_preconditioner = true;
    }
    bool converged = false;
    int its = belos_solve(A, b, x, tol, converged, message);
    st.iterations = its;
    const double expected = fresh_rate_ * decades;  // what a fresh one needs for this tol
    const bool slow = its > std::max(2 * expected, expected + 10);
    if (!st.fresh_preconditioner && (!converged || slow)) {  // the reused one stopped working
      build_preconditioner(A);
      st.fresh_preconditioner = true;
      its = belos_solve(A, b, x, tol, converged, message);
      st.iterations += its;
    }
    if (st.fresh_preconditioner) fresh_rate_ = its / decades;  // what a fresh one achieves
  }
  // true residual check
  Vector r(b.getMap());
  A->apply(x, r);
  r.update(1.0, b, -1.0);
  const double bn = b.norm2();
  st.true_residual = bn > 0 ? r.norm2() / bn : r.norm2();
  if (!(st.true_residual <= check_factor_ * tol) && bn > 0) {
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "linear solver (%s) failed: true relative residual %.3e exceeds %.3e "
                  "(residual check factor x tolerance); ",
                  description().c_str(), st.true_residual, check_factor_ * tol);
    prec_ = Teuchos::null;
    throw LinearSolveError(buf + message);
  }
  return st;
}

}  // namespace emc::linalg
