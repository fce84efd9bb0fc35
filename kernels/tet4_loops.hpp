#pragma once
// Element loops over a P1 tet mesh in a memory space (templated drivers of the kernels of
// kernels/em_tet4.hpp, labelled parallel kernels on the execution space given): the reference
// geometry, the energy-momentum internal force alone, and the force with its exact tangent
// added into a CRS matrix (docs/THEORY.md §1.1, §1.4). Nodal sums are atomic adds unless the
// execution space runs one thread (Serial), where they are plain adds in element order: bit for
// bit a host loop over the elements; on a threaded backend the order of a node's contributions,
// hence their sum's last bits, varies from run to run.
#include <Kokkos_Core.hpp>
#include <type_traits>

#include "kernels/crs.hpp"
#include "kernels/em_tet4.hpp"
#include "kernels/tet4.hpp"
#include "kernels/types.hpp"

namespace emc::kernels {

/// A tet mesh's reference geometry: per tet its 4 node ids, shape gradients G_A (G(k, A, j))
/// and reference volume V_e (tet_gradients), over num_nodes nodes; min_volume: the smallest V_e
/// (<= 0: an inverted or degenerate tet, whose G is zero; 1e300 without tets).
template <class MemorySpace>
struct TetMesh {
  Tetrahedra<MemorySpace> tets;
  Kokkos::View<double* [4][3], Kokkos::LayoutRight, MemorySpace> G;
  Kokkos::View<double*, MemorySpace> Ve;
  int num_nodes = 0;
  double min_volume = 1e300;

  TetMesh() = default;
  /// The geometry of the tets over the nodes X, computed on space
  /// ("emcontact::fem::tet_gradients").
  template <class ExecutionSpace>
  TetMesh(const ExecutionSpace& space, const Tetrahedra<MemorySpace>& tets,
          const Points<MemorySpace>& X);
  int size() const { return static_cast<int>(tets.extent(0)); }
};

/// Whether ExecutionSpace runs its kernels on one thread (no concurrent adds).
template <class ExecutionSpace>
constexpr bool one_thread() {
#ifdef KOKKOS_ENABLE_SERIAL
  return std::is_same_v<ExecutionSpace, Kokkos::Serial>;
#else
  return false;
#endif
}

/// x += v: atomic when adds into x may run at once.
template <bool Atomic>
KOKKOS_INLINE_FUNCTION void scatter_add(double& x, double v) {
  if constexpr (Atomic)
    Kokkos::atomic_add(&x, v);
  else
    x += v;
}

namespace tet4_detail {

/// G and V_e of every tet into G and Ve (a free function: a device lambda is never in a
/// constructor); returns the smallest V_e.
template <class ExecutionSpace, class MemorySpace>
double geometry(const ExecutionSpace& space, const Tetrahedra<MemorySpace>& tets,
                const Points<MemorySpace>& X,
                const Kokkos::View<double* [4][3], Kokkos::LayoutRight, MemorySpace>& G,
                const Kokkos::View<double*, MemorySpace>& Ve) {
  double vmin = 1e300;
  Kokkos::parallel_reduce(
      "emcontact::fem::tet_gradients", range(space, tets.extent(0)),
      KOKKOS_LAMBDA(const int k, double& lo) {
        double x[4][3], g[4][3] = {};  // g is set for v > 0 only
        for (int a = 0; a < 4; ++a)
          for (int i = 0; i < 3; ++i) x[a][i] = X(tets(k, a), i);
        const double v = tet_gradients(x, g);
        Ve(k) = v;
        if (v > 0)
          for (int a = 0; a < 4; ++a)
            for (int i = 0; i < 3; ++i) G(k, a, i) = g[a][i];
        lo = v < lo ? v : lo;
      },
      Kokkos::Min<double>(vmin));
  return tets.extent(0) ? vmin : 1e300;
}

}  // namespace tet4_detail

template <class MemorySpace>
template <class ExecutionSpace>
TetMesh<MemorySpace>::TetMesh(const ExecutionSpace& space, const Tetrahedra<MemorySpace>& t,
                              const Points<MemorySpace>& X)
    : tets(t),
      G("emc::tet_gradients", t.extent(0)),
      Ve(Kokkos::ViewAllocateWithoutInitializing("emc::tet_volumes"), t.extent(0)),
      num_nodes(static_cast<int>(X.extent(0))) {
  check_access<ExecutionSpace, MemorySpace>();
  min_volume = tet4_detail::geometry(space, tets, X, G, Ve);
}

namespace tet4_detail {

/// Tet k's G, and its nodes' values of u (rows of 3).
template <class MemorySpace, class U>
KOKKOS_INLINE_FUNCTION void element(const TetMesh<MemorySpace>& mesh, int k, const U& u0,
                                    const U& u1, double G[4][3], double e0[4][3], double e1[4][3]) {
  for (int a = 0; a < 4; ++a) {
    const int n = mesh.tets(k, a);
    for (int i = 0; i < 3; ++i) {
      G[a][i] = mesh.G(k, a, i);
      e0[a][i] = u0(n, i);
      e1[a][i] = u1(n, i);
    }
  }
}

}  // namespace tet4_detail

/// f(n, i) += the energy-momentum internal force of every tet at node n (em_tet4 without its
/// tangent, docs/THEORY.md §1.4 eq. 18; u0 = u_n, u1 = u_{n+1}; one material) in a labelled
/// loop over the tets ("emcontact::fem::em_tet4_force").
template <class ExecutionSpace, class MemorySpace>
void em_tet4_forces(const ExecutionSpace& space, const TetMesh<MemorySpace>& mesh,
                    const Lame& material, Integrator integ,
                    const NonDeduced<Points<MemorySpace>>& u0,
                    const NonDeduced<Points<MemorySpace>>& u1,
                    const NonDeduced<Vectors3<MemorySpace>>& f) {
  check_access<ExecutionSpace, MemorySpace>();
  constexpr bool atomic = !one_thread<ExecutionSpace>();
  const TetMesh<MemorySpace> m = mesh;
  const Lame lm = material;
  Kokkos::parallel_for(
      "emcontact::fem::em_tet4_force", range(space, m.size()), KOKKOS_LAMBDA(const int k) {
        double G[4][3], e0[4][3], e1[4][3], fe[12];
        tet4_detail::element(m, k, u0, u1, G, e0, e1);
        em_tet4(G, m.Ve(k), lm, integ, e0, e1, fe, nullptr);
        for (int a = 0; a < 4; ++a)
          for (int i = 0; i < 3; ++i) scatter_add<atomic>(f(m.tets(k, a), i), fe[3 * a + i]);
      });
}

/// The same force into f and its exact tangent d f / d u_{n+1} (em_tet4's 12 x 12 element
/// matrices) added into the values of K, a pattern of these tets (tet_pattern), through its
/// block positions: no row search ("emcontact::fem::em_tet4").
template <class ExecutionSpace, class MemorySpace>
void em_tet4_assemble(const ExecutionSpace& space, const TetMesh<MemorySpace>& mesh,
                      const Lame& material, Integrator integ,
                      const NonDeduced<Points<MemorySpace>>& u0,
                      const NonDeduced<Points<MemorySpace>>& u1,
                      const NonDeduced<Vectors3<MemorySpace>>& f,
                      const NonDeduced<TetPattern<MemorySpace>>& K) {
  check_access<ExecutionSpace, MemorySpace>();
  constexpr bool atomic = !one_thread<ExecutionSpace>();
  const TetMesh<MemorySpace> m = mesh;
  const Lame lm = material;
  const auto row_map = K.matrix.row_map;
  const auto values = K.matrix.values;
  const auto block = K.block;
  Kokkos::parallel_for(
      "emcontact::fem::em_tet4", range(space, m.size()), KOKKOS_LAMBDA(const int k) {
        double G[4][3], e0[4][3], e1[4][3], fe[12], Ke[12][12];
        tet4_detail::element(m, k, u0, u1, G, e0, e1);
        em_tet4(G, m.Ve(k), lm, integ, e0, e1, fe, Ke);
        for (int a = 0; a < 4; ++a) {
          const int n = m.tets(k, a);
          for (int i = 0; i < 3; ++i) {
            scatter_add<atomic>(f(n, i), fe[3 * a + i]);
            const int row = row_map(3 * n + i);
            for (int b = 0; b < 4; ++b)
              for (int j = 0; j < 3; ++j)
                scatter_add<atomic>(values(row + block(k, a, b) + j), Ke[3 * a + i][3 * b + j]);
          }
        }
      });
}

}  // namespace emc::kernels
