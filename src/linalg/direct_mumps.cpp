// DirectMumps: the MUMPS calls (init, analysis, factorisation, solve, end) and their errors.
#include "emcontact/linalg/direct_mumps.hpp"

#include <dmumps_c.h>
#include <mpi.h>

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_TimeMonitor.hpp>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <vector>

#include "emcontact/format.hpp"
#include "emcontact/linalg/linear_solver.hpp"
#include "emcontact/parallel.hpp"

// indices as in the MUMPS users' guide (1-based)
#define ICNTL(I) icntl[(I)-1]
#define INFOG(I) infog[(I)-1]

namespace emc::linalg {
namespace {

using Teuchos::RCP;
using Teuchos::rcp;

/// What the common INFOG(1) codes of the MUMPS users' guide mean.
const char* meaning(int code) {
  switch (code) {
    case -5:
    case -7:
    case -13:
      return "not enough memory";
    case -6:
      return "structurally singular matrix";
    case -8:
    case -9:
    case -14:
    case -15:
    case -17:
    case -20:
      return "internal workspace too small (ICNTL(14))";
    case -10:
      return "numerically singular matrix";
    case -16:
      return "matrix order out of range";
    case -2:
      return "number of entries out of range";
    case -3:
      return "MUMPS called with an invalid job";
    default:
      return "see the MUMPS users' guide";
  }
}

bool workspace_error(int code) {
  return code == -8 || code == -9 || code == -14 || code == -15 || code == -17 || code == -20;
}

}  // namespace

struct DirectMumps::State {
  DMUMPS_STRUC_C id{};
  RCP<const Comm> comm;
  RCP<const Graph> graph;           ///< held, so that its address cannot be reused
  std::vector<MUMPS_INT> irn, jcn;  ///< 1-based global rows and columns of my entries
  std::vector<double> a;
  RCP<const Map> root;  ///< all rows on rank 0
  RCP<Import> to_root;
  RCP<Vector> rhs;  ///< on root: MUMPS's centralized right-hand side and solution
  bool analysed = false, factored = false;
};

DirectMumps::DirectMumps(const RCP<const Comm>& comm) : s_(std::make_shared<State>()) {
  s_->comm = comm;
  auto& id = s_->id;
  id.job = -1;
  id.par = 1;  // the host works too
  id.sym = 0;  // general (the Newton matrix is non-symmetric in general)
  id.comm_fortran = static_cast<MUMPS_INT>(MPI_Comm_c2f(raw_comm(*comm)));
  dmumps_c(&id);
  if (id.INFOG(1) < 0) throw LinearSolveError("MUMPS initialisation failed");
  id.ICNTL(1) = -1;  // no output: errors become LinearSolveError
  id.ICNTL(2) = -1;
  id.ICNTL(3) = -1;
  id.ICNTL(4) = 0;
  id.ICNTL(5) = 0;   // assembled matrix
  id.ICNTL(18) = 3;  // distributed: each rank gives its own rows
  id.ICNTL(20) = 0;  // dense right-hand side on the host
  id.ICNTL(21) = 0;  // solution on the host
  // diagonal scaling: MUMPS' automatic choice (ICNTL(8) = 77) computes an iterative row and
  // column scaling at every factorisation; the diagonal one is cheaper, with the same solves,
  // Newton iterations and energy errors on the examples (perf/README.md, "MUMPS")
  id.ICNTL(8) = 1;
}

DirectMumps::~DirectMumps() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (finalized) return;
  s_->id.job = -2;
  dmumps_c(&s_->id);
}

bool DirectMumps::factored() const {
  return s_->factored;
}

void DirectMumps::run(int job) {
  auto& id = s_->id;
  id.job = job;
  dmumps_c(&id);
  const int code = id.INFOG(1);
  if (code >= 0) return;
  const std::string message = format("MUMPS %s failed: INFOG(1) = %d, INFOG(2) = %d (%s)",
                                     job == 1   ? "analysis"
                                     : job == 2 ? "factorisation"
                                                : "solve",
                                     code, id.INFOG(2), meaning(code));
  if (job <= 2) s_->factored = false;
  if (job == 1) s_->analysed = false;
  throw LinearSolveError(message);
}

// Same structure: the same graph object, or (a rebuilt graph) the same global entries in the
// same order on every rank; the entry lists of A are rebuilt into irn/jcn either way.
bool DirectMumps::same_structure(const RCP<const Matrix>& A) {
  const auto g = A->getCrsGraph();
  int same = s_->analysed && g.get() == s_->graph.get() ? 1 : 0;
  if (!same && s_->analysed) {
    const auto lA = A->getLocalMatrixHost();
    const auto& rows = *A->getRowMap();
    const auto& cols = *A->getColMap();
    std::size_t k = 0;
    same = rows.getGlobalNumElements() == static_cast<std::size_t>(s_->id.n) &&
                   lA.nnz() == s_->irn.size()
               ? 1
               : 0;
    for (LO i = 0; same && i < lA.numRows(); ++i)
      for (auto e = lA.graph.row_map(i); same && e < lA.graph.row_map(i + 1); ++e, ++k)
        same = s_->irn[k] == rows.getGlobalElement(i) + 1 &&
               s_->jcn[k] == cols.getGlobalElement(lA.graph.entries(e)) + 1;
  }
  int all = 0;
  Teuchos::reduceAll(*s_->comm, Teuchos::REDUCE_MIN, 1, &same, &all);
  if (all) s_->graph = g;
  return all == 1;
}

void DirectMumps::analyse(const RCP<const Matrix>& A) {
  Teuchos::TimeMonitor t(*Teuchos::TimeMonitor::getNewTimer("emcontact: MUMPS analysis"));
  const auto& rows = *A->getRowMap();
  const GO n = static_cast<GO>(rows.getGlobalNumElements());
  if (rows.getMinAllGlobalIndex() != 0 || rows.getMaxAllGlobalIndex() != n - 1 ||
      n > std::numeric_limits<MUMPS_INT>::max())
    throw Error("internal: MUMPS needs the matrix rows numbered 0..N-1 (N < 2^31)");
  const auto lA = A->getLocalMatrixHost();
  const auto& cols = *A->getColMap();
  s_->irn.resize(lA.nnz());
  s_->jcn.resize(lA.nnz());
  s_->a.assign(lA.nnz(), 0.0);
  std::size_t k = 0;
  for (LO i = 0; i < lA.numRows(); ++i)
    for (auto e = lA.graph.row_map(i); e < lA.graph.row_map(i + 1); ++e, ++k) {
      s_->irn[k] = static_cast<MUMPS_INT>(rows.getGlobalElement(i) + 1);
      s_->jcn[k] = static_cast<MUMPS_INT>(cols.getGlobalElement(lA.graph.entries(e)) + 1);
    }
  auto& id = s_->id;
  id.n = static_cast<MUMPS_INT>(n);
  id.nz_loc = static_cast<MUMPS_INT>(k);
  id.nnz_loc = static_cast<MUMPS_INT8>(k);
  id.irn_loc = s_->irn.data();
  id.jcn_loc = s_->jcn.data();
  id.a_loc = s_->a.data();
  s_->factored = false;
  run(1);
  s_->analysed = true;
  s_->graph = A->getCrsGraph();
  rows_ = A->getRowMap();
  const auto comm = A->getRowMap()->getComm();
  s_->root = rcp(new Map(n, comm->getRank() == 0 ? n : 0, 0, comm));
  s_->to_root = rcp(new Import(rows_, s_->root));
  s_->rhs = rcp(new Vector(s_->root));
  ++analyses_;
}

void DirectMumps::factor(const RCP<const Matrix>& A) {
  if (!same_structure(A)) analyse(A);
  Teuchos::TimeMonitor t(*Teuchos::TimeMonitor::getNewTimer("emcontact: MUMPS factorisation"));
  const auto v = A->getLocalMatrixHost().values;
  for (std::size_t k = 0; k < s_->a.size(); ++k) s_->a[k] = v(k);
  s_->factored = false;
  try {
    run(2);
  } catch (const LinearSolveError&) {
    if (!workspace_error(s_->id.INFOG(1))) throw;
    s_->id.ICNTL(14) = std::max(100, 4 * s_->id.ICNTL(14));  // once, with 4x the workspace
    run(2);
  }
  s_->factored = true;
  ++factorisations_;
  static const bool trace = std::getenv("EMC_MUMPS_TRACE") != nullptr;
  if (trace && s_->comm->getRank() == 0)  // debugging aid: what each factorisation cost
    std::fprintf(stderr, "mumps: n %d, ordering %d (ICNTL(7)), %.3g flops, %d factor entries\n",
                 s_->id.n, s_->id.INFOG(7), s_->id.rinfog[2], s_->id.INFOG(29));
}

void DirectMumps::solve(const Vector& b, Vector& x) {
  if (!s_->factored) throw Error("internal: MUMPS solve without factors");
  auto& rhs = *s_->rhs;
  rhs.doImport(b, *s_->to_root, Tpetra::INSERT);
  {
    auto view = rhs.getLocalViewHost(Tpetra::Access::ReadWrite);
    s_->id.rhs = view.data();
    s_->id.nrhs = 1;
    s_->id.lrhs = s_->id.n;
    run(3);  // the solution overwrites rhs on the host
  }
  x.doExport(rhs, *s_->to_root, Tpetra::INSERT);
}

}  // namespace emc::linalg
