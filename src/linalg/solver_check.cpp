// The pass-through sublists (Belos, Ifpack2, MueLu) go to the packages unchanged: they are
// tried once at setup, so that a value a package refuses is an input error (one line, before
// any step) rather than an exception in the middle of the run, and names a package ignores
// (typos) are reported.
#include <BelosSolverFactory_Tpetra.hpp>
#include <BelosTpetraAdapter.hpp>
#include <algorithm>
#include <cstdio>
#include <limits>
#include <new>
#include <regex>
#include <sstream>

#include "emcontact/error.hpp"
#include "emcontact/input/echo.hpp"
#include "emcontact/linalg/linear_solver.hpp"

namespace emc::linalg {
namespace {

using Teuchos::RCP;
using Teuchos::rcp;

/// An SPD tridiagonal matrix with `rows` rows (a multiple of 3: nodes of 3 dofs, as MueLu
/// expects) per rank.
RCP<Matrix> test_matrix(const RCP<const Comm>& comm, LO rows) {
  const GO n = GO(rows) * comm->getSize();
  auto map = rcp(new Map(n, rows, 0, comm));
  auto A = rcp(new Matrix(map, 3));
  for (LO l = 0; l < rows; ++l) {
    const GO g = map->getGlobalElement(l);
    std::vector<GO> cols{g};
    std::vector<double> vals{4.0};
    for (GO c : {g - 1, g + 1})
      if (c >= 0 && c < n) {
        cols.push_back(c);
        vals.push_back(-1.0);
      }
    A->insertGlobalValues(g, Teuchos::arrayViewFromVector(cols),
                          Teuchos::arrayViewFromVector(vals));
  }
  A->fillComplete();
  return A;
}

/// A count in a pass-through sublist that sets how long one preconditioner application, setup
/// or solve takes, with the largest value allowed (a stop signal is honoured between Krylov
/// iterations, not inside these).
struct CountLimit {
  const char* name;
  int lo, hi;
  const char* why;
};

const CountLimit kCountLimits[] = {
    {"Maximum Iterations", 1, kMaxLinearIterations, "the Krylov iterations of one solve"},
    {"chebyshev: degree", std::numeric_limits<int>::min(), 100,
     "the matrix products of each application of a Chebyshev preconditioner or smoother"},
    {"relaxation: sweeps", std::numeric_limits<int>::min(), 100,
     "the sweeps of each application of a relaxation preconditioner or smoother"},
    {"max levels", std::numeric_limits<int>::min(), 50,
     "the multigrid levels (each coarsens: 50 cover any mesh)"},
};

/// Throws InputError naming the parameter if an int entry of `list` (any depth) named in
/// kCountLimits is out of its range; other types are left to the package.
void check_counts(const Teuchos::ParameterList& list, const std::string& path,
                  const std::string& where) {
  for (auto it = list.begin(); it != list.end(); ++it) {
    const std::string& name = list.name(it);
    const auto& entry = list.entry(it);
    if (entry.isList()) {
      check_counts(Teuchos::getValue<Teuchos::ParameterList>(entry), path + "/" + name, where);
      continue;
    }
    if (!entry.isType<int>()) continue;
    const int v = Teuchos::getValue<int>(entry);
    for (const auto& c : kCountLimits) {
      if (name != c.name || (v >= c.lo && v <= c.hi)) continue;
      const bool low = c.lo != std::numeric_limits<int>::min();
      throw InputError(where + "parameter \"" + path + "/" + name + "\": " + std::to_string(v) +
                       (v > c.hi ? " is too large" : " is too small") + " for " + c.why +
                       "; allowed: an integer " +
                       (low ? "from " + std::to_string(c.lo) + " to " : "up to ") +
                       std::to_string(c.hi));
    }
  }
}

/// The names, quoted, each cut and at most a few of them (a typo'd list can be huge).
std::string quoted_list(const std::vector<std::string>& names) {
  return input::echo_list(names);
}

}  // namespace

std::string one_line(const std::string& message) {
  static const std::regex location("^\\s*\\S+:[0-9]+:\\s*$");
  std::istringstream in(message);
  std::string out;
  for (std::string l; std::getline(in, l);) {
    if (std::regex_match(l, location) || l.rfind("Throw number", 0) == 0 ||
        l.rfind("Throw test that evaluated to true", 0) == 0)
      continue;
    const auto b = l.find_first_not_of(" \t\r");
    if (b == std::string::npos) continue;
    out += (out.empty() ? "" : " ") + l.substr(b);
  }
  if (out.size() > 300) out = out.substr(0, 297) + "...";
  return out.empty() ? "(no message)" : out;
}

/// Builds the preconditioner `type` on a test matrix and returns the matrix (prec_ is set);
/// `ignored` receives the Ifpack2 names of another preconditioner's family.
RCP<Matrix> LinearSolver::check_preconditioner(const RCP<const Comm>& comm,
                                               const std::string& where, Preconditioner type,
                                               std::vector<std::string>& ignored) {
  prec_type_ = type;
  // MueLu: above its default coarse size (2000 rows), so that the smoothers of a fine level are
  // set up too (a smoother parameter of the wrong type was otherwise found only mid-run)
  const bool muelu = type == Preconditioner::muelu;
  const auto A = test_matrix(comm, muelu ? 2400 : 6);
  std::vector<std::string> unused;
  ignored.clear();
  const std::string prec = muelu ? "MueLu" : "Ifpack2";
  try {
    build_preconditioner(A, &unused, &ignored);
  } catch (const std::bad_alloc&) {  // out of memory, not a refused parameter
    throw Error(where + "the trial of Solver/Linear/" + prec + " at setup: std::bad_alloc");
  } catch (const std::exception& e) {
    throw InputError(where + "parameter \"Solver/Linear/" + prec + "\": " + prec +
                     " refused it: " + one_line(e.what()) + "; allowed: parameters " + prec +
                     " accepts (see its documentation)");
  }
  if (!unused.empty() && comm->getRank() == 0)
    std::fprintf(stderr, "warning: %sSolver/Linear/Ifpack2: %s not known to Ifpack2 (typo?)\n",
                 where.c_str(), quoted_list(unused).c_str());
  return A;
}

void LinearSolver::check_pass_through(const RCP<const Comm>& comm, const std::string& file) {
  const std::string where = file.empty() ? "" : file + ": ";
  check_counts(belos_, "Solver/Linear/Belos", where);
  check_counts(ifpack2_, "Solver/Linear/Ifpack2", where);
  check_counts(muelu_, "Solver/Linear/MueLu", where);
  RCP<Matrix> A;
  std::vector<std::string> ignored;
  std::string used = preconditioner_name(prec_type_);
  if (auto_) {  // each one auto may choose is tried; a name is ignored if all of them ignore it
    std::vector<Preconditioner> small{small_preconditioner(0)};
    const Preconditioner large = small_preconditioner(std::numeric_limits<long long>::max());
    if (large != small.front()) small.push_back(large);
    used.clear();
    for (const Preconditioner p : small) {
      std::vector<std::string> mine;
      A = check_preconditioner(comm, where, p, mine);
      if (p == small.front()) {
        ignored = mine;
      } else {
        const auto read = [&](const std::string& n) {
          return std::find(mine.begin(), mine.end(), n) == mine.end();
        };
        ignored.erase(std::remove_if(ignored.begin(), ignored.end(), read), ignored.end());
      }
      used += (used.empty() ? "" : " and ") + std::string(preconditioner_name(p));
    }
    used += small.size() > 1 ? ", the preconditioners auto chooses from by size"
                             : ", the preconditioner auto chooses";
    std::vector<std::string> none;
    if (muelu_available()) A = check_preconditioner(comm, where, Preconditioner::muelu, none);
  } else {
    A = check_preconditioner(comm, where, prec_type_, ignored);
    used += ", the preconditioner used";
  }
  if (!ignored.empty() && comm->getRank() == 0)
    std::fprintf(stderr, "warning: %sSolver/Linear/Ifpack2: %s not read by %s\n", where.c_str(),
                 quoted_list(ignored).c_str(), used.c_str());
  const std::string name = krylov_name();
  try {
    Belos::SolverFactory<double, MultiVector, Operator> factory;
    auto solver = factory.create(name, belos_parameters(tol_));
    std::vector<std::string> unknown;
    const auto valid = solver->getValidParameters();
    for (auto it = belos_.begin(); it != belos_.end(); ++it)
      if (!valid->isParameter(belos_.name(it))) unknown.push_back(belos_.name(it));
    if (!unknown.empty() && comm->getRank() == 0)
      std::fprintf(stderr, "warning: %sSolver/Linear/Belos: %s not known to Belos %s (typo?)\n",
                   where.c_str(), quoted_list(unknown).c_str(), name.c_str());
    Vector b(A->getRowMap()), x(A->getRowMap());
    b.putScalar(1.0);
    bool converged = false;
    std::string message;
    belos_solve(A, b, x, tol_, converged, message);
  } catch (const std::bad_alloc&) {  // out of memory (Num Blocks x rows), not a refused value
    prec_ = Teuchos::null;
    throw Error(where + "the trial solve of Solver/Linear/Belos (" + name +
                ") at setup: std::bad_alloc");
  } catch (const std::exception& e) {
    prec_ = Teuchos::null;
    throw InputError(where + "parameter \"Solver/Linear/Belos\": Belos " + name +
                     " refused it: " + one_line(e.what()) +
                     "; allowed: parameters Belos accepts (see its documentation)");
  }
  prec_ = Teuchos::null;  // the run's matrix gets its own
  if (auto_) prec_type_ = Preconditioner::automatic;
}

}  // namespace emc::linalg
