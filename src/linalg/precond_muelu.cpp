#include "emcontact/linalg/linear_solver.hpp"

#ifdef EMC_HAVE_MUELU
#include <MueLu_CreateTpetraPreconditioner.hpp>
#else
#include <stdexcept>
#endif

namespace emc::linalg {

// Smoothed aggregation for 3 dofs per node. On 2+ ranks Debian's Amesos2 KLU2 coarse solver is
// wrong (README "Toolchain"), so the coarse level uses Schwarz with local direct solves unless
// the user's `MueLu` sublist says otherwise.
Teuchos::RCP<Operator> make_muelu(const Teuchos::RCP<Matrix>& A,
                                  const Teuchos::ParameterList& user) {
#ifndef EMC_HAVE_MUELU
  (void)A;
  (void)user;
  throw std::runtime_error(
      "Linear solver/preconditioner = \"muelu\": this build of emcontact has no MueLu (the Trilinos "
      "it was built against lacks it); allowed here: ilu, schwarz, none");
#else
  Teuchos::ParameterList p;
  p.set("number of equations", 3);
  p.set("verbosity", "none");
  if (A->getComm()->getSize() > 1) {
    p.set("coarse: type", "SCHWARZ");
    auto& c = p.sublist("coarse: params");
    c.set("schwarz: overlap level", 0);
    c.set("schwarz: combine mode", "ZERO");
    c.set("subdomain solver name", "AMESOS2");
  }
  p.setParameters(user);
  Teuchos::RCP<Operator> op = A;
  return MueLu::CreateTpetraPreconditioner(op, p);
#endif
}

}  // namespace emc::linalg
