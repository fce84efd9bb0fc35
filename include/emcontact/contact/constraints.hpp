#pragma once
// The constraints of the active contact set inside Newton (docs/THEORY.md §3-§5): each law's rows
// of P (and Pt, X for a law whose rows follow the iterate), beta on the dummies (eq. 44, 59),
// and the law's projection of the start iterate and of every update.
#include <vector>

#include "emcontact/contact/active_kernels.hpp"
#include "emcontact/contact/contact.hpp"
#include "emcontact/contact/law.hpp"
#include "emcontact/contact/state.hpp"
#include "emcontact/linalg/elimination.hpp"

namespace emc::contact {

class ActiveConstraints : public linalg::ConstraintHooks {
 public:
  ActiveConstraints(const Contact& contact, linalg::Elimination& elim, std::vector<GO> fixed);

  /// The trial active set of the step (frictionless entries get their facet and xi updated in
  /// place). Rebuilds P when the set differs from the last one on any rank (collective);
  /// returns true if the set's entries (slave nodes, and stick or slip) changed: the Newton
  /// matrix changed more than from iterate to iterate (an iterate-dependent law's P is rebuilt
  /// at every iterate anyway). index: the entries of the set my chains reach (Contact::gather).
  bool use(std::vector<Active>* trial, ActiveIndex index);
  /// The entries of the trial set my chains reach (Contact::gather).
  const ActiveIndex& index() const { return index_; }
  /// The trial set on the execution space, which Newton's iterates update.
  const ContactState& state() const { return state_; }
  ContactState& state() { return state_; }
  /// After a solve: the facets, xi and off flags the iterates moved into the trial set.
  void sync(std::vector<Active>& trial) const { to_host(state_, trial); }
  /// The contact nodes at t_n (the positions at u0 of the current contact nodes), for start.
  void set_start_positions(Positions x0) { x0_ = x0; }

  void start(const Vector& u0, Vector& u1) override;
  void before_reduce(const Vector& u0, const Vector& u1, Vector& g, const Matrix& A) override;
  void after_update(const Vector& u0, Vector& u1) override;
  double residual_roundoff() const override { return roundoff_; }
  /// The Newton matrix of the last iterate (null before the first).
  const Matrix* matrix() const { return A_; }
  bool abandon(int iteration, double r, double r0) override;

 private:
  const Contact& contact_;
  linalg::Elimination& elim_;
  std::vector<GO> fixed_;
  std::vector<Active>* trial_ = nullptr;
  std::vector<std::array<double, 5>> applied_;  ///< (slave, facet, xi, slip) P was built for
  std::vector<std::array<int, 2>> members_;     ///< (slave, slip) of the last set used
  Kokkos::View<GO*, ExecSpace> dummy_dofs_;     ///< the set's dummies, a slave's three in a row
  Values beta_;                                 ///< beta per slave of dummy_dofs_ (eq. 44)
  DiagonalOffsets dummy_diagonal_;              ///< their diagonal entries in A's values
  Teuchos::RCP<const Graph> dummy_graph_;       ///< the graph of A dummy_diagonal_ is for
  std::vector<const Law*> present_;             ///< laws with an entry on some rank
  bool iterate_dependent_ = false;              ///< some present law's rows follow the iterate
  Positions x0_;                                ///< contact nodes at t_n
  ActiveIndex index_;                           ///< the entries my chains reach
  ContactState state_;                          ///< the trial set's rows (Newton's iterates)
  double roundoff_ = 0;                         ///< LawRows::roundoff at the last iterate
  const Matrix* A_ = nullptr;                   ///< the Newton matrix of the last iterate

  LawState law_state(Positions x1);
  void exchange();
  void subtract_loads(const std::vector<std::pair<GO, double>>& load, Vector& g) const;
};

}  // namespace emc::contact
