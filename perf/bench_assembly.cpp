// The solver's assembly and elimination benchmarks (Tpetra; the element kernels alone are the
// kernel library's bench_kernels, kernels/bench). Counters are per core: Kokkos is Serial in
// Debian's Trilinos, so one process = one core.
//   BM_Assembly        the whole assembly driver: import, kernels, scatter into the FECrsMatrix
//   BM_Elimination     one Newton iteration's elimination: P^T A P + D, P^T g and P dq
//                      (...NewPattern: after an active-set change; ...Rigid: the masked path)
#include <benchmark/benchmark.h>

#include <Tpetra_Core.hpp>

#include "emcontact/fem/discretization.hpp"
#include "emcontact/linalg/elimination.hpp"
#include "support/box_model.hpp"

/// The assembly of a box of n^3 cubes (6 n^3 tets) with the scatter `how` (Solver/Assembly/
/// scatter): BM_Assembly one loop per element colour with plain adds (the default),
/// BM_AssemblyAtomic one loop over all elements with atomic adds.
static void assembly_bench(benchmark::State& state, emc::fem::Scatter how) {
  emc::fem::Model m = emc::test::box_model(static_cast<int>(state.range(0)));
  m.scatter = how;
  emc::fem::Discretization disc(m, Tpetra::getDefaultComm());
  emc::Vector u0(disc.owned_map()), V0(disc.owned_map()), u1(disc.owned_map()), r(disc.owned_map()),
      sc(disc.owned_map());
  u1.randomize();
  u1.scale(1e-3);
  V0.randomize();
  emc::FEMatrix A(disc.graph());
  disc.assemble(u0, V0, u1, 1e-3, &A, r, &sc);  // first call finds the CRS offsets once
  for (auto _ : state) disc.assemble(u0, V0, u1, 1e-3, &A, r, &sc);
  state.counters["tets"] = m.num_tets();
  state.counters["colours"] = disc.colouring().colours();
  state.counters["tets_per_s"] =
      benchmark::Counter(double(state.iterations()) * m.num_tets(), benchmark::Counter::kIsRate);
}
static void BM_Assembly(benchmark::State& state) {
  assembly_bench(state, emc::fem::Scatter::coloured);
}
static void BM_AssemblyAtomic(benchmark::State& state) {
  assembly_bench(state, emc::fem::Scatter::atomic);
}
BENCHMARK(BM_Assembly)->Arg(20)->Arg(40)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AssemblyAtomic)->Arg(20)->Arg(40)->Unit(benchmark::kMillisecond);

/// The elimination of one Newton iteration (docs/THEORY.md §3) on the box of BM_Assembly: the
/// bottom face fixed (Dirichlet) and every top-face node a stick slave with a dummy beta on its
/// own dofs, tied to the three nodes of a facet one layer below (weights 0.5, 0.3, 0.2:
/// a deformable master, the structured reduction) or to a rigid master (an empty row of P:
/// the masked path). BM_EliminationNewPattern moves every slave to the neighbouring facet at
/// each iteration, so that the reduction's pattern is rebuilt every time (an active-set change);
/// BM_Elimination keeps the pattern (the other Newton iterations).
enum class Masters { deformable, deformable_moving, rigid };

static std::vector<emc::linalg::PRow> stick_rows(int n, const emc::Map& map, Masters kind,
                                                 int shift, std::vector<emc::GO>& fixed,
                                                 std::vector<std::pair<emc::GO, double>>& dummy) {
  auto id = [n](int i, int j, int l) { return (l * (n + 1) + j) * (n + 1) + i; };
  std::vector<emc::linalg::PRow> rows;
  fixed.clear();
  dummy.clear();
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      for (int c = 0; c < 3; ++c) {
        const emc::GO bottom = emc::fem::dof_gid(id(i, j, 0), c);
        if (map.isNodeGlobalElement(bottom)) fixed.push_back(bottom);
        const emc::GO slave = emc::fem::dof_gid(id(i, j, n), c);
        if (!map.isNodeGlobalElement(slave)) continue;
        // the facet's second node: the right neighbour (shift 0) or the left one (shift 1)
        const int i2 = shift == 0 ? (i < n ? i + 1 : i - 1) : (i > 0 ? i - 1 : i + 1);
        const int j1 = j < n ? j + 1 : j - 1;
        if (kind == Masters::rigid)
          rows.push_back({slave, {}, {}});
        else
          rows.push_back(
              {slave,
               {emc::fem::dof_gid(id(i, j, n - 1), c), emc::fem::dof_gid(id(i2, j, n - 1), c),
                emc::fem::dof_gid(id(i, j1, n - 1), c)},
               {0.5, 0.3, 0.2}});
        dummy.emplace_back(slave, 1e3);
      }
  return rows;
}

static void elimination_bench(benchmark::State& state, Masters kind) {
  const int n = static_cast<int>(state.range(0));
  const emc::fem::Model m = emc::test::box_model(n);
  emc::fem::Discretization disc(m, Tpetra::getDefaultComm());
  const auto map = disc.owned_map();
  std::vector<emc::GO> fixed;
  std::vector<std::pair<emc::GO, double>> dummy;
  std::vector<emc::linalg::PRow> rows[2];
  for (int s = 0; s < 2; ++s) rows[s] = stick_rows(n, *map, kind, s, fixed, dummy);
  emc::linalg::Elimination elim(map);
  elim.set_constraints(fixed, rows[0], dummy);
  emc::Vector u0(map), V0(map), u1(map), g(map), sc(map), R(map), du(map);
  u1.randomize();
  u1.scale(1e-3);
  auto A = Teuchos::rcp(new emc::FEMatrix(disc.graph()));
  disc.assemble(u0, V0, u1, 1e-3, A.get(), g, &sc);
  elim.reduce_matrix(A);  // the pattern of rows[0], found once (BM_EliminationNewPattern: again)
  int it = 0;
  for (auto _ : state) {
    if (kind == Masters::deformable_moving) elim.set_constraints(fixed, rows[++it % 2], dummy);
    auto Ar = elim.reduce_matrix(A);
    elim.reduce_residual(g, R);
    elim.expand(R, du);
    benchmark::DoNotOptimize(Ar.get());
  }
  state.counters["dofs"] = static_cast<double>(map->getGlobalNumElements());
  state.counters["slave_dofs"] = static_cast<double>(rows[0].size());
  state.counters["pattern_builds"] = elim.pattern_builds();
}
static void BM_Elimination(benchmark::State& state) {
  elimination_bench(state, Masters::deformable);
}
static void BM_EliminationNewPattern(benchmark::State& state) {
  elimination_bench(state, Masters::deformable_moving);
}
static void BM_EliminationRigid(benchmark::State& state) {
  elimination_bench(state, Masters::rigid);
}
BENCHMARK(BM_Elimination)->Arg(20)->Arg(40)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EliminationNewPattern)->Arg(20)->Arg(40)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EliminationRigid)->Arg(20)->Arg(40)->Unit(benchmark::kMillisecond);

int main(int argc, char** argv) {
  Tpetra::ScopeGuard scope(&argc, &argv);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
