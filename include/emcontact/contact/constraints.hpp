#pragma once
// The constraints of the active contact set inside Newton (ALGORITHM.md §3-§5): the rows of P
// for the active slaves, beta on their dummies (eq. 44, 59), and for frictionless slaves the
// exact linearisation (Pt, X) and the update steps 2-3 after every Newton update.
#include <vector>

#include "emcontact/contact/contact.hpp"
#include "emcontact/linalg/elimination.hpp"

namespace emc::contact {

class ActiveConstraints : public linalg::ConstraintHooks {
 public:
  ActiveConstraints(const Contact& contact, linalg::Elimination& elim, std::vector<GO> fixed);

  /// The trial active set of the step (frictionless entries get their facet and xi updated in
  /// place). Rebuilds P when the set differs from the last one on any rank (collective);
  /// returns true if it did.
  bool use(std::vector<Active>* trial);

  void start(const Vector& u0, Vector& u1) override;
  void before_reduce(const Vector& u0, const Vector& u1, const Vector& g, const Matrix& A) override;
  void after_update(const Vector& u0, Vector& u1) override;

 private:
  const Contact& contact_;
  linalg::Elimination& elim_;
  std::vector<GO> fixed_;
  std::vector<Active>* trial_ = nullptr;
  std::vector<std::array<double, 4>> applied_;  ///< (slave, facet, xi) P was built for
  std::vector<GO> dummies_;
  bool frictionless_ = false;   ///< any active frictionless slave on any rank
  bool closing_stick_ = false;  ///< any active full-stick slave of a `close gap` pair
  std::vector<double> x0_;      ///< positions at t_n (frictionless)
  ActiveIndex index_;           ///< every rank's active entries (chains)
};

}  // namespace emc::contact
