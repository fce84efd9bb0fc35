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
  int fless = 0, closing = 0;
  for (const auto& a : *trial) {
    key.push_back({double(a.slave), double(a.facet), a.xi[0], a.xi[1]});
    const Pair& p = contact_.pairs()[a.pair];
    fless += p.kind == Kind::frictionless;
    closing += p.kind == Kind::full_stick && contact_.closes(a);
  }
  frictionless_ = contact_.global_count(fless) > 0;
  closing_stick_ = contact_.global_count(closing) > 0;
  if (frictionless_) {  // P is rebuilt at every iterate anyway (xi changes inside Newton)
    applied_.clear();
    index_ = contact_.gather(*trial);
  }
  if (contact_.global_count(key == applied_ ? 0 : 1) == 0) return false;
  std::vector<linalg::PRow> rows;
  dummies_.clear();
  index_ = contact_.gather(*trial);
  contact_.constraint_rows(*trial, index_, {}, {}, rows, dummies_);
  elim_.set_constraints(fixed_, rows, {});
  applied_ = std::move(key);
  return true;
}

// §5: the start iterate is projected (update steps 2-3), so that it satisfies (a) and (b);
// docs/THEORY.md §7.2: closing full-stick slaves start on their master point.
void ActiveConstraints::start(const Vector& u0, Vector& u1) {
  if (closing_stick_) contact_.close_stick(*trial_, u1);
  if (!frictionless_) return;
  x0_ = positions(contact_.disc_model(), contact_.replicate(u0));
  after_update(u0, u1);
}

void ActiveConstraints::before_reduce(const Vector&, const Vector& u1, const Vector& g,
                                      const Matrix& A) {
  if (!frictionless_) {  // stick only: P is fixed during the step, beta follows A (eq. 44)
    elim_.set_dummy_values(contact_.dummy_values(A, dummies_));
    return;
  }
  // frictionless: P depends on the iterate (N, tau at n+1/2, the facet): rebuild every time
  const auto x1 = positions(contact_.disc_model(), contact_.replicate(u1));
  std::vector<linalg::PRow> rows, pt_rows;
  std::vector<linalg::Entry> X;
  std::vector<std::pair<GO, double>> beta;
  std::vector<GO> stick_dummies;
  contact_.constraint_rows(*trial_, index_, x0_, x1, rows, stick_dummies);  // Pt = P there
  beta = contact_.dummy_values(A, stick_dummies);
  contact_.frictionless_rows(*trial_, index_, x0_, x1, g, A, rows, pt_rows, X, beta);
  elim_.set_constraints(fixed_, rows, beta);
  elim_.set_linearisation(pt_rows, X);
}

void ActiveConstraints::after_update(const Vector&, Vector& u1) {
  if (!frictionless_) return;
  const auto x1 = positions(contact_.disc_model(), contact_.replicate(u1));
  contact_.frictionless_project(*trial_, x0_, x1, u1);
  index_ = contact_.gather(*trial_);  // xi and facets moved: chains use the new ones
}

}  // namespace emc::contact
