// DirectSolver::as_operator: the factors' inverse as a Tpetra operator.
#include "emcontact/linalg/direct_solver.hpp"

#include "emcontact/error.hpp"

namespace emc::linalg {
namespace {

using Teuchos::RCP;

class DirectInverse : public Operator {
 public:
  DirectInverse(DirectSolver& s, RCP<const Map> map) : s_(s), map_(std::move(map)), z_(map_) {}
  RCP<const Map> getDomainMap() const override { return map_; }
  RCP<const Map> getRangeMap() const override { return map_; }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp mode, double alpha,
             double beta) const override {
    if (mode != Teuchos::NO_TRANS)
      throw Error(std::string("internal: the ") + s_.name() + " operator has no transpose");
    for (std::size_t j = 0; j < X.getNumVectors(); ++j) {
      s_.solve(*X.getVector(j), z_);
      Y.getVectorNonConst(j)->update(alpha, z_, beta);
    }
  }

 private:
  DirectSolver& s_;
  RCP<const Map> map_;
  mutable Vector z_;  ///< one solve's result, kept: every GMRES iteration applies the operator
};

}  // namespace

RCP<Operator> DirectSolver::as_operator() {
  if (rows_.is_null())
    throw Error(std::string("internal: ") + name() + " operator before any factorisation");
  return Teuchos::rcp(new DirectInverse(*this, rows_));
}

}  // namespace emc::linalg
