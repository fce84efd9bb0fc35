#include "emcontact/time/newton.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "emcontact/format.hpp"
#include "emcontact/time/interrupt.hpp"
#include "emcontact/time/timers.hpp"

namespace emc::time {

using Teuchos::RCP;
using Teuchos::rcp;
using Teuchos::TimeMonitor;

Newton::Newton(const fem::Discretization& disc, linalg::Elimination& elim,
               linalg::LinearSolver& solver, NewtonOptions opt)
    : disc_(disc), elim_(elim), solver_(solver), opt_(opt) {
  A_ = rcp(new FEMatrix(disc_.graph()));
  g_ = rcp(new Vector(disc_.owned_map()));
  if (solver_.uses_positions()) X_ = disc_.reference_positions();
  // a stop request ends a long Krylov solve too, not only the Newton iteration after it
  auto comm = disc_.comm();
  solver_.set_stop_check([comm] { return stop_requested(*comm); });
}

// Inexact Newton (docs/THEORY.md §1.7) around the Newton of §1.6 (its convergence test and
// round-off floor are unchanged): the linear solve needs to be accurate only to a fraction
// sigma of the residual the Newton step leaves anyway. Near the solution that is C r_k^2
// (quadratic convergence, C = r_k / r_{k-1}^2 measured in this step or, at the first iterate,
// in the last step), never below the round-off floor. So the
// iterates, and the converged residual, are those of exact solves to within sigma (test_newton;
// perf/README.md "Constants of the code, measured"), at a fraction of the Krylov iterations of
// solves to the input's tolerance, which stays the lower bound. An overestimated C loosens one
// solve, whose residual then shows a C smaller by about sigma: the estimate recovers.
double Newton::predicted_next(const std::vector<double>& r) const {
  const std::size_t k = r.size() - 1;
  const double C = k >= 1 ? r[k] / (r[k - 1] * r[k - 1]) : contraction_;
  if (!(C > 0) || !(r[k] > 0) || !std::isfinite(C)) return -1;
  return C * r[k] * r[k];
}

double Newton::linear_tolerance(const std::vector<double>& r, double floor) const {
  constexpr double sigma = 0.01, eta_max = 0.01;
  const double next = predicted_next(r);
  if (!opt_.adaptive_linear_tolerance || next < 0) return 0;
  return std::min(eta_max, sigma * std::max(next, floor) / r.back());
}

StartScales Newton::start_scales(const Vector& u0, const Vector& V0, double dt) {
  const auto map = disc_.owned_map();
  Vector scale(map), ones(map), mass(map), diag(map);
  disc_.assemble(u0, V0, u0, dt, A_.get(), *g_, &scale);
  ones.putScalar(1.0);
  disc_.apply_mass(ones, mass);  // the consistent mass's row sums
  A_->getLocalDiagCopy(diag);
  StartScales s;
  s.scale = scale.norm2();
  s.inertia_share = rcp(new Vector(map));
  auto share = s.inertia_share->getLocalViewHost(Tpetra::Access::OverwriteAll);
  const auto m = mass.getLocalViewHost(Tpetra::Access::ReadOnly);
  const auto d = diag.getLocalViewHost(Tpetra::Access::ReadOnly);
  for (std::size_t i = 0; i < share.extent(0); ++i)
    share(i, 0) = d(i, 0) > 0 ? 2.0 / (dt * dt) * m(i, 0) / d(i, 0) : 0.0;
  return s;
}

NewtonResult Newton::solve(const Vector& u0, const Vector& V0, double dt, Vector& u1,
                           double reference, double rtol, bool iterate_once) {
  last_ = iterate(u0, V0, dt, u1, reference, rtol > 0 ? rtol : opt_.rtol, iterate_once);
  // C of a step's first iterate: only a solve from the step's start iterate measures it (a
  // re-solve or a final solve of §6.9 starts near its solution, where r_1 / r_0^2 is larger)
  if (reference <= 0 && last_.residuals.size() >= 2 && last_.residuals[0] > 0)
    contraction_ = last_.residuals[1] / (last_.residuals[0] * last_.residuals[0]);
  static const bool trace = std::getenv("EMC_NEWTON_TRACE") != nullptr;
  if (trace && disc_.comm()->getRank() == 0) {  // debugging aid: residual history per solve
    std::fprintf(stderr, "newton %s (floor %.2e, linear its %d, extra matrices %d):",
                 last_.converged ? "converged" : "failed", last_.floor, last_.linear_iterations,
                 last_.extra_assemblies);
    for (double r : last_.residuals) std::fprintf(stderr, " %.2e", r);
    std::fprintf(stderr, "%s%s\n", last_.failure.empty() ? "" : ": ", last_.failure.c_str());
  }
  return last_;
}

NewtonResult Newton::iterate(const Vector& u0, const Vector& V0, double dt, Vector& u1,
                             double reference, double rtol, bool once) {
  auto& t_asm = assembly_timer();
  auto& t_elim = elimination_timer();
  auto& t_solve = linear_solve_timer();
  auto& t_contact = contact_timer();
  const auto map = disc_.owned_map();
  Vector& g = *g_;
  Vector scale(map), R(map), dq(map), du(map);
  NewtonResult res;
  double r0 = 0;
  if (hooks_) {
    TimeMonitor tm(t_contact);
    hooks_->start(u0, u1);
  }
  const double eps = std::numeric_limits<double>::epsilon();
  // The residual at u1 and, with_matrix, the Newton matrix A_ (else A_ keeps the last one).
  auto assemble = [&](bool with_matrix) {
    fem::AssemblyInfo info;
    {
      TimeMonitor tm(t_asm);
      info = disc_.assemble(u0, V0, u1, dt, with_matrix ? A_.get() : nullptr, g, &scale);
    }
    res.matrices += with_matrix;
    if (info.min_detF > 0 && hooks_) {
      TimeMonitor tm(t_contact);
      hooks_->before_reduce(u0, u1, g, *A_);
    }
    return info;
  };
  bool with_matrix = true;
  for (int it = 0;; ++it) {
    if (stop_requested(*disc_.comm())) throw Interrupted();  // a signal within a long step
    const fem::AssemblyInfo info = assemble(with_matrix);
    if (!(info.min_detF > 0)) {
      res.failure = format("element %lld inverted (det F = %.3e) at Newton iterate %d",
                           info.worst_tet + 1, info.min_detF, it);
      return res;
    }
    RCP<Matrix> Ar;
    {
      TimeMonitor tm(t_elim);
      elim_.reduce_residual(g, R);
    }
    const double r = R.norm2();
    res.residuals.push_back(r);
    if (!std::isfinite(r)) {
      res.failure = "residual is not finite at Newton iterate " + std::to_string(it);
      return res;
    }
    if (it == 0) r0 = r;
    // docs/THEORY.md §1.6: the tolerance never sits below the round-off of g's terms, nor below
    // what re-projecting the constrained slaves leaves at every iterate
    double total = 0;  // hooks_ is set on every rank or on none: the reduction is collective
    if (hooks_) {
      const double roundoff = hooks_->residual_roundoff();
      Teuchos::reduceAll(*disc_.comm(), Teuchos::REDUCE_SUM, 1, &roundoff, &total);
    }
    const double roundoff = std::hypot(100 * eps * scale.norm2(), std::sqrt(total));
    const double floor = std::max(opt_.atol, roundoff);
    const double target = std::max(rtol * std::max(reference, r0), floor);
    res.floor = floor;
    // the start iterate only if it is a solution to round-off: the absolute tolerance applies
    // to Newton's own iterates (an atol above r_0 froze the bodies: u_{n+1} = u_n, V flipped);
    // a re-solve's at its tolerance unless an entry changed its state (`once`, §11.4)
    if (r <= target && (it > 0 || r <= roundoff || (reference > 0 && !once))) {
      res.converged = true;
      return res;
    }
    if (hooks_ && hooks_->abandon(it, r, r0)) {
      res.failure = "a sliding contact node slid against its direction at Newton iterate " +
                    std::to_string(it);
      return res;
    }
    if (it >= opt_.max_iterations) {
      res.failure = format(
          "Newton did not converge in %d iterations (residual %.3e, initial %.3e, target %.3e)", it,
          r, r0, target);
      return res;
    }
    if (!with_matrix) {  // convergence was predicted but did not come: the matrix after all
      assemble(true);
      ++res.extra_assemblies;
    }
    {
      TimeMonitor tm(t_elim);
      Ar = elim_.reduce_matrix(A_);
    }
    R.scale(-1.0);
    if (!X_.is_null()) solver_.set_configuration(*X_, u1);
    try {
      TimeMonitor tm(t_solve);
      const auto st = solver_.solve(Ar, R, dq, linear_tolerance(res.residuals, floor));
      res.linear_iterations += st.iterations;
    } catch (const linalg::LinearSolveError& e) {
      res.failure = e.what();
      return res;
    } catch (const linalg::SolveInterrupted&) {
      throw Interrupted();
    }
    elim_.expand(dq, du);
    u1.update(1.0, du, 1.0);
    if (hooks_) {
      TimeMonitor tm(t_contact);
      hooks_->after_update(u0, u1);
    }
    ++res.iterations;
    // the next iterate will most likely be the last (a tenth of the target predicted): its
    // Newton matrix would go unused, so only the residual is assembled there
    const double next = predicted_next(res.residuals);
    with_matrix = !(opt_.skip_last_matrix && next >= 0 && next < 0.1 * target);
  }
}

}  // namespace emc::time
