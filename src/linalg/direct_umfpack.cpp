// DirectUmfpack: the UMFPACK calls (symbolic, numeric, solve) and their errors. UMFPACK takes a
// matrix by columns: the entries of A (Tpetra's local CSR in global numbering) are sorted by
// column once per structure, so that UMFPACK factors A itself and solves A x = b with its
// forward triangular solves (UMFPACK_A), cheaper than the transposed ones (UMFPACK_At) that
// factoring A^T, Tpetra's rows as columns, would need (perf/README.md, "Sparse direct solvers").
#include "emcontact/linalg/direct_umfpack.hpp"

#include <suitesparse/umfpack.h>

#include <Teuchos_TimeMonitor.hpp>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include "emcontact/format.hpp"
#include "emcontact/linalg/linear_solver.hpp"

namespace emc::linalg {

using Teuchos::RCP;

namespace {

/// What UMFPACK's status codes mean (UMFPACK user guide, "Primary routines").
const char* meaning(int status) {
  switch (status) {
    case UMFPACK_WARNING_singular_matrix:
      return "numerically singular matrix";
    case UMFPACK_ERROR_out_of_memory:
      return "not enough memory";
    case UMFPACK_ERROR_invalid_matrix:
      return "invalid matrix structure";
    case UMFPACK_ERROR_different_pattern:
      return "the pattern changed since the analysis";
    default:
      return "see the UMFPACK user guide";
  }
}

}  // namespace

struct DirectUmfpack::State {
  RCP<const Graph> graph;         ///< held, so that its address cannot be reused
  std::vector<int> Bp, Bi;        ///< A by columns, global numbering, rows sorted
  std::vector<std::size_t> perm;  ///< entry p of Bi/Bx is Tpetra's local value perm[p]
  std::vector<GO> rows, cols;     ///< global row and column of each Tpetra entry (structure)
  std::vector<LO> row_of;         ///< local row of global row g
  std::vector<double> Bx, b, x, W;
  std::vector<int> Wi;
  double control[UMFPACK_CONTROL], info[UMFPACK_INFO];
  void *symbolic = nullptr, *numeric = nullptr;

  void free_numeric() {
    if (numeric) umfpack_di_free_numeric(&numeric);
    numeric = nullptr;
  }
  void free_symbolic() {
    free_numeric();
    if (symbolic) umfpack_di_free_symbolic(&symbolic);
    symbolic = nullptr;
  }
};

DirectUmfpack::DirectUmfpack(const RCP<const Comm>& comm) : s_(std::make_unique<State>()) {
  if (comm->getSize() > 1)
    throw InputError(
        "Solver/Linear/type = umfpack runs on one rank only (UMFPACK is "
        "sequential); allowed on " +
        std::to_string(comm->getSize()) + " ranks: gmres, cg, mumps");
  umfpack_di_defaults(s_->control);
  // no iterative refinement: LinearSolver checks the true residual of every solve, and GMRES
  // on reused factors refines anyway
  s_->control[UMFPACK_IRSTEP] = 0;
  // the symmetric strategy (AMD on A + A^T, diagonal pivots preferred): the reduced matrix has
  // the symmetric pattern of a finite-element matrix but for the contact rows, and its factors
  // fill less than the column ordering `auto` picks for it (perf/README.md, "Sparse direct
  // solvers")
  s_->control[UMFPACK_STRATEGY] = UMFPACK_STRATEGY_SYMMETRIC;
}

DirectUmfpack::~DirectUmfpack() {
  s_->free_symbolic();
}

bool DirectUmfpack::factored() const {
  return s_->numeric != nullptr;
}

bool DirectUmfpack::same_structure(const Matrix& A) const {
  if (s_->symbolic == nullptr) return false;
  const auto g = A.getCrsGraph();
  if (g.get() == s_->graph.get()) return true;
  const auto lA = A.getLocalMatrixHost();
  if (lA.nnz() != s_->cols.size() || A.getGlobalNumRows() != s_->row_of.size()) return false;
  const auto& rows = *A.getRowMap();
  const auto& cols = *A.getColMap();
  std::size_t k = 0;
  for (LO i = 0; i < lA.numRows(); ++i)
    for (auto e = lA.graph.row_map(i); e < lA.graph.row_map(i + 1); ++e, ++k)
      if (s_->rows[k] != rows.getGlobalElement(i) ||
          s_->cols[k] != cols.getGlobalElement(lA.graph.entries(e)))
        return false;
  return true;
}

void DirectUmfpack::analyse(const RCP<const Matrix>& A) {
  Teuchos::TimeMonitor t(*Teuchos::TimeMonitor::getNewTimer("emcontact: UMFPACK analysis"));
  s_->free_symbolic();
  const auto& rows = *A->getRowMap();
  const auto& cols = *A->getColMap();
  const GO n = static_cast<GO>(rows.getGlobalNumElements());
  const auto lA = A->getLocalMatrixHost();
  if (rows.getMinAllGlobalIndex() != 0 || rows.getMaxAllGlobalIndex() != n - 1 ||
      n > std::numeric_limits<int>::max() ||
      lA.nnz() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw Error("internal: UMFPACK needs the matrix rows numbered 0..N-1 (N, entries < 2^31)");
  const std::size_t nnz = lA.nnz();
  s_->rows.resize(nnz);
  s_->cols.resize(nnz);
  s_->row_of.assign(n, -1);
  for (LO i = 0; i < lA.numRows(); ++i) {
    const GO g = rows.getGlobalElement(i);
    s_->row_of[g] = i;
    for (auto e = lA.graph.row_map(i); e < lA.graph.row_map(i + 1); ++e) {
      s_->rows[e] = g;
      s_->cols[e] = cols.getGlobalElement(lA.graph.entries(e));
    }
  }
  // A by columns: a counting sort of the entries by global column; walking the rows in
  // ascending global order leaves each column's rows sorted, as UMFPACK asks
  std::vector<int> Ap(n + 1, 0);
  for (std::size_t e = 0; e < nnz; ++e) ++Ap[s_->cols[e] + 1];
  std::partial_sum(Ap.begin(), Ap.end(), Ap.begin());
  s_->perm.resize(nnz);
  s_->Bi.resize(nnz);
  std::vector<int> next(Ap.begin(), Ap.end() - 1);
  for (GO g = 0; g < n; ++g) {
    const LO i = s_->row_of[g];
    for (auto e = lA.graph.row_map(i); e < lA.graph.row_map(i + 1); ++e) {
      const int q = next[s_->cols[e]]++;
      s_->perm[q] = e;
      s_->Bi[q] = static_cast<int>(g);
    }
  }
  s_->Bp = std::move(Ap);
  s_->Bx.assign(nnz, 0.0);
  s_->b.resize(n);
  s_->x.resize(n);
  s_->Wi.resize(n);
  s_->W.resize(5 * n);
  const int status =
      umfpack_di_symbolic(static_cast<int>(n), static_cast<int>(n), s_->Bp.data(), s_->Bi.data(),
                          nullptr, &s_->symbolic, s_->control, s_->info);
  if (status != UMFPACK_OK) {
    s_->symbolic = nullptr;
    throw LinearSolveError(
        format("UMFPACK analysis failed: status %d (%s)", status, meaning(status)));
  }
  s_->graph = A->getCrsGraph();
  rows_ = A->getRowMap();
  ++analyses_;
}

void DirectUmfpack::factor(const RCP<const Matrix>& A) {
  if (!same_structure(*A)) analyse(A);
  s_->graph = A->getCrsGraph();
  Teuchos::TimeMonitor t(*Teuchos::TimeMonitor::getNewTimer("emcontact: UMFPACK factorisation"));
  const auto v = A->getLocalMatrixHost().values;
  for (std::size_t p = 0; p < s_->Bx.size(); ++p) s_->Bx[p] = v(s_->perm[p]);
  s_->free_numeric();
  const int status = umfpack_di_numeric(s_->Bp.data(), s_->Bi.data(), s_->Bx.data(), s_->symbolic,
                                        &s_->numeric, s_->control, s_->info);
  if (status != UMFPACK_OK) {  // a singular matrix is only a warning to UMFPACK
    s_->free_numeric();
    throw LinearSolveError(
        format("UMFPACK factorisation failed: status %d (%s)", status, meaning(status)));
  }
  ++factorisations_;
}

void DirectUmfpack::solve(const Vector& b, Vector& x) {
  if (!factored()) throw Error("internal: UMFPACK solve without factors");
  const std::size_t n = s_->row_of.size();
  {
    const auto bv = b.getLocalViewHost(Tpetra::Access::ReadOnly);
    for (std::size_t g = 0; g < n; ++g) s_->b[g] = bv(s_->row_of[g], 0);
  }
  const int status = umfpack_di_wsolve(UMFPACK_A, s_->Bp.data(), s_->Bi.data(), s_->Bx.data(),
                                       s_->x.data(), s_->b.data(), s_->numeric, s_->control,
                                       s_->info, s_->Wi.data(), s_->W.data());
  if (status != UMFPACK_OK) {
    throw LinearSolveError(format("UMFPACK solve failed: status %d (%s)", status, meaning(status)));
  }
  auto xv = x.getLocalViewHost(Tpetra::Access::OverwriteAll);
  for (std::size_t g = 0; g < n; ++g) xv(s_->row_of[g], 0) = s_->x[g];
}

}  // namespace emc::linalg
