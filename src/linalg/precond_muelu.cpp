#include "emcontact/linalg/linear_solver.hpp"

#ifdef EMC_HAVE_MUELU
#include <MueLu_CreateTpetraPreconditioner.hpp>
#include <MueLu_VerboseObject.hpp>
#endif
#include <stdexcept>

namespace emc::linalg {

// Aggregation AMG for 3 dofs per node with Chebyshev smoothers (matrix-vector products only, so
// they run on threads in a threaded Kokkos build, unlike Gauss-Seidel), whose eigenvalue
// interval and degree were chosen by measurement (perf/README.md "Linear solvers"). The
// hierarchy keeps R and P for refresh_muelu. On 2+ ranks Debian's Amesos2 KLU2 coarse solver
// is wrong (docs/developer-guide.md), so the coarse level uses Schwarz with local direct solves.
// The user's `MueLu` sublist overrides any of these.
Teuchos::RCP<Operator> make_muelu(const Teuchos::RCP<Matrix>& A, const Teuchos::ParameterList& user,
                                  const Teuchos::RCP<MultiVector>& nullspace,
                                  const Teuchos::RCP<MultiVector>& coordinates) {
#ifndef EMC_HAVE_MUELU
  (void)A;
  (void)user;
  (void)nullspace;
  (void)coordinates;
  throw std::runtime_error(
      "Solver/Linear/preconditioner = \"muelu\": this build of emcontact has no MueLu (the "
      "Trilinos it was built against lacks it); allowed here: auto, ilu, schwarz, chebyshev, "
      "none");
#else
  Teuchos::ParameterList p;
  p.set("number of equations", 3);
  p.set("verbosity", "none");
  p.set("multigrid algorithm", "unsmoothed");
  p.set("smoother: type", "CHEBYSHEV");
  auto& sm = p.sublist("smoother: params");
  sm.set("chebyshev: degree", 3);
  sm.set("chebyshev: ratio eigenvalue", 7.0);
  p.set("reuse: type", "RP");
  // an aggregate of one node has 3 dofs for 6 modes: a singular coarse block (KLU2 in the
  // Schwarz coarse solve failed on one rank of the 65k-tet ball). Leftover nodes join
  // neighbouring aggregates, and zero coarse diagonals become 1.
  p.set("aggregation: phase3 avoid singletons", true);
  p.set("rap: fix zero diagonals", true);
  if (A->getComm()->getSize() > 1) {
    p.set("coarse: type", "SCHWARZ");
    auto& c = p.sublist("coarse: params");
    c.set("schwarz: overlap level", 0);
    c.set("schwarz: combine mode", "ZERO");
    c.set("subdomain solver name", "AMESOS2");
  }
  p.setParameters(user);
  if (!nullspace.is_null()) p.sublist("user data").set("Nullspace", nullspace);
  if (!coordinates.is_null()) p.sublist("user data").set("Coordinates", coordinates);
  Teuchos::RCP<Operator> op = A;
  same_random_start();
  // before it reads `verbosity`, MueLu prints at its default level (high) the edit distance of
  // every valid name to an unknown one (190 lines on stdout): quiet unless the user asked
  if (!user.isParameter("verbosity")) MueLu::VerboseObject::SetDefaultVerbLevel(MueLu::None);
  return MueLu::CreateTpetraPreconditioner(op, p);
#endif
}

bool muelu_available() {
#ifdef EMC_HAVE_MUELU
  return true;
#else
  return false;
#endif
}

void refresh_muelu(const Teuchos::RCP<Matrix>& A, Operator& prec) {
#ifndef EMC_HAVE_MUELU
  (void)A;
  (void)prec;
#else
  auto* op = dynamic_cast<MueLu::TpetraOperator<Scalar, LO, GO, Node>*>(&prec);
  if (!op) throw std::logic_error("refresh_muelu: not a MueLu preconditioner");
  same_random_start();
  MueLu::ReuseTpetraPreconditioner(A, *op);
#endif
}

}  // namespace emc::linalg
