#pragma once
// The linear solver behind one interface: Belos (GMRES, or CG for symmetric matrices) with an
// Ifpack2 (ILU, additive Schwarz) or MueLu preconditioner on any number of ranks, Amesos2
// KLU2 or SuiteSparse UMFPACK on one rank, or MUMPS on any number of ranks. The preconditioner is
// reused across Newton iterations and steps while the iteration count stays near the count of a
// fresh one. After every solve the true residual is checked; a failure, or an exception of Belos,
// Ifpack2, MueLu or Amesos2 (a NaN in the matrix), throws LinearSolveError with the solver's own
// message on one line, which the time stepper treats as a failed step (dt halved).
#include <Teuchos_ParameterList.hpp>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "emcontact/error.hpp"
#include "emcontact/linalg/parameters.hpp"
#include "emcontact/types.hpp"

namespace emc::linalg {

class DirectSolver;

class LinearSolveError : public RunError {
 public:
  explicit LinearSolveError(const std::string& what) : RunError(what) {}
};

/// Thrown out of a Krylov solve when the stop check (LinearSolver::set_stop_check) answers
/// true. Not a std::exception: Belos prints every std::exception it passes on, and lets this
/// one through without a word.
struct SolveInterrupted {};

struct SolveStats {
  int iterations = 0;
  double true_residual = -1;  ///< ||b - A x|| / ||b|| after the solve (-1: not yet known)
  bool fresh_preconditioner = false;
};

/// The input's name of a preconditioner (Solver/Linear/preconditioner).
const char* preconditioner_name(Preconditioner p);

/// Reseeds std::rand, from which Tpetra's MultiVector::randomize seeds the random start of
/// Chebyshev's power method (Ifpack2's, and MueLu's Chebyshev smoothers): called before each
/// preconditioner setup, so that every setup of the same matrix is the same whatever came before
/// it, and a restarted run repeats the uninterrupted one bit for bit.
void same_random_start();

/// A preconditioner factory result (Ifpack2 or MueLu), as a Tpetra operator. `unused`, if
/// given, receives the names of `user` that Ifpack2 does not know; `ignored` those it knows
/// for another preconditioner than `type` (e.g. "fact: ..." with chebyshev).
Teuchos::RCP<Operator> make_ifpack2(Preconditioner type, const Teuchos::RCP<const Matrix>& A,
                                    const Teuchos::ParameterList& user,
                                    std::vector<std::string>* unused = nullptr,
                                    std::vector<std::string>* ignored = nullptr);
/// Smoothed aggregation with 3 dofs per node; `nullspace` (rigid-body modes) and `coordinates`
/// (node map) go to MueLu's user data when not null.
Teuchos::RCP<Operator> make_muelu(const Teuchos::RCP<Matrix>& A, const Teuchos::ParameterList& user,
                                  const Teuchos::RCP<MultiVector>& nullspace = Teuchos::null,
                                  const Teuchos::RCP<MultiVector>& coordinates = Teuchos::null);
/// True when emcontact was built with MueLu (the OpenMP Trilinos of perf/ has none).
bool muelu_available();
/// Recomputes a make_muelu preconditioner for a new matrix of the same map, keeping what its
/// `reuse: type` keeps (by default the prolongators: only coarse operators and smoothers).
void refresh_muelu(const Teuchos::RCP<Matrix>& A, Operator& prec);
/// x = A^-1 b with Amesos2 KLU2 (one rank only), keeping the symbolic factorisation while
/// the matrix's graph is the same object.
class DirectKlu2 {
 public:
  DirectKlu2();
  void solve(const Teuchos::RCP<const Matrix>& A, const Vector& b, Vector& x);
  int symbolic_factorisations() const { return symbolic_; }

 private:
  struct State;
  std::shared_ptr<State> s_;
  int symbolic_ = 0;
};

/// A package's multi-line exception text on one line: the throw location and test lines
/// dropped, at most 300 characters.
std::string one_line(const std::string& message);

class LinearSolver {
 public:
  /// `linear` is the validated `Solver/Linear` sublist. The pass-through sublists (Belos,
  /// Ifpack2, MueLu) are tried once on a small matrix: a value the package refuses throws
  /// InputError naming `file` and the sublist; names the package does not know get a warning
  /// on rank 0.
  LinearSolver(const Teuchos::ParameterList& linear, Teuchos::RCP<const Comm> comm,
               const std::string& file = "");

  /// Solves A x = b from x = 0 to the relative tolerance `tol` (<= 0: the input's tolerance;
  /// never below it). Throws LinearSolveError if the true residual is too large.
  SolveStats solve(const Teuchos::RCP<Matrix>& A, const Vector& b, Vector& x, double tol = 0);
  /// The input's (tightest) relative tolerance.
  double tolerance() const { return tol_; }

  /// Forces a fresh preconditioner at the next solve (after a checkpoint, so that a restart
  /// continues bit for bit).
  void invalidate() { prec_ = Teuchos::null; }
  /// The matrix changed in structure (a new active set): a fresh preconditioner at the next
  /// solve, or with `multigrid reuse = refresh` the multigrid hierarchy's coarse operators and
  /// smoothers recomputed for it (its aggregates and prolongators kept).
  void matrix_changed();
  /// True for a direct solver (klu2, mumps, umfpack): it keeps its analysis while the graph is
  /// the same.
  bool direct() const {
    return type_ == SolverType::klu2 || type_ == SolverType::mumps || type_ == SolverType::umfpack;
  }
  /// True for a solver that assumes a symmetric matrix (Solver/Linear/type = cg).
  bool assumes_symmetric() const { return type_ == SolverType::cg; }
  /// True when the preconditioner is built from node positions (multigrid's rigid-body modes).
  bool uses_positions() const {
    return (prec_type_ == Preconditioner::muelu || auto_) &&
           null_space_ == NullSpace::rigid_body_modes;
  }
  /// The configuration of the next solves: reference positions X (coordinate c of node n at dof
  /// 3 n + c, the matrix's row map) and displacements u; the next preconditioner built takes
  /// its rigid-body modes from X + u or X (Solver/Linear/multigrid positions).
  void set_configuration(const Vector& X, const Vector& u);
  std::string description() const;
  /// `stop` is asked (collectively: every rank at the same point) before every product with
  /// the matrix in a Krylov solve; when it answers true the solve throws SolveInterrupted.
  void set_stop_check(std::function<bool()> stop) { stop_ = std::move(stop); }

 private:
  SolverType type_;
  Preconditioner prec_type_;  ///< the preconditioner built (auto: the one chosen by size)
  double tol_, check_factor_;
  int max_iters_;
  bool reuse_;
  Teuchos::ParameterList belos_, ifpack2_, muelu_;
  Teuchos::RCP<Operator> prec_;
  DirectKlu2 klu2_;
  std::shared_ptr<DirectSolver> direct_;  ///< mumps, umfpack; prec_ is then its factors' inverse
  double reuse_rate_;
  double fresh_rate_ = 0;           ///< Krylov iterations per decade of a fresh preconditioner
  NullSpace null_space_;            ///< multigrid near null space
  ModePositions positions_type_;    ///< the positions of the rigid-body modes
  bool zero_eliminated_ = false;    ///< modes zero at eliminated (decoupled) dofs
  bool refresh_ = false;            ///< multigrid reuse = refresh (if muelu)
  bool refreshable_ = false;        ///< refresh_ and the preconditioner is muelu
  bool auto_ = false;               ///< preconditioner = auto: chosen at each build
  long long auto_dofs_ = 0;         ///< auto: muelu from this many equations
  long long chebyshev_dofs_ = 0;    ///< auto on one thread: chebyshev from this many
  bool stale_ = false;              ///< prec_ is for an earlier structure: refresh
  Teuchos::RCP<Vector> positions_;  ///< node positions for the next multigrid build
  std::function<bool()> stop_;      ///< set_stop_check

  SolveStats checked_solve(const Teuchos::RCP<Matrix>& A, const Vector& b, Vector& x, double tol);
  int belos_solve(const Teuchos::RCP<Matrix>& A, const Vector& b, Vector& x, double tol,
                  bool& converged, std::string& message);
  Teuchos::RCP<Teuchos::ParameterList> belos_parameters(double tol) const;
  /// Belos' name of the iterative solver: "CG" or "GMRES".
  std::string krylov_name() const;
  /// mumps, umfpack: a new factorisation, or GMRES on the last factors while they work.
  void direct_solve(const Teuchos::RCP<Matrix>& A, const Vector& b, Vector& x, SolveStats& st,
                    std::string& message);
  /// Builds (level 2) or refreshes (level 1) the preconditioner for A.
  void setup_preconditioner(const Teuchos::RCP<Matrix>& A, int level);
  void build_preconditioner(const Teuchos::RCP<Matrix>& A,
                            std::vector<std::string>* unused = nullptr,
                            std::vector<std::string>* ignored = nullptr);
  Teuchos::RCP<Operator> make_muelu_with_modes(const Teuchos::RCP<Matrix>& A) const;
  /// preconditioner = auto: muelu for A of at least auto_dofs_ rows, else small_preconditioner.
  void choose_preconditioner(const Teuchos::RCP<Matrix>& A);
  /// auto's choice below multigrid's size: chebyshev on 2+ threads or from chebyshev_dofs_
  /// rows on, else ilu.
  Preconditioner small_preconditioner(long long rows) const;
  void check_pass_through(const Teuchos::RCP<const Comm>& comm, const std::string& file);
  Teuchos::RCP<Matrix> check_preconditioner(const Teuchos::RCP<const Comm>& comm,
                                            const std::string& where, Preconditioner type,
                                            std::vector<std::string>& ignored);
};

}  // namespace emc::linalg
