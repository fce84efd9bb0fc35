#include "emcontact/linalg/linear_solver.hpp"

#include <BelosSolverFactory_Tpetra.hpp>
#include <BelosTpetraAdapter.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <Teuchos_TimeMonitor.hpp>
#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "emcontact/format.hpp"
#include "emcontact/linalg/direct_umfpack.hpp"
#include "emcontact/linalg/rigid_modes.hpp"

namespace emc::linalg {

using Teuchos::RCP;
using Teuchos::rcp;

namespace {

/// A's products, each after asking `stop` (collective: every rank applies A at the same points
/// of a Krylov iteration, once per iteration): a stop request ends even a solve of many
/// iterations after the product it arrives in.
class StopCheckedOperator : public Operator {
 public:
  StopCheckedOperator(RCP<const Operator> A, std::function<bool()> stop)
      : A_(std::move(A)), stop_(std::move(stop)) {}
  Teuchos::RCP<const Map> getDomainMap() const override { return A_->getDomainMap(); }
  Teuchos::RCP<const Map> getRangeMap() const override { return A_->getRangeMap(); }
  bool hasTransposeApply() const override { return A_->hasTransposeApply(); }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp mode, Scalar alpha,
             Scalar beta) const override {
    if (stop_()) throw SolveInterrupted{};
    A_->apply(X, Y, mode, alpha, beta);
  }

 private:
  RCP<const Operator> A_;
  std::function<bool()> stop_;
};

}  // namespace

// docs/THEORY.md §9: every preconditioner setup starts Chebyshev's power method alike.
void same_random_start() {
  std::srand(1);
}

const char* preconditioner_name(Preconditioner p) {
  switch (p) {
    case Preconditioner::automatic:
      return "auto";
    case Preconditioner::ilu:
      return "ilu";
    case Preconditioner::schwarz:
      return "schwarz";
    case Preconditioner::chebyshev:
      return "chebyshev";
    case Preconditioner::muelu:
      return "muelu";
    case Preconditioner::none:
      break;
  }
  return "none";
}

LinearSolver::LinearSolver(const Teuchos::ParameterList& linear, RCP<const Comm> comm,
                           const std::string& file)
    : type_(Teuchos::getIntegralValue<SolverType>(linear, "type")),
      prec_type_(Teuchos::getIntegralValue<Preconditioner>(linear, "preconditioner")),
      tol_(linear.get<double>("tolerance")),
      check_factor_(linear.get<double>("residual check factor")),
      max_iters_(linear.get<int>("max iterations")),
      reuse_(linear.get<bool>("reuse preconditioner")),
      reuse_rate_(linear.get<double>("factorisation reuse rate")),
      null_space_(Teuchos::getIntegralValue<NullSpace>(linear, "multigrid near null space")),
      positions_type_(Teuchos::getIntegralValue<ModePositions>(linear, "multigrid positions")),
      zero_eliminated_(linear.get<bool>("multigrid modes zero at eliminated dofs")),
      refresh_(Teuchos::getIntegralValue<MultigridReuse>(linear, "multigrid reuse") ==
               MultigridReuse::refresh),
      refreshable_(prec_type_ == Preconditioner::muelu && refresh_),
      auto_(prec_type_ == Preconditioner::automatic),
      auto_dofs_(linear.get<int>("multigrid from equations")),
      chebyshev_dofs_(linear.get<int>("chebyshev from equations")) {
  if (linear.isSublist("Belos")) belos_ = linear.sublist("Belos");
  if (linear.isSublist("Ifpack2")) ifpack2_ = linear.sublist("Ifpack2");
  if (linear.isSublist("MueLu")) muelu_ = linear.sublist("MueLu");
  if (type_ == SolverType::klu2 && comm->getSize() > 1)
    throw InputError(
        "Solver/Linear/type = klu2 runs on one rank only (Debian's Amesos2 KLU2 is wrong on "
        "2+ ranks); allowed on " +
        std::to_string(comm->getSize()) + " ranks: gmres, cg, mumps");
  if (type_ == SolverType::umfpack) direct_ = std::make_shared<DirectUmfpack>(comm);
  if (!direct()) check_pass_through(comm, file);
}

std::string LinearSolver::description() const {
  if (type_ == SolverType::klu2) return "Amesos2 KLU2";
  if (type_ == SolverType::mumps) return "MUMPS";
  if (type_ == SolverType::umfpack) return "SuiteSparse UMFPACK";
  return "Belos " + krylov_name() + " + " + preconditioner_name(prec_type_);
}

std::string LinearSolver::krylov_name() const {
  return type_ == SolverType::cg ? "CG" : "GMRES";
}

void LinearSolver::matrix_changed() {
  if (refreshable_ && !prec_.is_null())
    stale_ = true;
  else
    prec_ = Teuchos::null;
}

void LinearSolver::choose_preconditioner(const RCP<Matrix>& A) {
  const bool large = static_cast<long long>(A->getGlobalNumRows()) >= auto_dofs_;
  prec_type_ = large && muelu_available()
                   ? Preconditioner::muelu
                   : small_preconditioner(static_cast<long long>(A->getGlobalNumRows()));
  refreshable_ = prec_type_ == Preconditioner::muelu && refresh_;
}

// ILU(0)'s triangular solves run on one thread: on more, Chebyshev's matrix-vector products
// are faster (perf/README.md "OpenMP threads"); on one, from about 10k equations too
// (perf/README.md, "Linear solvers").
Preconditioner LinearSolver::small_preconditioner(long long rows) const {
  return ExecSpace().concurrency() > 1 || rows >= chebyshev_dofs_ ? Preconditioner::chebyshev
                                                                  : Preconditioner::ilu;
}

void LinearSolver::setup_preconditioner(const RCP<Matrix>& A, int level) {
  stale_ = false;
  if (level == 2) return build_preconditioner(A);
  Teuchos::TimeMonitor t(*Teuchos::TimeMonitor::getNewTimer("emcontact: preconditioner"));
  refresh_muelu(A, *prec_);
}

void LinearSolver::build_preconditioner(const RCP<Matrix>& A, std::vector<std::string>* unused,
                                        std::vector<std::string>* ignored) {
  Teuchos::TimeMonitor t(*Teuchos::TimeMonitor::getNewTimer("emcontact: preconditioner"));
  if (prec_type_ == Preconditioner::none)
    prec_ = Teuchos::null;
  else if (prec_type_ == Preconditioner::muelu)
    prec_ = make_muelu_with_modes(A);
  else
    prec_ = make_ifpack2(prec_type_, A, ifpack2_, unused, ignored);
}

void LinearSolver::set_configuration(const Vector& X, const Vector& u) {
  if (positions_.is_null() || !positions_->getMap()->isSameAs(*X.getMap()))
    positions_ = rcp(new Vector(X.getMap()));
  positions_->update(1.0, X, positions_type_ == ModePositions::current ? 1.0 : 0.0, u, 0.0);
}

// The rigid-body modes of the positions last given (none given, e.g. the setup check: MueLu's
// default, one constant vector per dof).
RCP<Operator> LinearSolver::make_muelu_with_modes(const RCP<Matrix>& A) const {
  if (!uses_positions() || positions_.is_null() || !positions_->getMap()->isSameAs(*A->getRowMap()))
    return make_muelu(A, muelu_);
  return make_muelu(A, muelu_, rigid_body_modes(*positions_, zero_eliminated_ ? A.get() : nullptr),
                    node_coordinates(*positions_));
}

RCP<Teuchos::ParameterList> LinearSolver::belos_parameters(double tol) const {
  auto params = rcp(new Teuchos::ParameterList);
  params->set("Convergence Tolerance", tol);
  params->set("Maximum Iterations", max_iters_);
  if (type_ == SolverType::gmres) {
    params->set("Num Blocks", std::min(max_iters_, 300));
    params->set("Maximum Restarts", std::max(1, max_iters_ / 300 + 1));
    // modified Gram-Schmidt: vector operations that run on threads, where ICGS's block
    // products go to the (serial) BLAS; faster on one core too (perf/README.md "Linear solvers")
    params->set("Orthogonalization", "IMGS");
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
  RCP<Operator> op = A;
  if (stop_) op = rcp(new StopCheckedOperator(A, stop_));
  auto problem = rcp(new Problem(op, Teuchos::rcpFromRef(x), Teuchos::rcpFromRef(b)));
  if (!prec_.is_null()) problem->setRightPrec(prec_);
  problem->setProblem();
  Belos::SolverFactory<double, MultiVector, Operator> factory;
  auto solver = factory.create(krylov_name(), params);
  solver->setProblem(problem);
  const Belos::ReturnType ret = solver->solve();
  converged = ret == Belos::Converged;
  message =
      format("Belos %s returned %s after %d iterations (achieved %.3g)", krylov_name().c_str(),
             converged ? "Converged" : "Unconverged", solver->getNumIters(), solver->achievedTol());
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
  if (type_ == SolverType::klu2) {
    klu2_.solve(A, b, x);
    message = "Amesos2 KLU2 direct solve";
  } else if (type_ == SolverType::mumps || type_ == SolverType::umfpack) {
    direct_solve(A, b, x, st, message);  // to tol_: exact like a direct solve
  } else {
    // 0: the last preconditioner as it is; 1: refreshed for A; 2: built fresh for A. A reused
    // one that is slow or fails moves up a level and the solve is repeated.
    int level = prec_.is_null() || !reuse_ ? 2 : stale_ ? 1 : 0;
    for (;;) {
      if (level == 1 && !refreshable_) level = 2;
      if (level == 2 && auto_) choose_preconditioner(A);
      if (level > 0) setup_preconditioner(A, level);
      bool converged = false;
      const int its = belos_solve(A, b, x, tol, converged, message);
      st.iterations += its;
      if (level == 2) {
        fresh_rate_ = its / decades;  // what a fresh one achieves
        break;
      }
      const double expected = fresh_rate_ * decades;  // what a fresh one needs for this tol
      if (converged && its <= std::max(2 * expected, expected + 10)) break;
      ++level;
    }
    st.fresh_preconditioner = level == 2;
  }
  // true residual check (the direct solvers' refinement has computed it already)
  const double bn = b.norm2();
  if (st.true_residual < 0) {
    Vector r(b.getMap());
    A->apply(x, r);
    r.update(1.0, b, -1.0);
    st.true_residual = bn > 0 ? r.norm2() / bn : r.norm2();
  }
  if (!(st.true_residual <= check_factor_ * tol) && bn > 0) {
    const std::string failed = format(
        "linear solver (%s) failed: true relative residual %.3e exceeds %.3e "
        "(residual check factor x tolerance); ",
        description().c_str(), st.true_residual, check_factor_ * tol);
    prec_ = Teuchos::null;
    throw LinearSolveError(failed + message);
  }
  return st;
}

}  // namespace emc::linalg
