// The assembly driver (Kokkos parallel_reduce over elements, atomic adds into shared rows of
// the FECrsMatrix and the residual) against an independent serial reference: the same element
// kernel called element by element on the host, summed into a std::map. ctest runs it with
// OMP_NUM_THREADS=2: in an OpenMP build of Kokkos (perf/build_trilinos_openmp.sh) this checks
// that threads adding into the same rows give the serial result; in Debian's Serial build it
// checks the scatter (CRS offsets, overlap export) itself.
#include <gtest/gtest.h>

#include <Tpetra_Core.hpp>

#include <cmath>
#include <map>

#include "emcontact/fem/discretization.hpp"
#include "kernels/newton_tet4.hpp"
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
                           const std::vector<double>& V0, const std::vector<double>& u1, double dt) {
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
      for (int q = 0; q < 12; ++q)
        ref.A[{row, 3 * GO(m.tets[4 * e + q / 3]) + q % 3}] += Ae[p][q];
    }
  }
  return ref;
}

TEST(AssemblyThreads, MatchesSerialElementLoop) {
  emc::fem::Model m = emc::test::box_model(8);
  m.gravity = {0.0, 0.0, -9.81};
  auto comm = Tpetra::getDefaultComm();
  ASSERT_EQ(comm->getSize(), 1) << "the reference holds the whole model";
  emc::fem::Discretization disc(m, comm);
  const auto map = disc.owned_map();
  emc::Vector u0(map), V0(map), u1(map), r(map);
  u0.randomize();
  u0.scale(1e-2);
  V0.randomize();
  u1.randomize();
  u1.scale(2e-2);
  emc::FEMatrix A(disc.graph());
  const double dt = 1e-3;
  for (int pass = 0; pass < 2; ++pass)  // the second pass reuses the CRS offsets of the first
    disc.assemble(u0, V0, u1, dt, &A, r, nullptr);

  auto full = [&](const emc::Vector& v) {  // global dof order (one rank: gid -> value)
    std::vector<double> out(3 * m.num_nodes());
    auto d = v.getLocalViewHost(Tpetra::Access::ReadOnly);
    for (std::size_t l = 0; l < d.extent(0); ++l) out[map->getGlobalElement(l)] = d(l, 0);
    return out;
  };
  const Reference ref = serial_reference(m, full(u0), full(V0), full(u1), dt);

  double rmax = 0, amax = 0;
  for (const auto& [g, v] : ref.r) rmax = std::max(rmax, std::abs(v));
  for (const auto& [ij, v] : ref.A) amax = std::max(amax, std::abs(v));
  const auto rv = full(r);
  // round-off of summing at most ~24 element contributions in another order: 1e-13 relative
  for (const auto& [g, v] : ref.r) EXPECT_NEAR(rv[g], v, 1e-13 * rmax) << "residual dof " << g;
  std::size_t entries = 0;
  for (std::size_t l = 0; l < map->getNodeNumElements(); ++l) {
    const GO row = map->getGlobalElement(l);
    const std::size_t n = A.getNumEntriesInGlobalRow(row);
    typename emc::FEMatrix::nonconst_global_inds_host_view_type cols("cols", n);
    typename emc::FEMatrix::nonconst_values_host_view_type vals("vals", n);
    std::size_t got = 0;
    A.getGlobalRowCopy(row, cols, vals, got);
    for (std::size_t j = 0; j < got; ++j) {
      auto it = ref.A.find({row, cols(j)});
      const double want = it == ref.A.end() ? 0.0 : it->second;
      EXPECT_NEAR(vals(j), want, 1e-13 * amax) << "entry (" << row << ", " << cols(j) << ")";
      entries += it != ref.A.end();
    }
  }
  EXPECT_EQ(entries, ref.A.size()) << "every reference entry is in the matrix";
  if (const char* t = std::getenv("OMP_NUM_THREADS"))
    std::printf("compared with OMP_NUM_THREADS=%s, Kokkos execution space %s (%d threads)\n", t,
                emc::ExecSpace::name(), emc::ExecSpace().concurrency());
}

}  // namespace
