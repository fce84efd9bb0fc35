#include <Ifpack2_Factory.hpp>
#include <Ifpack2_Parameters.hpp>

#include "emcontact/linalg/linear_solver.hpp"

namespace emc::linalg {

// `ilu`: RILUK(0); `schwarz`: restricted additive Schwarz with overlap 1 and RILUK(0) inside
// (measured best of the Ifpack2 options on 2 ranks, see README "Toolchain"). The user's
// `Ifpack2` sublist overrides these defaults unchanged.
Teuchos::RCP<Operator> make_ifpack2(Preconditioner type, const Teuchos::RCP<const Matrix>& A,
                                    const Teuchos::ParameterList& user,
                                    std::vector<std::string>* unused) {
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
  if (unused) {  // Ifpack2 ignores names it does not know
    Teuchos::ParameterList valid;
    Ifpack2::getValidParameters(valid);
    for (auto it = user.begin(); it != user.end(); ++it)
      if (!valid.isParameter(user.name(it))) unused->push_back(user.name(it));
  }
  prec->initialize();
  prec->compute();
  return prec;
}

}  // namespace emc::linalg
