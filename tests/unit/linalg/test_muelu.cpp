// Smoothed aggregation with rigid-body modes (linalg/rigid_modes, LinearSolver with
// preconditioner = muelu): the six modes lie in the null space of the assembled stiffness of a
// free body, and the AMG-preconditioned solve of a clamped body reaches the true residual, on
// the ranks ctest gives it (1 and 2: the coarse solve of 2+ ranks is not Amesos2 KLU2's).
#include <gtest/gtest.h>

#include <Tpetra_Core.hpp>
#include <cmath>

#include "emcontact/fem/discretization.hpp"
#include "emcontact/linalg/elimination.hpp"
#include "emcontact/linalg/linear_solver.hpp"
#include "emcontact/linalg/parameters.hpp"
#include "emcontact/linalg/rigid_modes.hpp"
#include "support/box_model.hpp"

using namespace emc;

namespace {

/// The Newton matrix (2/dt^2) M + K of a box at rest (u = 0), shifted and turned so that the
/// rotations are not about the origin's axes.
struct Box {
  fem::Model m = test::box_model(6);
  std::unique_ptr<fem::Discretization> disc;
  Teuchos::RCP<FEMatrix> A;
  Teuchos::RCP<Vector> X;

  explicit Box(double dt) {
    for (std::size_t n = 0; n < m.X.size() / 3; ++n) {
      const double x = m.X[3 * n], y = m.X[3 * n + 1];
      m.X[3 * n] = 0.8 * x - 0.6 * y + 2.0;
      m.X[3 * n + 1] = 0.6 * x + 0.8 * y - 1.0;
      m.X[3 * n + 2] += 0.5;
    }
    disc = std::make_unique<fem::Discretization>(m, Tpetra::getDefaultComm());
    const auto map = disc->owned_map();
    Vector u(map), V(map), r(map);
    A = Teuchos::rcp(new FEMatrix(disc->graph()));
    disc->assemble(u, V, u, dt, A.get(), r, nullptr);
    X = disc->reference_positions();
  }
};

/// The validated Solver/Linear list with the given preconditioner and near null space.
Teuchos::ParameterList linear_parameters(const std::string& null_space,
                                         const std::string& prec = "muelu", int from = 150000,
                                         int chebyshev_from = 8000) {
  Teuchos::ParameterList p;
  p.set("preconditioner", prec);
  p.set("multigrid from equations", from);
  p.set("chebyshev from equations", chebyshev_from);
  p.set("tolerance", 1e-10);
  p.set("multigrid near null space", null_space);
  p.validateParametersAndSetDefaults(*linalg::valid_linear_parameters());
  return p;
}

}  // namespace

// At u = 0 the linearised stiffness annihilates rigid motions exactly; with dt = 1e8 the mass
// term is 1e-16 of M, below round-off of K. So |K m| / (|K|_F |m|) is round-off (1e-16 per
// entry, a few dozen entries per row): 1e-12 leaves a margin, and a generic vector gives
// O(0.1), which the second check makes sure of.
TEST(RigidModes, InNullSpaceOfFreeBodyStiffness) {
  Box box(1e8);
  const auto modes = linalg::rigid_body_modes(*box.X);
  ASSERT_EQ(modes->getNumVectors(), 6u);
  MultiVector Km(modes->getMap(), 6);
  box.A->apply(*modes, Km);
  const double normA = box.A->getFrobeniusNorm();
  std::vector<double> km(6), mn(6);
  Km.norm2(Teuchos::arrayViewFromVector(km));
  modes->norm2(Teuchos::arrayViewFromVector(mn));
  for (int j = 0; j < 6; ++j) {
    EXPECT_GT(mn[j], 0) << "mode " << j;
    EXPECT_LT(km[j] / (normA * mn[j]), 1e-12) << "mode " << j;
  }
  Vector v(box.X->getMap()), Kv(box.X->getMap());
  v.randomize();
  box.A->apply(v, Kv);
  EXPECT_GT(Kv.norm2() / (normA * v.norm2()), 1e-3) << "a generic vector is not in the null space";
}

// Rows with no off-diagonal entry (eliminated dofs) get zero modes when A is given.
TEST(RigidModes, ZeroAtEliminatedDofs) {
  Box box(1e-3);
  std::vector<GO> fixed;
  const auto map = box.disc->owned_map();
  for (LO l = 0; l < static_cast<LO>(map->getNodeNumElements()); ++l)
    if (map->getGlobalElement(l) % 3 == 2) fixed.push_back(map->getGlobalElement(l));  // all z
  linalg::Elimination elim(map);
  elim.set_constraints(fixed, {}, {});
  const auto Ar = elim.reduce_matrix(box.A);
  const auto modes = linalg::rigid_body_modes(*box.X, Ar.get());
  const auto m = modes->getLocalViewHost(Tpetra::Access::ReadOnly);
  for (LO l = 0; l < static_cast<LO>(m.extent(0)); ++l)
    for (int j = 0; j < 6; ++j)
      if (map->getGlobalElement(l) % 3 == 2)
        EXPECT_EQ(m(l, j), 0.0);
      else if (j == map->getGlobalElement(l) % 3)
        EXPECT_EQ(m(l, j), 1.0);
}

/// The Newton matrix of the box clamped at its bottom (z = 0.5), P^T A P + D.
Teuchos::RCP<Matrix> clamped(Box& box, linalg::Elimination& elim) {
  const auto map = box.disc->owned_map();
  std::vector<GO> fixed;
  const auto X = box.X->getLocalViewHost(Tpetra::Access::ReadOnly);
  for (LO l = 0; l < static_cast<LO>(map->getNodeNumElements()); ++l)
    if (std::fabs(X(l - l % 3 + 2, 0) - 0.5) < 1e-12) fixed.push_back(map->getGlobalElement(l));
  elim.set_constraints(fixed, {}, {});
  return elim.reduce_matrix(box.A);
}

/// Solves Ar x = b for a random b, zero on the clamped dofs' rows like Newton's right-hand
/// sides: the true residual |b - A x| / |b| is within the solver's own check (100 x its
/// tolerance) and is the one the solver reports.
linalg::SolveStats solve_random(linalg::LinearSolver& solver, const Box& box,
                                linalg::Elimination& elim, const Teuchos::RCP<Matrix>& Ar,
                                const std::string& what) {
  const auto map = box.disc->owned_map();
  Vector u(map), b(map), x(map), r(map);
  solver.set_configuration(*box.X, u);
  b.randomize();
  elim.reduce_residual(b, r);
  Tpetra::deep_copy(b, r);
  const auto st = solver.solve(Ar, b, x);
  Ar->apply(x, r);
  r.update(1.0, b, -1.0);
  EXPECT_LT(r.norm2() / b.norm2(), 1e-8) << what;
  EXPECT_NEAR(st.true_residual, r.norm2() / b.norm2(), 1e-14) << what;
  return st;
}

// The box clamped at z = 0.5 (its bottom), dt 100x the explicit step (stiffness-dominated),
// solved to 1e-10 with GMRES + smoothed aggregation: the true residual |b - A x| / |b|
// is within the solver's own check (100 x tolerance), with rigid-body modes and translations.
TEST(MueLuSolve, ReachesTrueResidual) {
  if (!linalg::muelu_available()) GTEST_SKIP() << "built without MueLu";
  Box box(1e-2);
  const auto map = box.disc->owned_map();
  linalg::Elimination elim(map);
  const auto Ar = clamped(box, elim);
  for (const std::string ns : {"rigid body modes", "translations"}) {
    linalg::LinearSolver solver(linear_parameters(ns), map->getComm());
    EXPECT_GT(solve_random(solver, box, elim, Ar, ns).iterations, 0) << ns;
  }
}

// The same system with GMRES + Chebyshev (degree 3 in the diagonally scaled matrix, whose
// spectrum Ifpack2 estimates by power iterations): the true residual too, with fewer Krylov
// iterations than without a preconditioner.
TEST(ChebyshevSolve, ReachesTrueResidual) {
  Box box(1e-2);
  const auto map = box.disc->owned_map();
  linalg::Elimination elim(map);
  const auto Ar = clamped(box, elim);
  int iterations[2] = {0, 0};
  for (const std::string prec : {"chebyshev", "none"}) {
    linalg::LinearSolver solver(linear_parameters("rigid body modes", prec), map->getComm());
    EXPECT_FALSE(solver.uses_positions());
    iterations[prec == "none"] = solve_random(solver, box, elim, Ar, prec).iterations;
  }
  EXPECT_GT(iterations[0], 0);
  EXPECT_LT(2 * iterations[0], iterations[1]);
}

// preconditioner = auto takes muelu from `multigrid from equations` on (the box has 1029),
// below it chebyshev on 2+ threads or from `chebyshev from equations` on, else ilu, and each
// reaches the true residual.
TEST(MueLuSolve, AutoChoosesBySize) {
  Box box(1e-2);
  const auto map = box.disc->owned_map();
  linalg::Elimination elim(map);
  const auto Ar = clamped(box, elim);
  for (const int from : {1000, 2000})
    for (const int chebyshev_from : {500, 8000}) {
      linalg::LinearSolver solver(
          linear_parameters("rigid body modes", "auto", from, chebyshev_from), map->getComm());
      EXPECT_TRUE(solver.uses_positions());
      solve_random(solver, box, elim, Ar, "auto from " + std::to_string(from));
      const bool threads = ExecSpace().concurrency() > 1;
      const std::string below = threads || chebyshev_from <= 1029 ? "chebyshev" : "ilu";
      const std::string chosen = from <= 1029 && linalg::muelu_available() ? "muelu" : below;
      EXPECT_NE(solver.description().find(chosen), std::string::npos) << solver.description();
    }
}
