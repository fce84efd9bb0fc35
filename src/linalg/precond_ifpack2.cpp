#include <Ifpack2_Factory.hpp>
#include <Ifpack2_Parameters.hpp>

#include "emcontact/linalg/linear_solver.hpp"

namespace emc::linalg {
namespace {

/// Whether Ifpack2 parameter `name` (known to Ifpack2) belongs to a preconditioner other than
/// `type`, by its family prefix: RILUK reads only "fact:" names, Chebyshev only "chebyshev:"
/// ones (Schwarz hands names to its inner preconditioner: never flagged).
bool of_another_preconditioner(const std::string& name, Preconditioner type) {
  if (type == Preconditioner::schwarz) return false;
  const std::string own = type == Preconditioner::chebyshev ? "chebyshev:" : "fact:";
  for (const char* family :
       {"fact:", "chebyshev:", "relaxation:", "schwarz:", "partitioner:", "krylov:", "amesos2"})
    if (name.rfind(family, 0) == 0) return own != family;
  return false;
}

}  // namespace

// `ilu`: RILUK(0); `schwarz`: restricted additive Schwarz with overlap 1 and RILUK(0) inside
// (measured best of the Ifpack2 options on 2 ranks, perf/README.md "Linear solvers"). The user's
// `Ifpack2` sublist overrides these defaults unchanged.
Teuchos::RCP<Operator> make_ifpack2(Preconditioner type, const Teuchos::RCP<const Matrix>& A,
                                    const Teuchos::ParameterList& user,
                                    std::vector<std::string>* unused,
                                    std::vector<std::string>* ignored) {
  Teuchos::ParameterList p;
  std::string name = "RILUK";
  if (type == Preconditioner::schwarz) {
    name = "SCHWARZ";
    p.set("schwarz: overlap level", 1);
    p.set("schwarz: combine mode", "ZERO");  // restricted additive Schwarz
    p.set("schwarz: inner preconditioner name", "RILUK");
    p.sublist("schwarz: inner preconditioner parameters").set("fact: iluk level-of-fill", 0);
  } else if (type == Preconditioner::chebyshev) {
    name = "CHEBYSHEV";
    p.set("chebyshev: degree", 3);
  } else {
    p.set("fact: iluk level-of-fill", 0);
  }
  p.setParameters(user);
  auto prec = Ifpack2::Factory::create<Matrix>(name, A);
  prec->setParameters(p);
  if (unused || ignored) {  // Ifpack2 ignores names it does not know, and other families'
    Teuchos::ParameterList valid;
    Ifpack2::getValidParameters(valid);
    for (auto it = user.begin(); it != user.end(); ++it) {
      const std::string& n = user.name(it);
      if (!valid.isParameter(n)) {
        if (unused) unused->push_back(n);
      } else if (ignored && of_another_preconditioner(n, type)) {
        ignored->push_back(n);
      }
    }
  }
  same_random_start();
  prec->initialize();
  prec->compute();
  return prec;
}

}  // namespace emc::linalg
