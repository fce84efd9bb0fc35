#include "emcontact/contact/constraints.hpp"

namespace emc::contact {

ActiveConstraints::ActiveConstraints(const Contact& contact, linalg::Elimination& elim,
                                     std::vector<GO> fixed)
    : contact_(contact), elim_(elim), fixed_(std::move(fixed)) {
  elim_.set_constraints(fixed_, {}, {});
}

// ALGORITHM.md §3: rebuild P only when the active set changes (on any rank: collective).
bool ActiveConstraints::use(std::vector<Active>* trial) {
  trial_ = trial;
  std::vector<std::array<double, 4>> key;
  int fless = 0;
  for (const auto& a : *trial) {
    key.push_back({double(a.slave), double(a.facet), a.xi[0], a.xi[1]});
    fless += contact_.pairs()[a.pair].kind == Kind::frictionless;
  }
  frictionless_ = contact_.global_count(fless) > 0;
  if (contact_.global_count(key == applied_ ? 0 : 1) == 0) return false;
  std::vector<linalg::PRow> rows;
  dummies_.clear();
  contact_.constraint_rows(*trial, rows, dummies_);
  elim_.set_constraints(fixed_, rows, {});
  applied_ = std::move(key);
  return true;
}

void ActiveConstraints::start(const Vector&, Vector&) {}

void ActiveConstraints::before_reduce(const Vector&, const Vector&, const Vector&,
                                      const Matrix& A) {
  elim_.set_dummy_values(contact_.dummy_values(A, dummies_));  // beta, eq. 44
}

void ActiveConstraints::after_update(const Vector&, Vector&) {}

}  // namespace emc::contact
