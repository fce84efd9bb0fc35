// Element-kernel benchmarks of the kernel library (Google Benchmark), on every enabled execution
// space (the name's second part); rates are per process and wall-clock second (OpenMP: all
// its threads), the CPU column the process's (all threads).
//   BM_EmTet4                  energy-momentum force + exact 12x12 tangent + mass of one
//                              element (newton_tet4, one core, the kernel alone; SVK)
//   BM_EmTet4NeoHookean, BM_EmTet4MooneyRivlin   the same with the discrete gradient of
//                              kernels/hyperelastic.hpp (docs/THEORY.md §12): u_n, u_{n+1}
//                              random (+-0.1), the direct branch of delta (§12.3)
//   BM_EmTet4NeoHookeanSmallStep   u_{n+1} within +-1e-4 of u_n (a dynamic step): its series
//                              (the counter series_order: K of §12.3, 0 for the direct branch)
//   BM_Tet4Force/<space>/n     the force-only loop over a box of 6 n^3 tets (em_tet4_forces;
//                              the nodal forces zeroed, then summed: atomic adds when threaded)
//   BM_Tet4Tangent/<space>/n   force + exact tangent added into the CRS matrix of the tets'
//                              pattern (em_tet4_assemble; forces and values zeroed first)
//   .../<space>/coloured/n     the same colour by colour (TetColouring: plain adds)
#include <benchmark/benchmark.h>

#include <Kokkos_Core.hpp>
#include <random>
#include <string>

#include "bench_util.hpp"
#include "kernels/newton_tet4.hpp"
#include "kernels/tet4_loops.hpp"
#include "support/meshes.hpp"

namespace k = emc::kernels;
namespace t = emc::kernels::test;

/// The order of delta's series between u0 and u1 (docs/THEORY.md §12.3; 0: the direct branch;
/// -1: SVK, which has none).
static int series_order(const k::Lame&, const double[4][3], const double[2][4][3]) {
  return -1;
}
static int series_order(const k::LogHyperelastic& m, const double G[4][3],
                        const double u[2][4][3]) {
  double H[2][3][3], E[2][3][3], M[3][3];
  for (int n = 0; n < 2; ++n) {
    k::displacement_gradient(G, u[n], H[n]);
    k::green_strain(H[n], E[n]);
  }
  k::DiscreteGradient dg;
  k::discrete_gradient(m, E[0], E[1], dg, false);
  if (!dg.series) return 0;
  k::hyper_detail::mul(dg.Ci, dg.dE, M);
  return k::hyper_detail::series_order(k::hyper_detail::dot(M, M));
}

/// u_n, V_n random (+-0.1), u_{n+1} random (+-0.1) or, step > 0, u_n + (+-step).
template <class Material>
static void newton_element(benchmark::State& state, const Material& material, double step = 0) {
  double X[4][3] = {{0, 0, 0}, {1, 0.1, 0}, {0.1, 1, 0.1}, {0, 0.2, 1}}, G[4][3];
  const double Ve = k::tet_gradients(X, G);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> d(-0.1, 0.1);
  k::ElementState s;
  for (int a = 0; a < 4; ++a)
    for (int i = 0; i < 3; ++i) {
      s.u0[a][i] = d(rng);
      s.u1[a][i] = d(rng);
      s.V0[a][i] = d(rng);
      if (step > 0) s.u1[a][i] = s.u0[a][i] + step / 0.1 * d(rng);
    }
  double u[2][4][3];
  for (int a = 0; a < 4; ++a)
    for (int i = 0; i < 3; ++i) u[0][a][i] = s.u0[a][i], u[1][a][i] = s.u1[a][i];
  const int order = series_order(material, G, u);
  if (order >= 0) state.counters["series_order"] = order;
  const double grav[3] = {0, 0, -9.81};
  double r[12], A[12][12], sc[12];
  for (auto _ : state) {
    for (int p = 0; p < 12; ++p)
      for (int q = 0; q < 12; ++q) A[p][q] = 0;
    k::newton_tet4(G, Ve, material, 1000, grav, k::Integrator::energy_momentum, 1e-3, s, r, A, sc);
    benchmark::DoNotOptimize(A);
    s.u1[0][0] += 1e-12;
  }
  state.counters["tets_per_s"] =
      benchmark::Counter(state.iterations(), benchmark::Counter::kIsRate);
}
static void BM_EmTet4(benchmark::State& state) {
  newton_element(state, k::lame(1e6, 0.3));
}
BENCHMARK(BM_EmTet4);
static void BM_EmTet4NeoHookean(benchmark::State& state) {
  const k::Lame l = k::lame(1e6, 0.3);
  newton_element(state, k::neo_hookean(l.lambda, l.mu));
}
BENCHMARK(BM_EmTet4NeoHookean);
static void BM_EmTet4NeoHookeanSmallStep(benchmark::State& state) {
  const k::Lame l = k::lame(1e6, 0.3);
  newton_element(state, k::neo_hookean(l.lambda, l.mu), 1e-4);
}
BENCHMARK(BM_EmTet4NeoHookeanSmallStep);
static void BM_EmTet4MooneyRivlin(benchmark::State& state) {
  const k::Lame l = k::lame(1e6, 0.3);
  newton_element(state, k::mooney_rivlin(0.5 * l.mu - 5e4, 5e4, l.lambda - 2e5));
}
BENCHMARK(BM_EmTet4MooneyRivlin);

namespace {

/// A box of 6 n^3 tets on E with random displacements (1e-3 of its size).
template <class E>
struct BoxOn {
  using M = typename E::memory_space;
  t::Box box;
  k::TetMesh<M> mesh;
  k::Points<M> u0, u1;
  k::Vectors3<M> f;
  explicit BoxOn(int n) : box(n) {
    const std::vector<double> v0 = t::random_values(box.X.size(), 1e-3, 1);
    const std::vector<double> v1 = t::random_values(box.X.size(), 1e-3, 2);
    const auto tets = t::rows<int, 4, M>(box.tets.data(), box.num_tets(), "bench::tets");
    mesh =
        k::TetMesh<M>(E(), tets, t::rows<double, 3, M>(box.X.data(), box.num_nodes(), "bench::X"));
    u0 = t::rows<double, 3, M>(v0.data(), box.num_nodes(), "bench::u0");
    u1 = t::rows<double, 3, M>(v1.data(), box.num_nodes(), "bench::u1");
    f = k::Vectors3<M>("bench::f", box.num_nodes());
  }
};

void tet_counters(benchmark::State& state, int tets) {
  state.counters["tets"] = tets;
  state.counters["tets_per_s"] =
      benchmark::Counter(double(state.iterations()) * tets, benchmark::Counter::kIsRate);
}

template <class E>
void tet4_force(benchmark::State& state, bool coloured) {
  BoxOn<E> b(static_cast<int>(state.range(0)));
  const E space;
  const k::TetColouring<typename E::memory_space> col(space, b.mesh.tets, b.box.num_nodes());
  for (auto _ : state) {
    Kokkos::deep_copy(space, b.f, 0.0);
    k::em_tet4_forces(space, b.mesh, k::lame(1e6, 0.3), k::Integrator::energy_momentum, b.u0, b.u1,
                      b.f, coloured ? &col : nullptr);
    space.fence();
  }
  tet_counters(state, b.box.num_tets());
  state.counters["colours"] = coloured ? col.colours() : 0;
}

template <class E>
void tet4_tangent(benchmark::State& state, bool coloured) {
  BoxOn<E> b(static_cast<int>(state.range(0)));
  const E space;
  const k::TetPattern<typename E::memory_space> K(space, b.mesh.tets, b.box.num_nodes());
  const k::TetColouring<typename E::memory_space> col(space, b.mesh.tets, b.box.num_nodes());
  for (auto _ : state) {
    Kokkos::deep_copy(space, b.f, 0.0);
    Kokkos::deep_copy(space, K.matrix.values, 0.0);
    k::em_tet4_assemble(space, b.mesh, k::lame(1e6, 0.3), k::Integrator::energy_momentum, b.u0,
                        b.u1, b.f, K, coloured ? &col : nullptr);
    space.fence();
  }
  tet_counters(state, b.box.num_tets());
  state.counters["colours"] = coloured ? col.colours() : 0;
  state.counters["nnz"] = static_cast<double>(K.matrix.values.extent(0));
}

struct Register {
  template <class E>
  static void on() {
    const std::string s = E::name();
    for (const bool coloured : {false, true}) {
      const std::string how = coloured ? "/coloured" : "";
      benchmark::RegisterBenchmark(
          ("BM_Tet4Force/" + s + how).c_str(),
          [coloured](benchmark::State& st) { tet4_force<E>(st, coloured); })
          ->Arg(20)
          ->Arg(40)
          ->Unit(benchmark::kMillisecond)
          ->MeasureProcessCPUTime()
          ->UseRealTime();
      benchmark::RegisterBenchmark(
          ("BM_Tet4Tangent/" + s + how).c_str(),
          [coloured](benchmark::State& st) { tet4_tangent<E>(st, coloured); })
          ->Arg(20)
          ->Arg(40)
          ->Unit(benchmark::kMillisecond)
          ->MeasureProcessCPUTime()
          ->UseRealTime();
    }
  }
};

}  // namespace

int main(int argc, char** argv) {
  Kokkos::ScopeGuard kokkos(argc, argv);
  t::for_each_space<Register>(t::Spaces());
  benchmark::Initialize(&argc, argv);
  t::add_kokkos_context();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
