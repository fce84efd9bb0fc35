#pragma once
// The time module's settings: the `Time` section and `Solver/Newton` of the input, read once at
// set-up (emc::time::read_settings, beside their schema in parameters.hpp) into plain structs.
#include "kernels/em_tet4.hpp"

namespace emc::time {

/// `Solver/Newton`.
struct NewtonOptions {
  double rtol = 1e-10, atol = 0;
  int max_iterations = 25;
  bool adaptive_linear_tolerance = true;  ///< see Newton::linear_tolerance
  bool skip_last_matrix = true;           ///< no Newton matrix at an iterate predicted to converge
  bool warm_resolves = true;  ///< the active-set loop's re-solves start from the last solve
  double search_rtol = 0;     ///< the active-set loop's search solves (0: to rtol)
};

/// Settling to static equilibrium before t = 0 (docs/THEORY.md §6.7, `Time/settle ...`).
struct SettleOptions {
  int max_steps = 0;  ///< 0: no settling
  /// done when a step of dt from rest gives a kinetic energy below tolerance times the
  /// elastic energy, with the same active set
  double tolerance = 1e-12;
};

/// The time loop's steps: `Time/dt`, `end`, `max step cuts`, `grow after`.
struct StepOptions {
  double dt = 0.01, end = 1.0;
  int max_cuts = 6, grow_after = 4;
};

struct Settings {
  /// `Time/integrator`: the element kernels' stress (the fem model's, set from here)
  kernels::Integrator integrator = kernels::Integrator::energy_momentum;
  StepOptions step;
  SettleOptions settle;
  NewtonOptions newton;
};

}  // namespace emc::time
