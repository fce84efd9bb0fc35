// The elimination of docs/THEORY.md §3: the reduced matrix P^T A P + D and residual P^T g that
// the code builds with Tpetra equal a dense reference built here, on 1 and 2 ranks; the
// expansion du = P dq moves a stick slave exactly as N times its master nodes.
#include <gtest/gtest.h>

#include <Tpetra_Core.hpp>
#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include "emcontact/linalg/elimination.hpp"
#include "emcontact/linalg/p_matrix.hpp"
#include "emcontact/linalg/structured_reduction.hpp"

using namespace emc;

namespace {

constexpr int kN = 18;  // 6 nodes x 3 dofs

/// A dense non-symmetric matrix with a random pattern, the same on every rank.
std::vector<std::vector<double>> dense_matrix() {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> d(-1, 1);
  std::vector<std::vector<double>> A(kN, std::vector<double>(kN, 0.0));
  for (int i = 0; i < kN; ++i)
    for (int j = 0; j < kN; ++j) A[i][j] = (i == j) ? 10 + d(rng) : (rng() % 3 == 0 ? d(rng) : 0.0);
  return A;
}

/// Row i of a distributed matrix (owned here) as a dense vector.
std::vector<double> dense_row(const Matrix& A, GO i) {
  std::vector<double> row(kN, 0.0);
  const std::size_t n = A.getNumEntriesInGlobalRow(i);
  Matrix::nonconst_global_inds_host_view_type cols("c", n);
  Matrix::nonconst_values_host_view_type vals("v", n);
  std::size_t got = n;
  A.getGlobalRowCopy(i, cols, vals, got);
  for (std::size_t k = 0; k < got; ++k) row[cols(k)] += vals(k);
  return row;
}

/// The dense matrix distributed over `map`.
Teuchos::RCP<Matrix> distributed(const std::vector<std::vector<double>>& Ad,
                                 const Teuchos::RCP<const Map>& map) {
  auto A = Teuchos::rcp(new Matrix(map, kN));
  for (std::size_t l = 0; l < map->getNodeNumElements(); ++l) {
    const GO i = map->getGlobalElement(l);
    std::vector<GO> cols;
    std::vector<double> vals;
    for (int j = 0; j < kN; ++j)
      if (Ad[i][j] != 0) {
        cols.push_back(j);
        vals.push_back(Ad[i][j]);
      }
    A->insertGlobalValues(i, Teuchos::ArrayView<const GO>(cols),
                          Teuchos::ArrayView<const double>(vals));
  }
  A->fillComplete();
  return A;
}

/// max |Ar - R| over my rows and max |R| (in `norm`), both reduced over the ranks.
double max_error(const Matrix& Ar, const std::vector<std::vector<double>>& R, const Map& map,
                 double& norm) {
  double err = 0, nrm = 0;
  for (std::size_t l = 0; l < map.getNodeNumElements(); ++l) {
    const GO i = map.getGlobalElement(l);
    const auto row = dense_row(Ar, i);
    for (int j = 0; j < kN; ++j) {
      err = std::max(err, std::fabs(row[j] - R[i][j]));
      nrm = std::max(nrm, std::fabs(R[i][j]));
    }
  }
  double g[2] = {0, 0}, l[2] = {err, nrm};
  Teuchos::reduceAll(*map.getComm(), Teuchos::REDUCE_MAX, 2, l, g);
  norm = g[1];
  return g[0];
}

}  // namespace

TEST(Elimination, MatchesDenseReference) {
  auto comm = Tpetra::getDefaultComm();
  auto map = Teuchos::rcp(new Map(kN, 0, comm));
  const auto Ad = dense_matrix();
  auto A = distributed(Ad, map);

  // node 0 fixed; node 5 (dofs 15-17) a stick slave on the facet of nodes 1, 2, 4 with
  // N = (0.2, 0.5, 0.3) (§4), whose dummies get beta; node 2 dof 7 is fixed too, so its
  // column of P vanishes also in the slave's rows.
  const double N[3] = {0.2, 0.5, 0.3};
  const int master[3] = {1, 2, 4};
  std::vector<GO> fixed_all = {0, 1, 2, 7};
  std::vector<linalg::PRow> rows_all;
  for (int c = 0; c < 3; ++c) {
    linalg::PRow r{15 + c, {}, {}};
    for (int k = 0; k < 3; ++k)
      if (3 * master[k] + c != 7) {
        r.cols.push_back(3 * master[k] + c);
        r.weights.push_back(N[k]);
      }
    rows_all.push_back(r);
  }
  const double beta = 3.7;
  std::vector<GO> fixed;
  std::vector<linalg::PRow> rows;
  std::vector<std::pair<GO, double>> dummies;
  for (GO g : fixed_all)
    if (map->isNodeGlobalElement(g)) fixed.push_back(g);
  for (const auto& r : rows_all)
    if (map->isNodeGlobalElement(r.row)) {
      rows.push_back(r);
      dummies.emplace_back(r.row, beta);
    }
  linalg::Elimination elim(map);
  elim.set_constraints(fixed, rows, dummies);
  auto Ar = elim.reduce_matrix(A);

  // dense reference
  std::vector<std::vector<double>> P(kN, std::vector<double>(kN, 0.0)),
      R(kN, std::vector<double>(kN, 0.0));
  for (int i = 0; i < kN; ++i) P[i][i] = 1;
  for (GO g : fixed_all) P[g][g] = 0;
  for (const auto& r : rows_all) {
    P[r.row][r.row] = 0;
    for (std::size_t k = 0; k < r.cols.size(); ++k) P[r.row][r.cols[k]] = r.weights[k];
  }
  for (int i = 0; i < kN; ++i)
    for (int j = 0; j < kN; ++j) {
      double s = 0;
      for (int a = 0; a < kN; ++a)
        for (int b = 0; b < kN; ++b) s += P[a][i] * Ad[a][b] * P[b][j];
      R[i][j] = s;
    }
  for (GO g : fixed_all) R[g][g] += 1;
  for (const auto& r : rows_all) R[r.row][r.row] += beta;

  double norm = 0;
  const double gerr = max_error(*Ar, R, *map, norm);
  EXPECT_LT(gerr, 1e-14 * norm);

  // with a right factor Pt (slave rows differ) and an X (some entries in rows owned elsewhere,
  // duplicates summed): P^T A Pt + X + D (docs/THEORY.md §5.4)
  {
    std::vector<linalg::PRow> pt_all;
    for (const auto& r : rows_all) {
      linalg::PRow q = r;
      for (double& w : q.weights) w *= 1.3;
      q.cols.push_back(9);
      q.weights.push_back(0.25 + r.row);
      pt_all.push_back(q);
    }
    std::vector<linalg::Entry> X_all = {
        {15, 3, 0.5}, {3, 16, -0.7}, {12, 12, 0.1}, {12, 12, 0.2}, {4, 17, 1.5}};
    std::vector<linalg::PRow> pt;
    for (const auto& r : pt_all)
      if (map->isNodeGlobalElement(r.row)) pt.push_back(r);
    std::vector<linalg::Entry> X;
    if (comm->getRank() == 0) X = X_all;  // rank 0 inserts every entry, wherever it is owned
    elim.set_constraints(fixed, rows, dummies);
    elim.set_linearisation(pt, X);
    auto Ar2 = elim.reduce_matrix(A);
    std::vector<std::vector<double>> Pt = P, R2(kN, std::vector<double>(kN, 0.0));
    for (const auto& r : pt_all) {
      std::fill(Pt[r.row].begin(), Pt[r.row].end(), 0.0);
      for (std::size_t k = 0; k < r.cols.size(); ++k) Pt[r.row][r.cols[k]] += r.weights[k];
    }
    for (int i = 0; i < kN; ++i)
      for (int j = 0; j < kN; ++j) {
        double v = 0;
        for (int a = 0; a < kN; ++a)
          for (int b = 0; b < kN; ++b) v += P[a][i] * Ad[a][b] * Pt[b][j];
        R2[i][j] = v;
      }
    for (GO g : fixed_all) R2[g][g] += 1;
    for (const auto& r : rows_all) R2[r.row][r.row] += beta;
    for (const auto& e : X_all) R2[e.row][e.col] += e.value;
    double e2 = 0;
    for (std::size_t l = 0; l < map->getNodeNumElements(); ++l) {
      const GO i = map->getGlobalElement(l);
      const auto row = dense_row(*Ar2, i);
      for (int j = 0; j < kN; ++j) e2 = std::max(e2, std::fabs(row[j] - R2[i][j]));
    }
    double ge2 = 0;
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, 1, &e2, &ge2);
    EXPECT_LT(ge2, 1e-13 * norm);
    elim.set_constraints(fixed, rows, dummies);  // back to P alone for the checks below
  }

  // P^T g and P dq against the dense P
  Vector g(map), R1(map), dq(map), du(map);
  g.randomize();
  dq.randomize();
  elim.reduce_residual(g, R1);
  elim.expand(dq, du);
  Vector gall(Teuchos::rcp(new Map(kN, 0, comm, Tpetra::LocallyReplicated)));
  Vector qall(gall.getMap());
  gall.doImport(g, Import(map, gall.getMap()), Tpetra::INSERT);
  qall.doImport(dq, Import(map, qall.getMap()), Tpetra::INSERT);
  auto gh = gall.getLocalViewHost(Tpetra::Access::ReadOnly);
  auto qh = qall.getLocalViewHost(Tpetra::Access::ReadOnly);
  auto rh = R1.getLocalViewHost(Tpetra::Access::ReadOnly);
  auto uh = du.getLocalViewHost(Tpetra::Access::ReadOnly);
  double e1 = 0, e2 = 0;
  for (std::size_t l = 0; l < map->getNodeNumElements(); ++l) {
    const GO i = map->getGlobalElement(l);
    double ptg = 0, pdq = 0;
    for (int a = 0; a < kN; ++a) {
      ptg += P[a][i] * gh(a, 0);
      pdq += P[i][a] * qh(a, 0);
    }
    e1 = std::max(e1, std::fabs(ptg - rh(l, 0)));
    e2 = std::max(e2, std::fabs(pdq - uh(l, 0)));
  }
  EXPECT_LT(e1, 1e-14);
  EXPECT_LT(e2, 1e-14);
  // the slave moves with N du_m (dq of fixed dofs is whatever; P ignores it)
  auto full_du = Vector(qall.getMap());
  full_du.doImport(du, Import(map, qall.getMap()), Tpetra::INSERT);
  auto dh = full_du.getLocalViewHost(Tpetra::Access::ReadOnly);
  for (int c = 0; c < 3; ++c) {
    double expect = 0;
    for (int k = 0; k < 3; ++k) expect += N[k] * dh(3 * master[k] + c, 0);
    EXPECT_NEAR(dh(15 + c, 0), expect, 1e-14);
  }
}

// docs/THEORY.md §9: P^T g through P^T formed as a matrix (the threaded backends' path) and
// through Tpetra's transposed apply both equal the dense P^T g, also after P's values change
// (a P^T formed for the old P must not be reused), and a repeated product is bit for bit the same.
TEST(Elimination, TransposeFormedOrAppliedEqualsDensePTg) {
  auto comm = Tpetra::getDefaultComm();
  auto map = Teuchos::rcp(new Map(kN, 0, comm));
  Vector g(map), R(map), again(map);
  {
    auto gh = g.getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (std::size_t l = 0; l < map->getNodeNumElements(); ++l)
      gh(l, 0) = std::sin(1.0 + static_cast<double>(map->getGlobalElement(l)));
  }
  // two slaves (nodes 5 and 3) on masters {1, 2, 4} and {0, 1, 2}: columns of P with several
  // entries, node 0's dofs fixed
  const int slave[2] = {5, 3}, master[2][3] = {{1, 2, 4}, {0, 1, 2}};
  for (const bool formed : {false, true})
    for (const double shift : {0.0, 0.15}) {
      const double N[2][3] = {{0.2 + shift, 0.5, 0.3 - shift}, {0.6, 0.1 + shift, 0.3 - shift}};
      std::vector<std::vector<double>> P(kN, std::vector<double>(kN, 0.0));
      for (int i = 3; i < kN; ++i) P[i][i] = 1;
      std::vector<linalg::PRow> rows;
      for (int s = 0; s < 2; ++s)
        for (int c = 0; c < 3; ++c) {
          const GO row = 3 * slave[s] + c;
          P[row][row] = 0;
          linalg::PRow r{row, {}, {}};
          for (int k = 0; k < 3; ++k)
            if (master[s][k] != 0) {  // node 0 fixed: its columns vanish
              r.cols.push_back(3 * master[s][k] + c);
              r.weights.push_back(N[s][k]);
              P[row][3 * master[s][k] + c] = N[s][k];
            }
          if (map->isNodeGlobalElement(row)) rows.push_back(r);
        }
      std::vector<GO> fixed;
      for (GO d = 0; d < 3; ++d)
        if (map->isNodeGlobalElement(d)) fixed.push_back(d);
      linalg::Elimination elim(map);
      elim.form_transpose(formed);
      elim.set_constraints(fixed, rows, {});
      elim.reduce_residual(g, R);
      if (shift == 0) {  // the same Elimination, new values of P: P^T must follow
        for (auto& r : rows)
          for (double& w : r.weights) w *= 0.5;
        for (int i = 9; i < kN; ++i)
          for (int j = 0; j < kN; ++j)
            if (i != j && P[i][j] != 0) P[i][j] *= 0.5;
        elim.set_constraints(fixed, rows, {});
        elim.reduce_residual(g, R);
      }
      elim.reduce_residual(g, again);
      Vector gall(Teuchos::rcp(new Map(kN, 0, comm, Tpetra::LocallyReplicated)));
      gall.doImport(g, Import(map, gall.getMap()), Tpetra::INSERT);
      const auto gh = gall.getLocalViewHost(Tpetra::Access::ReadOnly);
      const auto rh = R.getLocalViewHost(Tpetra::Access::ReadOnly);
      const auto ah = again.getLocalViewHost(Tpetra::Access::ReadOnly);
      double err = 0;
      bool same = true;
      for (std::size_t l = 0; l < map->getNodeNumElements(); ++l) {
        const GO i = map->getGlobalElement(l);
        double ptg = 0;
        for (int a = 0; a < kN; ++a) ptg += P[a][i] * gh(a, 0);
        err = std::max(err, std::fabs(ptg - rh(l, 0)));
        same = same && rh(l, 0) == ah(l, 0);
      }
      // |g| <= 1 and at most 3 terms per entry: a few ulps
      EXPECT_LT(err, 1e-15) << "formed " << formed << " shift " << shift;
      EXPECT_TRUE(same) << "formed " << formed << " shift " << shift;
    }
}

// A 0/1 diagonal P (fixed dofs, and stick slaves on rigid masters: empty rows) takes the
// masked path (no sparse products): A's entries survive only in kept rows and columns, D sits
// on the diagonal. Products with 1 and 0 are exact, so the result must equal the dense
// reference exactly; a second matrix on the same graph and a new set of constraints too.
TEST(Elimination, MaskedPathIsExact) {
  auto comm = Tpetra::getDefaultComm();
  auto map = Teuchos::rcp(new Map(kN, 0, comm));
  auto Ad = dense_matrix();
  std::vector<std::vector<GO>> fixed_sets = {{0, 1, 2, 7}, {4, 9, 10, 11}};
  std::vector<std::vector<GO>> slave_sets = {{15, 16, 17}, {0, 1, 2, 12}};
  const double beta = 2.5;
  linalg::Elimination elim(map);
  for (int pass = 0; pass < 3; ++pass) {
    if (pass == 2)  // same graph, new values: the saved graph copy is reused
      for (auto& row : Ad)
        for (double& v : row)
          if (v != 0) v *= -1.7;
    const auto A = distributed(Ad, map);
    const auto& fixed_all = fixed_sets[pass % 2];
    const auto& slaves_all = slave_sets[pass % 2];
    std::vector<GO> fixed;
    std::vector<linalg::PRow> rows;
    std::vector<std::pair<GO, double>> dummies;
    for (GO g : fixed_all)
      if (map->isNodeGlobalElement(g)) fixed.push_back(g);
    for (GO g : slaves_all)
      if (map->isNodeGlobalElement(g)) {
        rows.push_back({g, {}, {}});
        dummies.emplace_back(g, beta + g);
      }
    elim.set_constraints(fixed, rows, dummies);
    const auto Ar = elim.reduce_matrix(A);
    auto kept = [&](GO g) {
      return std::find(fixed_all.begin(), fixed_all.end(), g) == fixed_all.end() &&
             std::find(slaves_all.begin(), slaves_all.end(), g) == slaves_all.end();
    };
    auto kept_fixed = [&](GO g) {  // not a fixed dof (a dof both fixed and slave stays at 1)
      return std::find(fixed_all.begin(), fixed_all.end(), g) == fixed_all.end();
    };
    int mismatches = 0;
    for (std::size_t l = 0; l < map->getNodeNumElements(); ++l) {
      const GO i = map->getGlobalElement(l);
      const auto row = dense_row(*Ar, i);
      for (int j = 0; j < kN; ++j) {
        double expect = kept(i) && kept(j) ? Ad[i][j] : 0.0;
        if (i == j && !kept(i))
          expect =
              std::find(fixed_all.begin(), fixed_all.end(), i) != fixed_all.end() ? 1.0 : beta + i;
        mismatches += row[j] != expect;
      }
    }
    // P^T g and P dq with P = diag(kept): the entries kept, zeros elsewhere (P is not formed)
    Vector g(map), R(map), du(map);
    {
      auto gv = g.getLocalViewHost(Tpetra::Access::OverwriteAll);
      for (std::size_t l = 0; l < map->getNodeNumElements(); ++l)
        gv(l, 0) = 1.0 + 0.25 * static_cast<double>(map->getGlobalElement(l));
    }
    elim.reduce_residual(g, R);
    elim.expand(g, du);
    // beta again at the same dofs (a Newton iterate): only the values change
    std::vector<std::pair<GO, double>> doubled = dummies;
    for (auto& d : doubled) d.second *= 2;
    elim.set_dummy_values(doubled);
    const auto Ar2 = elim.reduce_matrix(A);
    {
      auto Rv = R.getLocalViewHost(Tpetra::Access::ReadOnly);
      auto dv = du.getLocalViewHost(Tpetra::Access::ReadOnly);
      for (std::size_t l = 0; l < map->getNodeNumElements(); ++l) {
        const GO i = map->getGlobalElement(l);
        const double expect = kept(i) ? 1.0 + 0.25 * static_cast<double>(i) : 0.0;
        mismatches += Rv(l, 0) != expect;
        mismatches += dv(l, 0) != expect;
        const bool slave =
            std::find(slaves_all.begin(), slaves_all.end(), i) != slaves_all.end() && kept_fixed(i);
        mismatches += slave && dense_row(*Ar2, i)[i] != 2 * (beta + i);
      }
    }
    int all = 0;
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, 1, &mismatches, &all);
    EXPECT_EQ(all, 0) << "pass " << pass;
  }
}

// beta per slave through set_dummies and set_dummy_betas (one kernel on D's vector on the masked
// path, the host list on the structured one) gives the reduced matrix of set_dummy_values bit
// for bit: at two iterates of a set, after a new set (the last set's dummies cleared), on both
// paths and on 1 and 2 ranks (a slave's three dofs on one rank).
TEST(Elimination, DummyBetasEqualDummyValues) {
  auto comm = Tpetra::getDefaultComm();
  auto map = Teuchos::rcp(new Map(kN, 0, comm));
  const auto A = distributed(dense_matrix(), map);
  struct Set {
    std::vector<GO> fixed;
    std::vector<int> slaves;
    bool masked;  ///< the slaves' rows empty (P a 0/1 diagonal), else tied to node 3
  };
  const std::vector<Set> sets = {{{0, 1, 2}, {1, 4}, true},
                                 {{9, 10, 11}, {0, 5}, true},
                                 {{0, 1, 2}, {2, 4}, false},
                                 {{}, {4}, true}};
  linalg::Elimination fast(map), ref(map);
  for (std::size_t pass = 0; pass < sets.size(); ++pass) {
    const Set& set = sets[pass];
    std::vector<GO> fixed, dummies;
    std::vector<linalg::PRow> rows;
    for (GO g : set.fixed)
      if (map->isNodeGlobalElement(g)) fixed.push_back(g);
    for (int n : set.slaves)
      for (int c = 0; c < 3; ++c) {
        const GO g = 3 * n + c;
        if (!map->isNodeGlobalElement(g)) continue;
        rows.push_back(set.masked ? linalg::PRow{g, {}, {}} : linalg::PRow{g, {9 + c}, {0.5}});
        dummies.push_back(g);
      }
    fast.set_constraints(fixed, rows, {});
    fast.set_dummies(dummies);
    for (int it = 0; it < 2; ++it) {  // two Newton iterates: new values at the same dummies
      Kokkos::View<double*, ExecSpace> beta("beta", dummies.size() / 3);
      auto bh = Kokkos::create_mirror_view(beta);
      std::vector<std::pair<GO, double>> diag;
      for (std::size_t k = 0; k < dummies.size(); ++k) {
        bh(k / 3) = (1 + it) * (3.25 + pass) + 0.5 * static_cast<double>(dummies[k] / 3);
        diag.emplace_back(dummies[k], bh(k / 3));
      }
      Kokkos::deep_copy(beta, bh);
      fast.set_dummy_betas(beta);
      ref.set_constraints(fixed, rows, diag);
      const auto Af = fast.reduce_matrix(A);
      std::vector<std::vector<double>> got;
      for (std::size_t l = 0; l < map->getNodeNumElements(); ++l)
        got.push_back(dense_row(*Af, map->getGlobalElement(l)));
      const auto Ar = ref.reduce_matrix(A);
      int mismatches = 0;
      for (std::size_t l = 0; l < map->getNodeNumElements(); ++l)
        mismatches += got[l] != dense_row(*Ar, map->getGlobalElement(l));
      int all = 0;
      Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, 1, &mismatches, &all);
      EXPECT_EQ(all, 0) << "set " << pass << ", iterate " << it;
    }
  }
}

namespace {

/// The dense P for slave rows and fixed dofs.
std::vector<std::vector<double>> dense_P(const std::vector<GO>& fixed,
                                         const std::vector<linalg::PRow>& p_rows) {
  std::vector<std::vector<double>> P(kN, std::vector<double>(kN, 0.0));
  for (int i = 0; i < kN; ++i) P[i][i] = 1;
  for (GO g : fixed) P[g][g] = 0;
  for (const auto& r : p_rows) {
    P[r.row][r.row] = 0;
    for (std::size_t k = 0; k < r.cols.size(); ++k) P[r.row][r.cols[k]] += r.weights[k];
  }
  return P;
}

/// The dense P^T A Pt + X + D for slave rows (P and Pt), fixed dofs (D = 1) and dummies (D = beta).
std::vector<std::vector<double>> dense_reduced(const std::vector<std::vector<double>>& Ad,
                                               const std::vector<GO>& fixed,
                                               const std::vector<linalg::PRow>& p_rows,
                                               const std::vector<linalg::PRow>& pt_rows,
                                               const std::vector<linalg::Entry>& X, double beta) {
  const auto P = dense_P(fixed, p_rows);
  std::vector<std::vector<double>> R(kN, std::vector<double>(kN, 0.0));
  auto Pt = P;
  for (const auto& r : pt_rows) {
    std::fill(Pt[r.row].begin(), Pt[r.row].end(), 0.0);
    for (std::size_t k = 0; k < r.cols.size(); ++k) Pt[r.row][r.cols[k]] += r.weights[k];
  }
  for (int i = 0; i < kN; ++i)
    for (int j = 0; j < kN; ++j)
      for (int a = 0; a < kN; ++a)
        for (int b = 0; b < kN; ++b) R[i][j] += P[a][i] * Ad[a][b] * Pt[b][j];
  for (GO g : fixed) R[g][g] += 1;
  for (const auto& r : p_rows) R[r.row][r.row] += beta;
  for (const auto& e : X) R[e.row][e.col] += e.value;
  return R;
}

}  // namespace

// The structured path finds its pattern once per set of constrained rows and columns: new
// weights and new values of A and X on the same pattern refill the same matrix and still equal
// the dense reference; a slave that moves to another facet (new columns) rebuilds the pattern.
// Rows of P, Pt and X reach dofs owned by the other rank at np2.
namespace {

/// Passes of one slave (node 5) on a facet of masters `facets[pass]`, with A, the weights and X
/// changing from pass to pass; the reduced matrix is checked against the dense reference and
/// P dq against the dense P at every pass, then `check(pass, elim, Ar)` runs.
template <class Check>
void structured_passes(bool keep_graph, const std::vector<std::array<int, 3>>& facets,
                       const Check& check) {
  auto comm = Tpetra::getDefaultComm();
  auto map = Teuchos::rcp(new Map(kN, 0, comm));
  linalg::Elimination elim(map);
  elim.keep_graph(keep_graph);
  auto Ad = dense_matrix();
  const std::vector<GO> fixed_all = {0, 1, 2};
  const double beta = 4.2;
  const auto A = distributed(Ad, map);  // one graph, as the Newton matrix's
  for (int pass = 0; pass < static_cast<int>(facets.size()); ++pass) {
    const auto& masters = facets[pass];
    if (pass > 0) {
      for (auto& row : Ad)
        for (double& v : row)
          if (v != 0) v *= 1.0 + 0.1 * pass;
      A->resumeFill();
      for (std::size_t l = 0; l < map->getNodeNumElements(); ++l) {
        const GO i = map->getGlobalElement(l);
        for (GO j = 0; j < kN; ++j)
          if (Ad[i][j] != 0)
            A->replaceGlobalValues(i, Teuchos::ArrayView<const GO>(&j, 1),
                                   Teuchos::ArrayView<const double>(&Ad[i][j], 1));
      }
      A->fillComplete();
    }
    std::vector<linalg::PRow> p_all, pt_all;
    for (int c = 0; c < 3; ++c) {  // slave node 5 on the facet, tangent dofs 15, 16 kept
      linalg::PRow p{15 + c, {}, {}}, pt{15 + c, {}, {}};
      for (int k = 0; k < 3; ++k) {
        p.cols.push_back(3 * masters[k] + c);
        p.weights.push_back(0.2 + 0.1 * k + 0.01 * pass);
        pt.cols.push_back(3 * masters[k] + (c + 1) % 3);
        pt.weights.push_back(-0.3 + 0.2 * k - 0.02 * pass);
      }
      for (int q = 0; q < 2; ++q) {
        p.cols.push_back(15 + q);
        p.weights.push_back(0.5 + q + pass);
        pt.cols.push_back(15 + q);
        pt.weights.push_back(0.7 - q);
      }
      p_all.push_back(p);
      pt_all.push_back(pt);
    }
    const std::vector<linalg::Entry> X_all = {
        {15, 3 * masters[0], 0.5 + pass}, {3 * masters[1], 16, -0.7}, {12, 12, 0.1 * pass}};
    std::vector<GO> fixed;
    std::vector<linalg::PRow> p, pt;
    std::vector<std::pair<GO, double>> dummies;
    for (GO g : fixed_all)
      if (map->isNodeGlobalElement(g)) fixed.push_back(g);
    for (int c = 0; c < 3; ++c)
      if (map->isNodeGlobalElement(15 + c)) {
        p.push_back(p_all[c]);
        pt.push_back(pt_all[c]);
        dummies.emplace_back(15 + c, beta);
      }
    std::vector<linalg::Entry> X;
    if (comm->getRank() == comm->getSize() - 1) X = X_all;  // the last rank adds them all
    elim.set_constraints(fixed, p, dummies);
    elim.set_linearisation(pt, X);
    const auto Ar = elim.reduce_matrix(A);
    const auto R = dense_reduced(Ad, fixed_all, p_all, pt_all, X_all, beta);
    double norm = 0;
    const double err = max_error(*Ar, R, *map, norm);
    EXPECT_LT(err, 1e-14 * norm) << "pass " << pass;
    const auto Pd = dense_P(fixed_all, p_all);  // du = P dq
    Vector dq(map), du(map);
    auto dqv = dq.getLocalViewHost(Tpetra::Access::ReadWrite);
    for (std::size_t l = 0; l < map->getNodeNumElements(); ++l)
      dqv(l, 0) = 1.0 + 0.25 * static_cast<double>(map->getGlobalElement(l));
    elim.expand(dq, du);
    auto duv = du.getLocalViewHost(Tpetra::Access::ReadOnly);
    for (std::size_t l = 0; l < map->getNodeNumElements(); ++l) {
      const GO i = map->getGlobalElement(l);
      double ref = 0;
      for (int j = 0; j < kN; ++j) ref += Pd[i][j] * (1.0 + 0.25 * j);
      EXPECT_NEAR(duv(l, 0), ref, 1e-14 * 20) << "pass " << pass << ", dof " << i;
    }
    check(pass, elim, Ar);
  }
}

}  // namespace

TEST(Elimination, StructuredPathReusesItsPattern) {
  int builds = 0;
  structured_passes(false, {{1, 2, 4}, {1, 2, 4}, {3, 2, 1}},  // pass 2: another facet
                    [&](int pass, const linalg::Elimination& elim, const auto&) {
                      builds += pass != 1;  // pass 1: the pattern of pass 0, new weights, values
                      EXPECT_EQ(elim.pattern_builds(), builds) << "pass " << pass;
                      EXPECT_EQ(elim.graph_builds(), builds) << "pass " << pass;
                      // P's graph: the constructor's, then one per new set of columns
                      EXPECT_EQ(elim.p_builds(), 1 + builds) << "pass " << pass;
                    });
}

// For a direct solver (docs/THEORY.md §3.6) the reduced matrix's graph holds A's whole pattern
// and the entries of earlier facets too: a slave back on an earlier facet keeps the same
// matrix object (its analysis), and the values still equal the dense reference.
TEST(Elimination, StructuredPathKeepsAGraphThatHasTheEntries) {
  const Matrix* second = nullptr;
  structured_passes(true, {{1, 2, 4}, {1, 2, 4}, {3, 2, 1}, {1, 2, 4}},
                    [&](int pass, const linalg::Elimination& elim, const auto& Ar) {
                      const int patterns[4] = {1, 1, 2, 3}, graphs[4] = {1, 1, 2, 2};
                      EXPECT_EQ(elim.pattern_builds(), patterns[pass]) << "pass " << pass;
                      EXPECT_EQ(elim.graph_builds(), graphs[pass]) << "pass " << pass;
                      if (pass == 2) second = Ar.get();
                      if (pass == 3) EXPECT_EQ(Ar.get(), second);
                    });
}

// The entries of a new graph, sorted and unique: packed into 64-bit keys where row and column
// fit in 32 bits, as pairs where one does not (ids of 2^32 and more); both as std::sort and
// std::unique give.
TEST(Elimination, SortUniqueEntriesWithAndWithoutPacking) {
  std::mt19937 rng(7);
  for (const GO big : {GO(0), (GO(1) << 32) + 5}) {
    std::vector<std::pair<GO, GO>> v;
    for (int k = 0; k < 2000; ++k)
      v.emplace_back(static_cast<GO>(rng() % 50), static_cast<GO>(rng() % 4000000000u));
    for (int k = 0; k < 200; ++k) v.push_back(v[rng() % v.size()]);  // repeats
    if (big > 0) v.emplace_back(3, big);
    auto expect = v;
    std::sort(expect.begin(), expect.end());
    expect.erase(std::unique(expect.begin(), expect.end()), expect.end());
    linalg::sort_unique_entries(v);
    EXPECT_EQ(v, expect) << "largest id " << big;
  }
}

// P made from its rows in local arrays (docs/THEORY.md §3.1): a repeated column adds its
// weights, fixed rows are empty, a special row wins over a fixed one, columns may be owned by
// the other rank (np2); its rows and P x equal the dense P, before and after write_P_rows
// rewrites the special rows' weights on the same columns.
TEST(PMatrix, MatchesTheDensePWithRepeatedAndRemoteColumns) {
  auto comm = Tpetra::getDefaultComm();
  auto map = Teuchos::rcp(new Map(kN, 0, comm));
  const std::vector<GO> all_fixed = {2, 10, 16};  // 16 is also a special row below
  const auto rows_with = [](double s) {
    return std::vector<linalg::PRow>{{15, {0, 3, 6, 3}, {0.2 * s, 0.3, 0.4, 0.1 * s}},
                                     {16, {1, 4, 7}, {0.5, 0.25 * s, 0.25}},
                                     {17, {}, {}}};  // a dummy: an empty row
  };
  Teuchos::RCP<Matrix> P;
  for (double s : {1.0, -2.0}) {
    std::vector<GO> fixed;
    std::vector<linalg::PRow> rows;
    for (GO g : all_fixed)
      if (map->isNodeGlobalElement(g)) fixed.push_back(g);
    for (const auto& r : rows_with(s))
      if (map->isNodeGlobalElement(r.row)) rows.push_back(r);
    if (s == 1.0)
      P = linalg::make_P(map, fixed, rows);
    else
      linalg::write_P_rows(*P, rows);
    const auto Pd = dense_P(all_fixed, rows_with(s));
    double norm = 0;
    // the same additions in the same order as the dense P: equal to the bit
    EXPECT_EQ(max_error(*P, Pd, *map, norm), 0.0) << "s = " << s;
    Vector x(map), y(map);
    {
      auto xv = x.getLocalViewHost(Tpetra::Access::OverwriteAll);
      for (std::size_t l = 0; l < map->getNodeNumElements(); ++l)
        xv(l, 0) = 1.0 + 0.1 * static_cast<double>(map->getGlobalElement(l));
    }
    P->apply(x, y);
    double err = 0;
    auto yv = y.getLocalViewHost(Tpetra::Access::ReadOnly);
    for (std::size_t l = 0; l < map->getNodeNumElements(); ++l) {
      const GO i = map->getGlobalElement(l);
      double ref = 0;
      for (int j = 0; j < kN; ++j) ref += Pd[i][j] * (1.0 + 0.1 * j);
      err = std::max(err, std::fabs(yv(l, 0) - ref));
    }
    double all = 0;
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, 1, &err, &all);
    EXPECT_LT(all, 1e-14) << "s = " << s;  // sums of four products of O(1) numbers
  }
}
