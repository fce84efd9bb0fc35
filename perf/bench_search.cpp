// Contact search benchmarks (docs/THEORY.md §2.5): the grid of the master facets (Views,
// built in parallel) and the queries of the slave nodes, one by one on the host and in the
// parallel batch query. Counters are per core: Kokkos is Serial in Debian's Trilinos.
//   BM_ContactSearch          grid built from host containers, then 100k random queries
//   BM_ContactGridBuild       the parallel build alone, from Views
//   BM_ContactQueries         100k random-order queries, one locate() each (/32: 2048 facets,
//                             all in cache: the cost of the computation alone)
//   BM_ContactQueriesOrdered  the same in spatial order (as slave nodes numbered along a surface)
//   BM_ContactQueriesBatch    random order through locate_all (host vectors, sort by cell included)
//   BM_ContactLocateAll       random order through locate_all on Views (sort by cell included)
#include <benchmark/benchmark.h>

#include <Kokkos_Core.hpp>
#include <Tpetra_Core.hpp>
#include <algorithm>
#include <cmath>
#include <random>

#include "emcontact/contact/search.hpp"

namespace {

/// A bumpy surface of 2 n^2 facets (n = 224: 100352 facets) and 100k points near it.
struct BumpySurface {
  std::vector<std::array<int, 3>> facets;
  std::vector<double> x, q;
  double margin;
  explicit BumpySurface(int n);
};

BumpySurface::BumpySurface(int n) : margin(0.5 / n) {
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double px = double(i) / n, py = double(j) / n;
      x.insert(x.end(), {px, py, 0.05 * std::sin(6 * px) * std::cos(4 * py)});
    }
  auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      facets.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      facets.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> d(0, 1), dz(-0.002, 0.002);
  for (int t = 0; t < 100000; ++t) {
    const double px = d(rng), py = d(rng);
    q.insert(q.end(), {px, py, 0.05 * std::sin(6 * px) * std::cos(4 * py) + dz(rng)});
  }
}

/// Locates every query point (3 coordinates each); returns how many found a facet.
long locate_each(const emc::contact::FacetGrid& grid, const std::vector<double>& q) {
  long found = 0;
  for (std::size_t t = 0; t < q.size() / 3; ++t) found += grid.locate(&q[3 * t]).facet >= 0;
  return found;
}

/// The counters of the contact benchmarks: surface size and queries per second.
void query_counters(benchmark::State& state, std::size_t facets, std::size_t queries) {
  state.counters["facets"] = static_cast<double>(facets);
  state.counters["queries_per_s"] =
      benchmark::Counter(double(state.iterations()) * queries, benchmark::Counter::kIsRate);
}

/// A copy of host data in a View on the execution space (n rows of 3).
template <class T>
Kokkos::View<T* [3], emc::ExecSpace> to_view(const T* data, std::size_t n, const char* label) {
  Kokkos::View<T* [3], emc::ExecSpace> v(std::string(label), n);
  Kokkos::deep_copy(
      v, Kokkos::View<const T* [3], Kokkos::HostSpace, Kokkos::MemoryUnmanaged>(data, n));
  return v;
}

}  // namespace

static void BM_ContactSearch(benchmark::State& state) {
  const BumpySurface s(static_cast<int>(state.range(0)));
  const auto& [facets, x, q, margin] = s;
  long found = 0;
  for (auto _ : state) {
    emc::contact::FacetGrid grid(facets, x, margin);  // rebuilt every step in the solver
    found += locate_each(grid, q);
  }
  benchmark::DoNotOptimize(found);
  query_counters(state, facets.size(), q.size() / 3);
}
BENCHMARK(BM_ContactSearch)->Arg(224)->Unit(benchmark::kMillisecond);

// The parallel build from Views (records, bounds, counts, scan, fill, sort): facets per second.
static void BM_ContactGridBuild(benchmark::State& state) {
  const BumpySurface s(static_cast<int>(state.range(0)));
  const auto facets = to_view(s.facets.front().data(), s.facets.size(), "facets");
  const auto x = to_view(s.x.data(), s.x.size() / 3, "x");
  std::size_t cells = 0, entries = 0, reach = 0;
  for (auto _ : state) {
    emc::contact::FacetGrid grid(facets, x, s.margin);
    cells = grid.num_cells();
    entries = grid.box_lists().entries;
    reach = grid.reach_lists().entries;
  }
  state.counters["cells"] = static_cast<double>(cells);
  state.counters["entries"] = static_cast<double>(entries);
  state.counters["reach_entries"] = static_cast<double>(reach);
  state.counters["facets"] = static_cast<double>(s.facets.size());
  state.counters["facets_per_s"] =
      benchmark::Counter(double(state.iterations()) * s.facets.size(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ContactGridBuild)->Arg(224)->Unit(benchmark::kMillisecond);

// The queries alone, against a grid built once.
static void BM_ContactQueries(benchmark::State& state) {
  const BumpySurface s(static_cast<int>(state.range(0)));
  const auto& [facets, x, q, margin] = s;
  emc::contact::FacetGrid grid(facets, x, margin);
  long found = 0;
  for (auto _ : state) {
    found += locate_each(grid, q);
    benchmark::ClobberMemory();  // the queries are inlined: no hoisting out of the loop
  }
  benchmark::DoNotOptimize(found);
  query_counters(state, facets.size(), q.size() / 3);
}
BENCHMARK(BM_ContactQueries)->Arg(32)->Arg(224)->Unit(benchmark::kMillisecond);

// The same queries in spatial order (rows of 1/64 in y, then x), as slave nodes numbered
// along the surface come: the facets a query needs are then in cache.
static void BM_ContactQueriesOrdered(benchmark::State& state) {
  const BumpySurface s(static_cast<int>(state.range(0)));
  const auto& [facets, x, q, margin] = s;
  std::vector<int> order(q.size() / 3);
  for (std::size_t t = 0; t < order.size(); ++t) order[t] = static_cast<int>(t);
  auto key = [&](int t) { return std::make_pair(int(q[3 * t + 1] * 64), q[3 * t]); };
  std::sort(order.begin(), order.end(), [&](int a, int b) { return key(a) < key(b); });
  std::vector<double> sorted;
  for (int t : order) sorted.insert(sorted.end(), {q[3 * t], q[3 * t + 1], q[3 * t + 2]});
  emc::contact::FacetGrid grid(facets, x, margin);
  long found = 0;
  for (auto _ : state) {
    found += locate_each(grid, sorted);
    benchmark::ClobberMemory();
  }
  benchmark::DoNotOptimize(found);
  query_counters(state, facets.size(), sorted.size() / 3);
}
BENCHMARK(BM_ContactQueriesOrdered)->Arg(224)->Unit(benchmark::kMillisecond);

// The random-order queries through the batch query from host vectors, which visits them cell
// by cell (its parallel sort included).
static void BM_ContactQueriesBatch(benchmark::State& state) {
  const BumpySurface s(static_cast<int>(state.range(0)));
  const auto& [facets, x, q, margin] = s;
  emc::contact::FacetGrid grid(facets, x, margin);
  std::vector<emc::contact::Hit> hits;
  long found = 0;
  for (auto _ : state) {
    grid.locate_all(q.data(), q.size() / 3, hits);
    for (const auto& h : hits) found += h.facet >= 0;
  }
  benchmark::DoNotOptimize(found);
  query_counters(state, facets.size(), q.size() / 3);
}
BENCHMARK(BM_ContactQueriesBatch)->Arg(224)->Unit(benchmark::kMillisecond);

// The same on Views: the parallel query as the solver's slave-node kernel will call it.
static void BM_ContactLocateAll(benchmark::State& state) {
  const BumpySurface s(static_cast<int>(state.range(0)));
  const auto facets = to_view(s.facets.front().data(), s.facets.size(), "facets");
  const auto x = to_view(s.x.data(), s.x.size() / 3, "x");
  const auto y = to_view(s.q.data(), s.q.size() / 3, "y");
  const emc::contact::FacetGrid grid(facets, x, s.margin);
  Kokkos::View<emc::contact::Hit*, emc::ExecSpace> hits("hits", y.extent(0));
  for (auto _ : state) {
    grid.locate_all(y, hits);
    Kokkos::fence();
  }
  query_counters(state, s.facets.size(), y.extent(0));
}
BENCHMARK(BM_ContactLocateAll)->Arg(224)->Unit(benchmark::kMillisecond);

int main(int argc, char** argv) {
  Tpetra::ScopeGuard scope(&argc, &argv);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
