#pragma once
// `Solver/Linear` of the input (the linear solver): declared here, put in the input's schema by
// the app (emc::app::input_schema).
#include <Teuchos_ParameterList.hpp>

namespace emc::linalg {

/// The values of the choices of `Solver/Linear` (their validators', read with
/// Teuchos::getIntegralValue): `type`, `multigrid near null space`, `multigrid positions`,
/// `multigrid reuse`, `preconditioner` (`automatic` is `auto`: by size and threads).
enum class SolverType { gmres, cg, klu2, mumps, umfpack };
enum class Preconditioner { automatic, ilu, schwarz, chebyshev, muelu, none };
enum class NullSpace { rigid_body_modes, translations };
enum class ModePositions { current, reference };
enum class MultigridReuse { refresh, rebuild };

/// The most iterations of one Krylov solve (`max iterations`, and the Belos sublist's
/// `Maximum Iterations`).
constexpr int kMaxLinearIterations = 100000;

/// Valid parameters of `Solver/Linear` (read by LinearSolver): `type` (gmres | cg | klu2 |
/// mumps | umfpack), `preconditioner` (auto | ilu | schwarz | muelu | none), `tolerance`, `max
/// iterations`, `reuse preconditioner`, `factorisation reuse rate`, the multigrid choices,
/// `residual check factor`, and the pass-through sublists `Belos`, `Ifpack2`, `MueLu` whose
/// contents go unchanged to Trilinos.
Teuchos::RCP<const Teuchos::ParameterList> valid_linear_parameters();

}  // namespace emc::linalg
