#pragma once
// Linear momentum of each body of a simulation (tests only).
#include <array>
#include <vector>

#include "emcontact/app/simulation.hpp"
#include "kernels/mass_tet4.hpp"
#include "kernels/tet4.hpp"
#include "support/replicate.hpp"

namespace emc::testing {

/// Linear momentum of each body from the row sums of the mass matrix (with massless nodes, exact:
/// sum_AB M_AB V_B = sum_B (sum_A M_AB) V_B). Collective (replicates V).
inline std::vector<std::array<double, 3>> body_momenta(emc::app::Simulation& sim) {
  const auto& m = sim.model;
  const auto V = replicate(*sim.disc, *sim.state.V);
  std::vector<double> lumped(m.num_nodes(), 0.0);
  for (int e = 0; e < m.num_tets(); ++e) {
    double x[4][3];
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) x[a][i] = m.X[3 * m.tets[4 * e + a] + i];
    const double rho = m.bodies[m.body_of_tet[e]].density;
    double M[4][4];  // docs/THEORY.md §6.8
    emc::kernels::mass_matrix(rho, emc::kernels::tet_volume(x), emc::fem::massless_mask(m, e), M);
    for (int a = 0; a < 4; ++a) lumped[m.tets[4 * e + a]] += M[a][0] + M[a][1] + M[a][2] + M[a][3];
  }
  std::vector<std::array<double, 3>> p(m.bodies.size(), {0, 0, 0});
  for (std::size_t b = 0; b < m.bodies.size(); ++b)
    for (int n = m.bodies[b].node_begin; n < m.bodies[b].node_end; ++n)
      for (int i = 0; i < 3; ++i) p[b][i] += lumped[n] * V[3 * n + i];
  return p;
}

}  // namespace emc::testing
