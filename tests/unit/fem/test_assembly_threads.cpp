// The assembly driver (Kokkos loops over elements, one per element colour with plain adds or
// one with atomic adds into shared rows of the FECrsMatrix and the residual) against an
// independent serial reference: the same element kernel called element by element on the
// host, summed into a std::map. ctest runs it with OMP_NUM_THREADS=2: in an OpenMP build of
// Kokkos (perf/build_trilinos_openmp.sh) this checks that threads adding into the same rows give
// the serial result; in Debian's Serial build it checks the scatter (CRS offsets, colouring,
// overlap export) itself. The colouring is checked by brute force, and the coloured assembly
// bit for bit: between two calls, and (ctest's test_assembly_threads_1 writes the digest of a
// run with 1 thread, test_assembly_threads compares) between thread counts.
#include <gtest/gtest.h>

#include <Tpetra_Core.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <random>

#include "emcontact/fem/discretization.hpp"
#include "kernels/newton_tet4.hpp"
#include "kernels/tet4_loops.hpp"
#include "support/box_model.hpp"

namespace {

using emc::GO;
namespace k = emc::kernels;

struct Reference {
  std::map<GO, double> r;
  std::map<std::pair<GO, GO>, double> A;
};

/// Every element of `m` through the kernel, serially, with the nodal values of full vectors.
Reference serial_reference(const emc::fem::Model& m, const std::vector<double>& u0,
                           const std::vector<double>& V0, const std::vector<double>& u1,
                           double dt) {
  Reference ref;
  const auto& b = m.bodies[0];
  const k::Lame lame = k::lame(b.young, b.poisson);
  const double grav[3] = {m.gravity[0], m.gravity[1], m.gravity[2]};
  for (int e = 0; e < m.num_tets(); ++e) {
    double X[4][3], G[4][3];
    k::ElementState s;
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) {
        const int d = 3 * m.tets[4 * e + a] + i;
        X[a][i] = m.X[d];
        s.u0[a][i] = u0[d];
        s.V0[a][i] = V0[d];
        s.u1[a][i] = u1[d];
      }
    const double Ve = k::tet_gradients(X, G);
    double re[12], Ae[12][12] = {};
    k::newton_tet4(G, Ve, lame, b.density, grav, m.integrator, dt, s, re, Ae, nullptr);
    for (int p = 0; p < 12; ++p) {
      const GO row = 3 * GO(m.tets[4 * e + p / 3]) + p % 3;
      ref.r[row] += re[p];
      for (int q = 0; q < 12; ++q) ref.A[{row, 3 * GO(m.tets[4 * e + q / 3]) + q % 3}] += Ae[p][q];
    }
  }
  return ref;
}

/// The random state and the assembly of the box of n^3 cubes on one rank.
struct Assembled {
  emc::fem::Model m;
  std::unique_ptr<emc::fem::Discretization> disc;
  std::unique_ptr<emc::Vector> u0, V0, u1, r, s;
  std::unique_ptr<emc::FEMatrix> A;
  emc::fem::AssemblyInfo info;

  Assembled(int n, emc::fem::Scatter how) : m(emc::test::box_model(n)) {
    m.gravity = {0.0, 0.0, -9.81};
    m.scatter = how;
    disc = std::make_unique<emc::fem::Discretization>(m, Tpetra::getDefaultComm());
    const auto map = disc->owned_map();
    u0 = std::make_unique<emc::Vector>(map);
    V0 = std::make_unique<emc::Vector>(map);
    u1 = std::make_unique<emc::Vector>(map);
    r = std::make_unique<emc::Vector>(map);
    s = std::make_unique<emc::Vector>(map);
    fill(*u0, 1e-2, 1);  // on the host from the global dof: the same for any thread count
    fill(*V0, 1.0, 2);
    fill(*u1, 2e-2, 3);
    A = std::make_unique<emc::FEMatrix>(disc->graph());
  }
  /// Uniform in [-scale, scale), a function of the global dof and the seed only.
  static void fill(emc::Vector& v, double scale, unsigned seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> d(-scale, scale);
    std::vector<double> all(v.getMap()->getMaxAllGlobalIndex() + 1);
    for (double& x : all) x = d(rng);
    auto h = v.getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (std::size_t l = 0; l < h.extent(0); ++l) h(l, 0) = all[v.getMap()->getGlobalElement(l)];
  }
  void assemble() { info = disc->assemble(*u0, *V0, *u1, 1e-3, A.get(), *r, s.get()); }
};

/// Calls fn(row, col, value) for every stored entry of my rows of A, in the owned map's order.
template <class F>
void for_each_entry(const emc::FEMatrix& A, F&& fn) {
  const auto map = A.getRowMap();
  for (std::size_t l = 0; l < map->getNodeNumElements(); ++l) {
    const GO row = map->getGlobalElement(l);
    const std::size_t n = A.getNumEntriesInGlobalRow(row);
    typename emc::FEMatrix::nonconst_global_inds_host_view_type cols("cols", n);
    typename emc::FEMatrix::nonconst_values_host_view_type vals("vals", n);
    std::size_t got = 0;
    A.getGlobalRowCopy(row, cols, vals, got);
    for (std::size_t j = 0; j < got; ++j) fn(row, cols(j), vals(j));
  }
}

/// Every value of a vector and of the matrix (rows in the owned map's order), as bit patterns.
std::vector<std::uint64_t> bits(const emc::Vector& r, const emc::Vector& s,
                                const emc::FEMatrix& A) {
  std::vector<std::uint64_t> out;
  auto push = [&](double x) {
    std::uint64_t b;
    std::memcpy(&b, &x, sizeof b);
    out.push_back(b);
  };
  for (const emc::Vector* v : {&r, &s}) {
    auto d = v->getLocalViewHost(Tpetra::Access::ReadOnly);
    for (std::size_t l = 0; l < d.extent(0); ++l) push(d(l, 0));
  }
  for_each_entry(A, [&](GO, GO, double v) { push(v); });
  return out;
}

/// FNV-1a of the bit patterns.
std::uint64_t digest(const std::vector<std::uint64_t>& b) {
  std::uint64_t h = 1469598103934665603ull;
  for (std::uint64_t x : b)
    for (int k = 0; k < 8; ++k) h = (h ^ ((x >> (8 * k)) & 0xff)) * 1099511628211ull;
  return h;
}

class AssemblyThreads : public ::testing::TestWithParam<emc::fem::Scatter> {};

TEST_P(AssemblyThreads, MatchesSerialElementLoop) {
  ASSERT_EQ(Tpetra::getDefaultComm()->getSize(), 1) << "the reference holds the whole model";
  Assembled a(8, GetParam());
  for (int pass = 0; pass < 2; ++pass)  // the second pass reuses the CRS offsets of the first
    a.assemble();
  const auto& m = a.m;
  const auto map = a.disc->owned_map();
  const emc::Vector& r = *a.r;
  const emc::FEMatrix& A = *a.A;
  const double dt = 1e-3;

  auto full = [&](const emc::Vector& v) {  // global dof order (one rank: gid -> value)
    std::vector<double> out(3 * m.num_nodes());
    auto d = v.getLocalViewHost(Tpetra::Access::ReadOnly);
    for (std::size_t l = 0; l < d.extent(0); ++l) out[map->getGlobalElement(l)] = d(l, 0);
    return out;
  };
  const Reference ref = serial_reference(m, full(*a.u0), full(*a.V0), full(*a.u1), dt);

  double rmax = 0, amax = 0;
  for (const auto& [g, v] : ref.r) rmax = std::max(rmax, std::abs(v));
  for (const auto& [ij, v] : ref.A) amax = std::max(amax, std::abs(v));
  const auto rv = full(r);
  // round-off of summing at most ~24 element contributions in another order: 1e-13 relative
  for (const auto& [g, v] : ref.r) EXPECT_NEAR(rv[g], v, 1e-13 * rmax) << "residual dof " << g;
  std::size_t entries = 0;
  for_each_entry(A, [&](GO row, GO col, double v) {
    auto it = ref.A.find({row, col});
    const double want = it == ref.A.end() ? 0.0 : it->second;
    EXPECT_NEAR(v, want, 1e-13 * amax) << "entry (" << row << ", " << col << ")";
    entries += it != ref.A.end();
  });
  EXPECT_EQ(entries, ref.A.size()) << "every reference entry is in the matrix";
  if (const char* t = std::getenv("OMP_NUM_THREADS"))
    std::printf("compared with OMP_NUM_THREADS=%s, Kokkos execution space %s (%d threads)\n", t,
                emc::ExecSpace::name(), emc::ExecSpace().concurrency());
}

INSTANTIATE_TEST_SUITE_P(Scatter, AssemblyThreads,
                         ::testing::Values(emc::fem::Scatter::coloured, emc::fem::Scatter::atomic),
                         [](const auto& info) {
                           return info.param == emc::fem::Scatter::coloured ? "coloured" : "atomic";
                         });

// Exhaustive: every chunk in exactly one colour, ascending within it, every element in one
// chunk, and no two elements of different chunks of one colour with a node in common; with
// chunks of 1 element (the plain element colouring), of 7 and of the assembly's length.
class Colouring : public ::testing::TestWithParam<int> {};

TEST_P(Colouring, ChunksOfAColourShareNoNode) {
  const emc::fem::Model m = emc::test::box_model(8);
  emc::fem::Discretization disc(m, Tpetra::getDefaultComm());
  EXPECT_EQ(disc.colouring().chunk, emc::fem::assembly_chunk);
  const auto node_lid = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), disc.tets().nodes);
  const int nn = static_cast<int>(disc.overlap_map()->getNodeNumElements() / 3);
  const k::TetColouring<emc::MemSpace> col(emc::ExecSpace(), disc.tets().nodes, nn, GetParam());
  const auto chunks = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), col.chunks);
  const int ne = static_cast<int>(node_lid.extent(0));
  const int len = GetParam(), nc = (ne + len - 1) / len;
  ASSERT_EQ(static_cast<int>(chunks.extent(0)), nc);
  ASSERT_GT(col.colours(), 1);
  EXPECT_EQ(col.start[0], 0);
  EXPECT_EQ(col.start[col.colours()], nc);
  std::vector<int> seen(ne, 0);
  for (int c = 0; c < col.colours(); ++c) {
    EXPECT_LT(col.start[c], col.start[c + 1]) << "colour " << c << " is empty";
    std::map<int, int> chunk_of_node;  // node -> the chunk of this colour touching it
    for (int i = col.start[c]; i < col.start[c + 1]; ++i) {
      ASSERT_TRUE(chunks(i) >= 0 && chunks(i) < nc);
      if (i > col.start[c]) EXPECT_LT(chunks(i - 1), chunks(i)) << "colour " << c;
      for (int k = chunks(i) * len; k < std::min(ne, (chunks(i) + 1) * len); ++k) {
        ++seen[k];
        for (int a = 0; a < 4; ++a) {
          const auto [it, fresh] = chunk_of_node.emplace(node_lid(k, a), chunks(i));
          EXPECT_TRUE(fresh || it->second == chunks(i))
              << "chunks " << it->second << " and " << chunks(i) << " of colour " << c
              << " share node " << node_lid(k, a);
        }
      }
    }
  }
  for (int k = 0; k < ne; ++k) EXPECT_EQ(seen[k], 1) << "element " << k;
  std::printf("%d elements, %d chunks of %d in %d colours\n", ne, nc, len, col.colours());
}

INSTANTIATE_TEST_SUITE_P(Chunk, Colouring, ::testing::Values(1, 7, emc::fem::assembly_chunk));

// The coloured assembly twice: the same bits. With EMC_ASSEMBLY_DIGEST_OUT its digest is written
// (ctest: with 1 thread); with EMC_ASSEMBLY_DIGEST_REF it must equal the one in that file (ctest:
// with 2 threads, so that an OpenMP build checks that the thread count changes no bit).
TEST(AssemblyThreads, ColouredIsBitwiseReproducible) {
  Assembled a(8, emc::fem::Scatter::coloured);
  a.assemble();
  const auto first = bits(*a.r, *a.s, *a.A);
  const double det1 = a.info.min_detF;
  a.assemble();
  const auto second = bits(*a.r, *a.s, *a.A);
  ASSERT_EQ(first.size(), second.size());
  std::size_t differ = 0;
  for (std::size_t k = 0; k < first.size(); ++k) differ += first[k] != second[k];
  EXPECT_EQ(differ, 0u) << "values changed between two assemblies of the same state";
  EXPECT_EQ(a.info.min_detF, det1);
  const std::uint64_t h = digest(second);
  const int threads = emc::ExecSpace().concurrency();
  std::printf("digest %016llx of %zu values, %s with %d threads\n",
              static_cast<unsigned long long>(h), second.size(), emc::ExecSpace::name(), threads);
  if (const char* out = std::getenv("EMC_ASSEMBLY_DIGEST_OUT")) {
    std::ofstream(out) << std::hex << h << " " << std::dec << threads << "\n";
  }
  if (const char* ref = std::getenv("EMC_ASSEMBLY_DIGEST_REF")) {
    std::ifstream in(ref);
    std::uint64_t want = 0;
    int want_threads = 0;
    ASSERT_TRUE(in >> std::hex >> want >> std::dec >> want_threads) << "cannot read " << ref;
    EXPECT_EQ(h, want) << "the coloured assembly with " << threads
                       << " threads differs from the one with " << want_threads;
  }
}

}  // namespace
