// Schema of `Solver/Linear`.
#include "emcontact/linalg/parameters.hpp"

#include <cmath>
#include <limits>

#include "emcontact/input/validators.hpp"

namespace emc::linalg {
namespace {

using namespace emc::input;

void set_linear(Teuchos::ParameterList& pl) {
  set_choice(pl, "type", "gmres",
             "Linear solver: gmres; cg only for a symmetric Newton matrix (the midpoint integrator "
             "without frictionless contact; otherwise the run warns); klu2, direct, one rank only; "
             "mumps, direct, any number of ranks; umfpack, direct, one rank.",
             {"gmres", "cg", "klu2", "mumps", "umfpack"},
             {"Belos GMRES (iterative)",
              "Belos conjugate gradients (iterative; only for a symmetric Newton matrix: the "
              "mid-point integrator without frictionless contact, otherwise the run warns)",
              "Amesos2 KLU2 (direct, one rank)",
              "MUMPS (direct, any number of ranks; its factors are reused as GMRES's "
              "preconditioner while they work, see factorisation reuse rate)",
              "SuiteSparse UMFPACK (direct, one rank; factors reused like mumps', and cheaper "
              "to apply on the examples' systems, see perf/README.md)"},
             std::vector<SolverType>{SolverType::gmres, SolverType::cg, SolverType::klu2,
                                     SolverType::mumps, SolverType::umfpack});
  set_choice(
      pl, "preconditioner", "auto",
      "Preconditioner of the iterative solvers (ignored by klu2, mumps and umfpack); auto: "
      "muelu from Solver/Linear/multigrid from equations on, below it chebyshev on 2+ threads "
      "or from Solver/Linear/chebyshev from equations on, else ilu (perf/README.md).",
      {"auto", "ilu", "schwarz", "chebyshev", "muelu", "none"},
      {"muelu from Solver/Linear/multigrid from equations on (if built with MueLu), else "
       "chebyshev on 2+ threads or from Solver/Linear/chebyshev from equations on, else ilu",
       "Ifpack2 ILU", "Ifpack2 additive Schwarz",
       "Ifpack2 Chebyshev polynomial of the diagonally scaled matrix (matrix-vector products "
       "only: runs on threads)",
       "MueLu aggregation multigrid with rigid-body modes and Chebyshev smoothers (fewer "
       "Krylov iterations on large meshes, see perf/README.md)",
       "no preconditioner"},
      std::vector<Preconditioner>{Preconditioner::automatic, Preconditioner::ilu,
                                  Preconditioner::schwarz, Preconditioner::chebyshev,
                                  Preconditioner::muelu, Preconditioner::none});
  pl.set("tolerance", 1e-10,
         "Relative residual tolerance of the iterative solvers: every solve's with "
         "Solver/Newton/adaptive linear tolerance = false, else the tightest one (the solves "
         "that decide Newton's last iterate). Keep it below Newton's relative tolerance: a "
         "linear solve less accurate than Newton's target costs extra Newton iterations "
         "(perf/README.md). Below 1: the zero correction already meets a relative residual "
         "of 1, and Newton would not move.",
         double_range(std::numeric_limits<double>::min(), std::nextafter(1.0, 0.0)));
  pl.set("max iterations", 1000,
         "Iterations of the iterative solvers (at most 100000: a solve that long is a "
         "preconditioner that does not work; a stop signal ends one at its next iteration).",
         int_range(1, kMaxLinearIterations));
  pl.set("reuse preconditioner", true,
         "Reuse the preconditioner setup across solves where possible.");
  pl.set("factorisation reuse rate", 0.1,
         "mumps, umfpack: the factors of an earlier matrix stay GMRES's preconditioner while GMRES "
         "reduces the residual by at least this factor per iteration: it gets the iterations "
         "this rate needs to reach Solver/Linear/tolerance (a direct solve is exact, so the "
         "adaptive linear tolerance is not used), and if it has not converged then, the matrix "
         "is factored anew. Reuse preconditioner = false: a factorisation at every solve.",
         double_range(1e-6, 0.9));
  pl.set("multigrid from equations", 150000,
         "With preconditioner = auto: muelu for Newton systems of at least this many equations "
         "(3 per node), ilu or chebyshev below (the crossover measured in perf/README.md).",
         int_at_least(1));
  pl.set("chebyshev from equations", 8000,
         "With preconditioner = auto on one thread, below multigrid from equations: chebyshev "
         "for Newton systems of at least this many equations, ilu below (the one-core crossover "
         "measured in perf/README.md; on 2+ threads chebyshev at any size).",
         int_at_least(1));
  set_choice(
      pl, "multigrid near null space", "rigid body modes",
      "What the aggregation multigrid (preconditioner = muelu) must represent on coarse levels.",
      {"rigid body modes", "translations"},
      {"the six rigid-body modes of the node positions (3D elasticity)",
       "MueLu's default: one constant vector per dof (the translations)"},
      std::vector<NullSpace>{NullSpace::rigid_body_modes, NullSpace::translations});
  set_choice(pl, "multigrid positions", "current",
             "The node positions the rigid-body modes are built from, at each multigrid setup.",
             {"current", "reference"},
             {"X + u of the Newton iterate (the deformed body's rotations)",
              "the reference coordinates X"},
             std::vector<ModePositions>{ModePositions::current, ModePositions::reference});
  pl.set("multigrid modes zero at eliminated dofs", false,
         "Set the rigid-body modes to zero at eliminated dofs (Dirichlet and contact-slave "
         "dummy rows, which are decoupled from the others); false: the modes as they are.");
  set_choice(pl, "multigrid reuse", "refresh",
             "What a new active set (or a reused hierarchy that has become slow) does to the "
             "multigrid preconditioner before a full rebuild.",
             {"refresh", "rebuild"},
             {"recompute coarse operators and smoothers, keep aggregates and prolongators "
              "(MueLu reuse: type = RP); a full rebuild if still slow",
              "a full rebuild"},
             std::vector<MultigridReuse>{MultigridReuse::refresh, MultigridReuse::rebuild});
  pl.set("residual check factor", 100.0,
         "After each solve the true relative residual must be below factor * tolerance, "
         "else the run fails.",
         double_at_least(1.0));
  pl.sublist("Belos", false,
             "Passed to the Belos solver over emcontact's defaults (gmres: Orthogonalization = "
             "IMGS, Num Blocks = min(max iterations, 300); any Belos parameter; Maximum "
             "Iterations from 1 to 100000).")
      .disableRecursiveValidation();
  pl.sublist(
        "Ifpack2", false,
        "Passed to Ifpack2 over emcontact's defaults (ilu: fact: iluk level-of-fill = 0; "
        "chebyshev: chebyshev: degree = 3; schwarz: overlap 1, ILU(0) inside; any Ifpack2 "
        "parameter of the chosen preconditioner; a name Ifpack2 does not know, or one of another "
        "preconditioner's family (fact: with chebyshev, chebyshev: with ilu), is warned "
        "about at the start; chebyshev: degree and relaxation: sweeps at most 100).")
      .disableRecursiveValidation();
  pl.sublist("MueLu", false,
             "Passed to MueLu over emcontact's defaults (plain aggregation, Chebyshev degree 3 "
             "with eigenvalue ratio 7, reuse: type RP, a Schwarz coarse solve on 2+ ranks; any "
             "MueLu parameter, e.g. multigrid algorithm = sa; max levels at most 50, chebyshev: "
             "degree and relaxation: sweeps at most 100 in any sublist).")
      .disableRecursiveValidation();
}

}  // namespace

Teuchos::RCP<const Teuchos::ParameterList> valid_linear_parameters() {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList("Linear"));
  set_linear(*pl);
  return pl;
}

}  // namespace emc::linalg
