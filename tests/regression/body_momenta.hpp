#pragma once
// Linear momentum of each body of a simulation (tests only).
#include <Teuchos_CommHelpers.hpp>
#include <array>
#include <vector>

#include "emcontact/app/simulation.hpp"
#include "support/replicate.hpp"

namespace emc::testing {

/// Linear momentum of each body from the row sums of the mass matrix (with massless nodes, exact:
/// sum_AB M_AB V_B = sum_B (sum_A M_AB) V_B, docs/THEORY.md §6.8). Collective (replicates V).
inline std::vector<std::array<double, 3>> body_momenta(emc::app::Simulation& sim) {
  const auto& m = sim.model;
  const auto V = replicate(*sim.disc, *sim.state.V);
  const std::vector<double> mine = emc::fem::mass_row_sums(m);  // of this rank's own tets
  std::vector<double> lumped(mine.size());
  Teuchos::reduceAll(*sim.disc->comm(), Teuchos::REDUCE_SUM, static_cast<int>(mine.size()),
                     mine.data(), lumped.data());
  std::vector<std::array<double, 3>> p(m.bodies.size(), {0, 0, 0});
  for (std::size_t b = 0; b < m.bodies.size(); ++b)
    for (int n = m.bodies[b].node_begin; n < m.bodies[b].node_end; ++n)
      for (int i = 0; i < 3; ++i) p[b][i] += lumped[n] * V[3 * n + i];
  return p;
}

}  // namespace emc::testing
