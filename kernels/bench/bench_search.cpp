// Contact search benchmarks of the kernel library (docs/THEORY.md §2.5; Google Benchmark): the
// grid of a bumpy surface's 2 n^2 facets (n = 224: 100352 facets; n = 708: 1002528) and queries
// near it, max(100k, facets / 2) of them (about one per surface node). Host loops run on one
// core; <space> benchmarks on every enabled execution space (rates per process: OpenMP, all its
// threads; wall-clock rates, the CPU column the process's).
//   BM_ContactSearch/n                   grid built from host containers, then the random
//                                        queries one by one
//   BM_ContactGridBuild/<space>/n        the parallel build alone, from Views
//   BM_ContactQueries/n                  the random-order queries, one locate() each (/32: 2048
//                                        facets, all in cache: the computation alone)
//   BM_ContactQueriesOrdered/n           the same in spatial order (as slave nodes numbered
//                                        along a surface come)
//   BM_ContactQueriesBatch/n             random order through locate_all from host vectors
//                                        (the sort by cell included)
//   BM_ContactQueriesKernel/<space>/random/n, .../ordered/n
//                                        one locate() per query in a parallel_for, in random
//                                        or spatial order (no sort)
//   BM_ContactLocateAll/<space>/n        random order through locate_all on Views (the sort by
//                                        cell included)
#include <benchmark/benchmark.h>

#include <Kokkos_Core.hpp>
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "bench_util.hpp"
#include "kernels/search.hpp"
#include "support/meshes.hpp"

namespace {

namespace k = emc::kernels;
namespace t = emc::kernels::test;
using HostGrid = k::FacetGrid<Kokkos::HostSpace>;

/// A bumpy surface of 2 n^2 facets and random query points near it (q), also in spatial order
/// (sorted: rows of 2 / 7 n across y, then along x).
struct BumpySurface {
  t::Sheet sheet;
  std::vector<double> q, sorted;
  double margin;
  explicit BumpySurface(int n);
  std::size_t queries() const { return q.size() / 3; }
};

BumpySurface::BumpySurface(int n) : sheet(n, 0.05, 6, 4), margin(0.5 / n) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> d(0, 1), dz(-0.002, 0.002);
  const std::size_t count = std::max<std::size_t>(100000, sheet.facets.size() / 2);
  for (std::size_t k = 0; k < count; ++k) {
    const double px = d(rng), py = d(rng);
    q.insert(q.end(), {px, py, sheet.z(px, py) + dz(rng)});
  }
  std::vector<int> order(count);
  for (std::size_t k = 0; k < count; ++k) order[k] = static_cast<int>(k);
  const double rows = 2.0 * n / 7;
  auto key = [&](int k) { return std::make_pair(int(q[3 * k + 1] * rows), q[3 * k]); };
  std::sort(order.begin(), order.end(), [&](int a, int b) { return key(a) < key(b); });
  for (int k : order) sorted.insert(sorted.end(), {q[3 * k], q[3 * k + 1], q[3 * k + 2]});
}

/// Locates every query point (3 coordinates each) on the host; returns how many found a facet.
long locate_each(const HostGrid& grid, const std::vector<double>& q) {
  long found = 0;
  for (std::size_t k = 0; k < q.size() / 3; ++k) found += grid.locate(&q[3 * k]).facet >= 0;
  return found;
}

/// The counters of the contact benchmarks: surface size and queries per second.
void query_counters(benchmark::State& state, std::size_t facets, std::size_t queries) {
  state.counters["facets"] = static_cast<double>(facets);
  state.counters["queries"] = static_cast<double>(queries);
  state.counters["queries_per_s"] =
      benchmark::Counter(double(state.iterations()) * queries, benchmark::Counter::kIsRate);
}

template <class M>
k::Triangles<M> facets_view(const BumpySurface& s) {
  return t::rows<int, 3, M>(s.sheet.facets.front().data(), s.sheet.facets.size(), "bench::facets");
}
template <class M>
k::Points<M> points_view(const std::vector<double>& v, const char* label) {
  return t::rows<double, 3, M>(v.data(), v.size() / 3, label);
}

void BM_ContactSearch(benchmark::State& state) {
  const BumpySurface s(static_cast<int>(state.range(0)));
  long found = 0;
  for (auto _ : state) {
    HostGrid grid(s.sheet.facets, s.sheet.x, s.margin);  // rebuilt every step in the solver
    found += locate_each(grid, s.q);
  }
  benchmark::DoNotOptimize(found);
  query_counters(state, s.sheet.facets.size(), s.queries());
}

// The queries alone, one by one on the host, against a grid built once: random or spatial order.
void host_queries(benchmark::State& state, bool ordered) {
  const BumpySurface s(static_cast<int>(state.range(0)));
  const HostGrid grid(s.sheet.facets, s.sheet.x, s.margin);
  long found = 0;
  for (auto _ : state) {
    found += locate_each(grid, ordered ? s.sorted : s.q);
    benchmark::ClobberMemory();  // the queries are inlined: no hoisting out of the loop
  }
  benchmark::DoNotOptimize(found);
  query_counters(state, s.sheet.facets.size(), s.queries());
}
void BM_ContactQueries(benchmark::State& state) {
  host_queries(state, false);
}
void BM_ContactQueriesOrdered(benchmark::State& state) {
  host_queries(state, true);
}

// The random-order queries through the batch query from host vectors.
void BM_ContactQueriesBatch(benchmark::State& state) {
  const BumpySurface s(static_cast<int>(state.range(0)));
  const HostGrid grid(s.sheet.facets, s.sheet.x, s.margin);
  std::vector<k::Hit> hits;
  long found = 0;
  for (auto _ : state) {
    grid.locate_all(s.q.data(), s.queries(), hits);
    for (const auto& h : hits) found += h.facet >= 0;
  }
  benchmark::DoNotOptimize(found);
  query_counters(state, s.sheet.facets.size(), s.queries());
}

// The parallel build from Views on E (records, bounds, counts, scan, fill, sort): facets/s.
template <class E>
void grid_build(benchmark::State& state) {
  using M = typename E::memory_space;
  const BumpySurface s(static_cast<int>(state.range(0)));
  const auto facets = facets_view<M>(s);
  const auto x = points_view<M>(s.sheet.x, "bench::x");
  std::size_t cells = 0, entries = 0, reach = 0;
  for (auto _ : state) {
    k::FacetGrid<M> grid(E(), facets, x, s.margin);
    E().fence();
    cells = grid.num_cells();
    entries = grid.box_lists().entries;
    reach = grid.reach_lists().entries;
  }
  state.counters["cells"] = static_cast<double>(cells);
  state.counters["entries"] = static_cast<double>(entries);
  state.counters["reach_entries"] = static_cast<double>(reach);
  state.counters["facets"] = static_cast<double>(s.sheet.facets.size());
  state.counters["facets_per_s"] = benchmark::Counter(
      double(state.iterations()) * s.sheet.facets.size(), benchmark::Counter::kIsRate);
}

/// One locate() per query in a parallel_for over the queries in their order (a free function:
/// a device lambda is never in a member).
template <class E, class Grid, class Y, class Found>
void locate_kernel(const E& space, const Grid& grid, const Y& y, const Found& found) {
  Kokkos::parallel_for(
      "bench::locate", Kokkos::RangePolicy<E>(space, 0, y.extent(0)), KOKKOS_LAMBDA(const int q) {
        const double p[3] = {y(q, 0), y(q, 1), y(q, 2)};
        found(q) = grid.locate(p).facet;
      });
}

template <class E>
void kernel_queries(benchmark::State& state, bool ordered) {
  using M = typename E::memory_space;
  const BumpySurface s(static_cast<int>(state.range(0)));
  const k::FacetGrid<M> grid(E(), facets_view<M>(s), points_view<M>(s.sheet.x, "bench::x"),
                             s.margin);
  const auto y = points_view<M>(ordered ? s.sorted : s.q, "bench::y");
  Kokkos::View<int*, M> found("bench::found", y.extent(0));
  for (auto _ : state) {
    locate_kernel(E(), grid, y, found);
    E().fence();
  }
  query_counters(state, s.sheet.facets.size(), s.queries());
}

// The random-order queries through locate_all on Views of E (the sort by cell included).
template <class E>
void locate_all(benchmark::State& state) {
  using M = typename E::memory_space;
  const BumpySurface s(static_cast<int>(state.range(0)));
  const k::FacetGrid<M> grid(E(), facets_view<M>(s), points_view<M>(s.sheet.x, "bench::x"),
                             s.margin);
  const auto y = points_view<M>(s.q, "bench::y");
  typename k::FacetGrid<M>::HitsView hits("bench::hits", y.extent(0));
  for (auto _ : state) {
    grid.locate_all(E(), y, hits);
    E().fence();
  }
  query_counters(state, s.sheet.facets.size(), s.queries());
}

/// The surfaces of the <space> benchmarks: 100k facets and 1M.
void sizes(benchmark::internal::Benchmark* b) {
  b->Arg(224)->Arg(708)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();
}

struct Register {
  template <class E>
  static void on() {
    const std::string s = E::name();
    benchmark::RegisterBenchmark(("BM_ContactGridBuild/" + s).c_str(), grid_build<E>)->Apply(sizes);
    benchmark::RegisterBenchmark(("BM_ContactQueriesKernel/" + s + "/random").c_str(),
                                 [](benchmark::State& st) { kernel_queries<E>(st, false); })
        ->Apply(sizes);
    benchmark::RegisterBenchmark(("BM_ContactQueriesKernel/" + s + "/ordered").c_str(),
                                 [](benchmark::State& st) { kernel_queries<E>(st, true); })
        ->Apply(sizes);
    benchmark::RegisterBenchmark(("BM_ContactLocateAll/" + s).c_str(), locate_all<E>)->Apply(sizes);
  }
};

}  // namespace

BENCHMARK(BM_ContactSearch)->Arg(224)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ContactQueries)->Arg(32)->Arg(224)->Arg(708)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ContactQueriesOrdered)->Arg(224)->Arg(708)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ContactQueriesBatch)->Arg(224)->Unit(benchmark::kMillisecond);

int main(int argc, char** argv) {
  Kokkos::ScopeGuard kokkos(argc, argv);
  t::for_each_space<Register>(t::Spaces());
  benchmark::Initialize(&argc, argv);
  t::add_kokkos_context();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
