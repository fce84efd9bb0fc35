#pragma once
// docs/THEORY.md §7.4: the velocity update that gives back the energy a gap closure moved.
// V_{n+1} += gamma dv with M dv = p (the consistent mass on the free dofs; p the impulse
// direction along the contact normals, which keeps L and J), gamma >= 0 the root of
//   gamma dv.M V + gamma^2 / 2 dv.M dv = D
// (the kinetic energy rises by exactly D, whatever the accuracy of the mass solve).
#include <Teuchos_RCP.hpp>
#include <vector>

#include "emcontact/fem/discretization.hpp"
#include "emcontact/types.hpp"

namespace emc::time {

struct Restoration {
  bool ok = true;      ///< false: no gamma gives D (D < 0 beyond what the impulse can take)
  double gamma = 0;    ///< the impulse's size
  int iterations = 0;  ///< CG iterations of the mass solve
};

class EnergyRestoration {
 public:
  /// `fixed`: my owned Dirichlet dofs (their velocity never changes).
  EnergyRestoration(const fem::Discretization& disc, const std::vector<GO>& fixed);
  /// Adds gamma M^-1 p to V so that the kinetic energy rises by D (collective). Nothing when
  /// p = 0 or |D| <= roundoff (a closure of gaps at round-off: bodies at rest on each other).
  Restoration restore(const Vector& p, double D, double roundoff, Vector& V) const;

 private:
  const fem::Discretization& disc_;
  Teuchos::RCP<Vector> free_;     ///< 1 on free dofs, 0 on fixed ones
  Teuchos::RCP<Vector> inverse_;  ///< the inverse lumped mass (1 on fixed dofs): CG's Jacobi
};

}  // namespace emc::time
