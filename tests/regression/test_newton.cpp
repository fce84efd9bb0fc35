// Newton converges quadratically on a large-deformation step (docs/THEORY.md §1.4: the exact,
// non-symmetric energy-momentum tangent). Linear solves are direct (KLU2) so that the rate
// measured is Newton's own.
#include <gtest/gtest.h>

#include <Tpetra_Core.hpp>
#include <cmath>

#include "emcontact/app/input_schema.hpp"
#include "emcontact/app/meshes.hpp"
#include "emcontact/app/simulation.hpp"
#include "emcontact/fem/discretization.hpp"
#include "emcontact/time/newton.hpp"

namespace {

Teuchos::RCP<emc::Vector> owned_initial_velocity(const emc::fem::Discretization& disc) {
  const auto V = emc::fem::initial_velocity(disc.model());
  auto out = Teuchos::rcp(new emc::Vector(disc.owned_map()));
  auto h = out->getLocalViewHost(Tpetra::Access::OverwriteAll);
  for (std::size_t l = 0; l < disc.owned_map()->getNodeNumElements(); ++l)
    h(l, 0) = V[disc.owned_map()->getGlobalElement(static_cast<emc::LO>(l))];
  return out;
}

// one step of 0.05 s at 20 rad/s: the box turns by 1 rad and stretches by its spin
emc::fem::Model large_step_model(const Teuchos::RCP<const emc::Comm>& comm,
                                 Teuchos::RCP<Teuchos::ParameterList>* params = nullptr) {
  const std::string file = std::string(EMC_TEST_DIR) + "/tumbling.xml";
  const auto in =
      emc::app::read_input(file, {"Time/dt=0.05", "Bodies/block/Initial/angular velocity={0,3,20}",
                                  "Bodies/block/Initial/velocity={0,0,0}"});
  auto meshes = emc::app::build_meshes(*in.params, in.dir, file, *comm);
  if (params) *params = in.params;
  return emc::fem::build_model(*in.params, std::move(meshes), file);
}

}  // namespace

TEST(Newton, QuadraticOnLargeDeformationStep) {
  auto comm = Tpetra::getDefaultComm();
  Teuchos::RCP<Teuchos::ParameterList> params;
  auto model = large_step_model(comm, &params);
  const auto& in = *params;
  const emc::fem::Discretization disc(model, emc::fem::distribute(model, comm), comm);
  emc::linalg::Elimination elim(disc.owned_map());
  auto linear = in.sublist("Solver").sublist("Linear");
  linear.set("type", comm->getSize() == 1 ? "klu2" : "gmres");
  linear.set("tolerance", 1e-14);
  emc::linalg::LinearSolver solver(linear, comm);
  emc::time::NewtonOptions opt;
  opt.rtol = 1e-16;  // run until round-off stops it
  opt.max_iterations = 12;
  emc::time::Newton newton(disc, elim, solver, opt);

  emc::Vector u0(disc.owned_map()), u1(disc.owned_map());
  const auto V0 = owned_initial_velocity(disc);
  u1.assign(u0);
  const auto res = newton.solve(u0, *V0, 0.05, u1);
  const auto& r = res.residuals;
  ASSERT_GE(r.size(), 4u);
  for (std::size_t k = 0; k < r.size(); ++k)
    std::printf("  iterate %zu: |P^T g| = %.3e\n", k, r[k]);
  // order estimates p_k = log(r_{k+1}/r_k) / log(r_k/r_{k-1}) while well above round-off
  const double noise = 1e-13 * r[0];  // round-off floor here is about 2e-15 r[0]
  double best = 0;
  for (std::size_t k = 1; k + 1 < r.size(); ++k)
    if (r[k + 1] > noise && r[k] < r[k - 1]) {
      const double p = std::log(r[k + 1] / r[k]) / std::log(r[k] / r[k - 1]);
      std::printf("  order estimate at iterate %zu: %.2f\n", k + 1, p);
      best = std::max(best, p);
    }
  EXPECT_GT(best, 1.8);
  EXPECT_LT(r.back(), 1e-9 * r[0]);
  // the step is genuinely large: the displacement is a sizeable fraction of the body
  EXPECT_GT(u1.normInf(), 0.1);
}

/// The large step solved several times, with the results and solutions of every pass.
class NewtonPasses : public ::testing::Test {
 protected:
  Teuchos::RCP<const emc::Comm> comm = Tpetra::getDefaultComm();
  Teuchos::RCP<Teuchos::ParameterList> params;
  emc::fem::Model model = large_step_model(comm, &params);
  emc::fem::Discretization disc{model, emc::fem::distribute(model, comm), comm};
  std::vector<emc::time::NewtonResult> runs;
  std::vector<emc::Vector> solutions;

  /// Solves the step `passes` times from u = 0 with one Newton (GMRES + ILU to 1e-13,
  /// options `opt`); before the last pass, when `wrong_last`, its contraction estimate is set
  /// far too small.
  void solve_passes(const emc::time::NewtonOptions& opt, int passes, bool wrong_last) {
    auto linear = params->sublist("Solver").sublist("Linear");
    linear.set("type", "gmres");
    linear.set("preconditioner", "ilu");  // on every backend (auto takes Chebyshev on threads)
    linear.set("tolerance", 1e-13);
    const auto V0 = owned_initial_velocity(disc);
    emc::Vector u0(disc.owned_map()), u1(disc.owned_map());
    emc::linalg::Elimination elim(disc.owned_map());
    emc::linalg::LinearSolver solver(linear, comm);
    emc::time::Newton newton(disc, elim, solver, opt);
    for (int pass = 0; pass < passes; ++pass) {
      u1.assign(u0);
      if (wrong_last && pass == passes - 1) newton.set_contraction(1e-30);
      runs.push_back(newton.solve(u0, *V0, 0.05, u1));
      ASSERT_TRUE(runs.back().converged) << runs.back().failure;
      solutions.emplace_back(u1, Teuchos::Copy);
    }
  }
};

// Inexact Newton (Newton::linear_tolerance): solving each linear system only to what the
// quadratic Newton step needs leaves the iterates those of solves to the full tolerance (the
// linear error is kept below 1% of the next residual), with fewer Krylov iterations. The
// same step is solved twice so that the second solve also adapts its first tolerance.
TEST_F(NewtonPasses, AdaptiveLinearToleranceKeepsTheIterates) {
  for (bool adaptive : {false, true}) {
    emc::time::NewtonOptions opt;
    opt.rtol = 1e-12;
    opt.adaptive_linear_tolerance = adaptive;
    solve_passes(opt, 2, false);
  }
  ASSERT_EQ(runs.size(), 4u);
  for (int pass = 0; pass < 2; ++pass) {
    const auto& exact = runs[pass].residuals;
    const auto& inexact = runs[2 + pass].residuals;
    std::printf("pass %d: Krylov iterations %d (fixed tolerance) vs %d (adaptive)\n", pass,
                runs[pass].linear_iterations, runs[2 + pass].linear_iterations);
    ASSERT_EQ(exact.size(), inexact.size());
    for (std::size_t k = 0; k < exact.size(); ++k) {
      std::printf("  iterate %zu: %.6e vs %.6e\n", k, exact[k], inexact[k]);
      if (exact[k] > 100 * runs[pass].floor)  // above round-off the iterates agree
        EXPECT_NEAR(inexact[k] / exact[k], 1.0, 0.05);
      else  // at round-off: both at its level
        EXPECT_LT(inexact[k], 100 * runs[pass].floor);
    }
    EXPECT_LT(runs[2 + pass].linear_iterations, runs[pass].linear_iterations);
  }
}

// The iterate predicted to converge is assembled without its Newton matrix (it would go
// unused). That changes nothing: the same iterates bit for bit, with or without the skip,
// including when the prediction fails and the matrix is assembled after all (third pass: a
// contraction estimate far too small predicts convergence after the first solve).
TEST_F(NewtonPasses, SkippingTheLastMatrixChangesNothing) {
  for (bool skip : {false, true}) {
    emc::time::NewtonOptions opt;
    opt.rtol = 1e-11;  // the last iterate, 1.1e-9 r_0, is predicted at 2e-10 r_0
    opt.skip_last_matrix = skip;
    solve_passes(opt, 3, true);
  }
  ASSERT_EQ(runs.size(), 6u);
  for (int pass = 0; pass < 3; ++pass) {
    const auto& with = runs[3 + pass];
    EXPECT_EQ(runs[pass].residuals, with.residuals);
    emc::Vector diff(solutions[pass], Teuchos::Copy);
    diff.update(-1.0, solutions[3 + pass], 1.0);
    EXPECT_EQ(diff.normInf(), 0.0);
    EXPECT_EQ(runs[pass].extra_assemblies, 0);  // never skipped
    EXPECT_EQ(runs[pass].matrices, static_cast<int>(runs[pass].residuals.size()));
    // with the skip, the last iterate had no matrix (each solve had one)
    EXPECT_EQ(with.matrices, with.iterations);
    std::printf("pass %d: %zu iterates, matrices assembled again after a wrong prediction: %d\n",
                pass, with.residuals.size(), with.extra_assemblies);
    EXPECT_EQ(with.extra_assemblies, pass == 2 ? 1 : 0);
  }
}

// docs/THEORY.md §6.9, §1.7: a search solve (relative tolerance 1e-4) continued by a final solve
// from its iterate (reference: the search solve's first residual) ends where one whole solve
// ends, to the Newton tolerance; and only the solve from the start iterate sets the contraction
// estimate C that the next step's first linear tolerance uses (the final solve's r_1 / r_0^2 is
// not that of a first iterate).
TEST_F(NewtonPasses, SearchThenFinalSolveReachesTheWholeSolve) {
  emc::time::NewtonOptions opt;
  opt.rtol = 1e-11;
  solve_passes(opt, 1, false);
  const auto V0 = owned_initial_velocity(disc);
  auto linear = params->sublist("Solver").sublist("Linear");
  linear.set("type", "gmres");
  linear.set("tolerance", 1e-13);
  emc::linalg::Elimination elim(disc.owned_map());
  emc::linalg::LinearSolver solver(linear, comm);
  emc::time::Newton newton(disc, elim, solver, opt);
  emc::Vector u0(disc.owned_map()), u1(disc.owned_map());
  const auto search = newton.solve(u0, *V0, 0.05, u1, 0.0, 1e-4);
  ASSERT_TRUE(search.converged) << search.failure;
  const double C = newton.contraction();
  const auto final = newton.solve(u0, *V0, 0.05, u1, search.residuals.front());
  ASSERT_TRUE(final.converged) << final.failure;
  std::printf("search %d + final %d iterations against %d whole\n", search.iterations,
              final.iterations, runs[0].iterations);
  EXPECT_LT(search.iterations, runs[0].iterations);  // it stopped early
  EXPECT_LE(final.residuals.back(), 1e-11 * search.residuals.front());
  emc::Vector diff(u1, Teuchos::Copy);
  diff.update(-1.0, solutions[0], 1.0);
  EXPECT_LT(diff.normInf(), 1e-8 * solutions[0].normInf());
  EXPECT_GT(C, 0.0);
  EXPECT_EQ(newton.contraction(), C);  // the final solve left C alone
}

// docs/THEORY.md §1.6, the round-off floor's inertia term: far from the reference configuration
// (|u| many step increments |u_{n+1} - u_n|) the rounding of u_{n+1} leaves a residual of about
// eps (2/dt^2) M |u|, which outgrows every other term of the floor after some thousand steps
// (the tumbling box failed at step 1749 to 2832 for dt = 1e-4 to 1e-9). Here the box starts as
// far out as 10^4 steps of its own speed would take it (a rigid translation: the same motion
// as from u = 0) and takes 10 steps of each small dt: every step converges, and E and L are
// conserved to round-off (the velocities' is 2 eps |u| / (dt |V|) = 4.4e-12 relative).
TEST(Newton, SmallStepsFarFromTheReferenceConfiguration) {
  auto comm = Tpetra::getDefaultComm();
  for (const double dt : {1e-4, 1e-6, 1e-9}) {
    emc::app::Options o;
    o.input = std::string(EMC_TEST_DIR) + "/tumbling.xml";
    char set_dt[40];
    std::snprintf(set_dt, sizeof set_dt, "Time/dt=%.17g", dt);
    o.overrides = {set_dt, "Time/end=1"};
    auto sim = emc::app::setup(o, comm);
    auto& s = sim->state;
    // the translation |V_max| 1e4 dt along (1, 1, 1)/sqrt(3)
    const double far = 1e4 * dt * s.V->normInf();
    s.u->putScalar(far / std::sqrt(3.0));
    const auto m0 = sim->disc->monitors(*s.u, *s.V);
    const double E0 = m0.kinetic + m0.elastic + m0.potential;
    double dE = 0, dL = 0;
    for (int step = 0; step < 10; ++step) {
      const auto rep = sim->stepper->advance();
      ASSERT_EQ(rep.cuts, 0) << "dt " << dt << ": " << rep.last_failure;
      const auto m = sim->disc->monitors(*s.u, *s.V);
      dE = std::max(dE, std::fabs(m.kinetic + m.elastic + m.potential - E0) / E0);
      for (int i = 0; i < 3; ++i)
        dL = std::max(dL, std::fabs(m.L[i] - m0.L[i]) / std::hypot(m0.L[0], m0.L[1], m0.L[2]));
    }
    std::printf("dt %.0e, |u| %.3g: 10 steps, E drift %.3e, L drift %.3e\n", dt, far, dE, dL);
    EXPECT_LT(dE, 1e-10);
    EXPECT_LT(dL, 1e-10);
  }
}
