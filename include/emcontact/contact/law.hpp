#pragma once
// One contact law per object (docs/THEORY.md §4 full stick, §5 frictionless): where xi is taken
// at activation, the rows it adds to the elimination (P, its exact right factor Pt, the
// variation X, the dummies' beta), and how it restores its constraints on the iterate. A new law
// implements this interface and is returned by make_law; the others are not touched.
#include <memory>
#include <vector>

#include "emcontact/contact/active.hpp"
#include "emcontact/contact/nodes.hpp"
#include "emcontact/linalg/elimination.hpp"

namespace emc::contact {

class Contact;
struct ContactState;

/// What a law sees of the iterate: the entries its chains reach (index), the contact nodes'
/// positions at t_n and at the iterate (empty when the law's rows do not depend on the
/// iterate), and the trial set's state (state.hpp), which holds what the laws keep from one
/// iterate or solve to the next: a law object holds no state of its own.
struct LawState {
  const Contact& contact;
  const ActiveIndex& index;
  Positions x0, x1;
  Positions::HostMirror xh;  ///< at n+1/2 (frictionless chains)
  /// The Newton matrix of the last solve (the return map's slip resolution, docs/THEORY.md
  /// §11.4), or null.
  const Matrix* A = nullptr;
  /// The trial set's state on the execution space (ActiveConstraints::state).
  ContactState* state = nullptr;
};

/// The elimination's rows a law contributes.
struct LawRows {
  std::vector<linalg::PRow> rows;           ///< rows of P
  std::vector<linalg::PRow> pt_rows;        ///< rows of Pt that differ from P's
  std::vector<linalg::Entry> X;             ///< the variation of P^T
  std::vector<std::pair<GO, double>> beta;  ///< (dummy dof, beta) from the Newton matrix
  std::vector<GO> dummies;  ///< dummies whose beta follows A while P is kept (eq. 44)
  /// Coulomb friction (docs/THEORY.md §11): rows of the left factor that differ from P's
  /// (Pl^T A Pt), and the friction forces (dof, value), subtracted from the residual g.
  std::vector<linalg::PRow> pl_rows;
  std::vector<std::pair<GO, double>> load;
  /// Rows that follow the iterate: sum over my slaves of (beta * position round-off)^2, the
  /// residual that re-projecting the slaves leaves at every iterate (Newton's floor).
  double roundoff = 0;
};

class Law {
 public:
  virtual ~Law() = default;
  virtual Kind kind() const = 0;
  /// §6.3: xi at activation is the CPP in the configuration x0 + w (x1 - x0).
  virtual double activation_weight() const = 0;
  /// §6.3 and docs/THEORY.md §7.2: whether that xi is clamped to the facet.
  virtual bool clamps(const Pair& p) const = 0;
  /// Whether P (Pt, X) changes with the iterate and is rebuilt at every Newton iteration.
  virtual bool iterate_dependent() const = 0;
  /// The rows of this law's entries among `active` at the iterate; g the contactless residual
  /// and A the Newton matrix (null when only P is asked for: the set changed).
  virtual void rows(const LawState& s, const std::vector<Active>& active, const Vector* g,
                    const Matrix* A, LawRows& out) const = 0;
  /// Newton's start iterate satisfies the law's constraints (collective; called on every rank
  /// when any rank has an entry of this law).
  virtual void start(const LawState& s, std::vector<Active>& active, Vector& u1) const = 0;
  /// After u1 += P dq: restores the nonlinear constraints (collective, as start).
  virtual void after_update(const LawState& s, std::vector<Active>& active, Vector& u1) const = 0;
  /// §6.4: whether an entry with normal force fN is released at the end of the solve.
  virtual bool releases(const Active& a, double fN) const = 0;
  /// docs/THEORY.md §11.4: after a converged solve (g its residual), the law's entries of
  /// `active` that are kept may change their state (stick/slip); returns how many did (local).
  virtual int settle(const LawState&, std::vector<Active>&, const Vector&) const { return 0; }
  /// §6.3: the state (stick/slip) of the law's entries `fresh` activated on the solve (g).
  virtual void activate(const LawState&, std::vector<Active>&, const Vector&) const {}
  /// After a failed solve: entries whose state is to blame change it; returns how many (local).
  virtual int after_failure(const LawState&, std::vector<Active>&) const { return 0; }
  /// The energy the law's entries dissipated over the step at the solution (local sum).
  virtual double dissipation(const LawState&, const std::vector<Active>&, const Vector&) const {
    return 0;
  }
};

std::shared_ptr<const Law> make_law(Kind kind);

}  // namespace emc::contact
