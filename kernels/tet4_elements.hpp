#pragma once
// The solver's element loops over a P1 tet body (docs/THEORY.md §1.3-§1.9, §6.8) as drivers of
// the kernels of kernels/newton_tet4.hpp, kernels/mass_tet4.hpp and kernels/monitors.hpp: the
// Newton residual of eq. 20 with its matrix and round-off scale, the mass matrix times a vector,
// the monitored sums and the von Mises stress, over TetElements (the per-element record: its
// material and density per element, its nodes' rows in dof vectors of 3 per node). Each kernel
// fills a fixed-size element block on the stack and the driver adds it into the rows through
// kernels/tet4_loops.hpp's for_each_tet: one loop with atomic adds (plain on one thread), or a
// loop per colour of a TetColouring with plain adds (the same bits on every host backend and
// thread count). Dof vectors are Views of one column (a Tpetra vector's local column fits).
#include <Kokkos_Core.hpp>

#include "kernels/monitors.hpp"
#include "kernels/newton_tet4.hpp"
#include "kernels/tet4_loops.hpp"

namespace emc::kernels {

/// Values of 3 per node (dof 3 n + c of node n), read only and writable.
template <class MemorySpace>
using Dofs = Kokkos::View<const double*, Kokkos::LayoutLeft, MemorySpace>;
template <class MemorySpace>
using DofsOut = Kokkos::View<double*, Kokkos::LayoutLeft, MemorySpace>;

/// The elements of a body (or of a rank's part of it) of one material model (Material: Lame for
/// Saint-Venant-Kirchhoff, LogHyperelastic for Neo-Hookean and Mooney-Rivlin; the kernels are
/// compiled for each, so that SVK pays nothing for the others): per tet its nodes (node n's dofs
/// are 3 n + c of the dof vectors), reference coordinates X, shape gradients G and volume V_e,
/// material constants and density, and the bits of its massless nodes (bit a: node a,
/// docs/THEORY.md §6.8; such a tet's mass terms come from the solver's moved mass and are left out
/// here).
template <class MemorySpace, class Material = Lame>
struct TetElements {
  using Rows = Kokkos::View<double* [4][3], Kokkos::LayoutRight, MemorySpace>;
  using Values = Kokkos::View<double*, MemorySpace>;
  Kokkos::View<int* [4], Kokkos::LayoutRight, MemorySpace> nodes;
  Rows X, G;
  Values Ve, rho;
  Kokkos::View<Material*, MemorySpace> material;
  Kokkos::View<int*, MemorySpace> massless;

  TetElements() = default;
  /// Uninitialised arrays for ne tets.
  explicit TetElements(int ne)
      : nodes(Kokkos::ViewAllocateWithoutInitializing("emc::tet_nodes"), ne),
        X(Kokkos::ViewAllocateWithoutInitializing("emc::tet_X"), ne),
        G(Kokkos::ViewAllocateWithoutInitializing("emc::tet_G"), ne),
        Ve(Kokkos::ViewAllocateWithoutInitializing("emc::tet_Ve"), ne),
        rho(Kokkos::ViewAllocateWithoutInitializing("emc::tet_rho"), ne),
        material(Kokkos::ViewAllocateWithoutInitializing("emc::tet_material"), ne),
        massless(Kokkos::ViewAllocateWithoutInitializing("emc::tet_massless"), ne) {}
  int size() const { return static_cast<int>(Ve.extent(0)); }
  KOKKOS_INLINE_FUNCTION void gradients(int k, double g[4][3]) const { rows(G, k, g); }
  KOKKOS_INLINE_FUNCTION void reference(int k, double x[4][3]) const { rows(X, k, x); }
  /// Tet k's nodes' values of a dof vector.
  template <class V>
  KOKKOS_INLINE_FUNCTION void gather(const V& v, int k, double out[4][3]) const {
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) out[a][i] = v(3 * nodes(k, a) + i);
  }

 private:
  KOKKOS_INLINE_FUNCTION static void rows(const Rows& r, int k, double out[4][3]) {
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) out[a][i] = r(k, a, i);
  }
};

/// Host copies of a TetElements' arrays: filled on the host, then copied into the record's
/// memory space by copy_to (the set-up of a record from a mesh).
template <class MemorySpace, class Material>
struct TetElementsMirror {
  using E = TetElements<MemorySpace, Material>;
  typename decltype(E::nodes)::HostMirror nodes;
  typename E::Rows::HostMirror X, G;
  typename E::Values::HostMirror Ve, rho;
  typename decltype(E::material)::HostMirror material;
  typename decltype(E::massless)::HostMirror massless;

  explicit TetElementsMirror(const E& e)
      : nodes(Kokkos::create_mirror_view(e.nodes)),
        X(Kokkos::create_mirror_view(e.X)),
        G(Kokkos::create_mirror_view(e.G)),
        Ve(Kokkos::create_mirror_view(e.Ve)),
        rho(Kokkos::create_mirror_view(e.rho)),
        material(Kokkos::create_mirror_view(e.material)),
        massless(Kokkos::create_mirror_view(e.massless)) {}
  void copy_to(const E& e) const {
    Kokkos::deep_copy(e.nodes, nodes);
    Kokkos::deep_copy(e.X, X);
    Kokkos::deep_copy(e.G, G);
    Kokkos::deep_copy(e.Ve, Ve);
    Kokkos::deep_copy(e.rho, rho);
    Kokkos::deep_copy(e.material, material);
    Kokkos::deep_copy(e.massless, massless);
  }
};

/// The step's constants of the Newton residual: gravity, dt and the integrator.
struct NewtonStep {
  double gravity[3] = {0, 0, 0};
  double dt = 1;
  Integrator integrator = Integrator::energy_momentum;
};

/// The positions of every tet's 12 x 12 entries in the values of a CRS matrix: entry (p, q) of
/// tet k (dofs p = 3 a + i, q = 3 b + j) at offsets(k, p, q), in row 3 nodes(k, a) + i and column
/// columns(k, q).
template <class MemorySpace>
using TetOffsets = Kokkos::View<int* [12][12], Kokkos::LayoutRight, MemorySpace>;

/// The Newton system's outputs: residual r, its round-off scale s (empty: not wanted) and the
/// matrix's values with the tets' positions in them (values empty: no matrix).
template <class MemorySpace>
struct NewtonRows {
  DofsOut<MemorySpace> r, s;
  Kokkos::View<double*, MemorySpace> values;
  TetOffsets<MemorySpace> offsets;
};

/// The smallest det F_{n+1} and the tet that has it (loc -1 without tets or where every det F
/// is NaN).
using MinDetF = Kokkos::MinLoc<double, int>::value_type;

namespace elements_detail {

/// One tet's residual (eq. 20), Newton matrix and round-off scale added into the rows.
template <class MemorySpace, class Material>
struct Newton {
  TetElements<MemorySpace, Material> e;
  NewtonStep step;
  Dofs<MemorySpace> u0, V0, u1;
  NewtonRows<MemorySpace> out;

  template <bool Atomic>
  KOKKOS_INLINE_FUNCTION void element(const int k, MinDetF& mn) const {
    ElementState st;
    e.gather(u0, k, st.u0);
    e.gather(V0, k, st.V0);
    e.gather(u1, k, st.u1);
    double G[4][3];
    e.gradients(k, G);
    const double detF = tet4_detF(G, st.u1);
    if (detF < mn.val) {
      mn.val = detF;
      mn.loc = k;
    }
    const bool matrix = out.values.extent(0) > 0, scale = out.s.extent(0) > 0;
    double re[12], Ae[12][12], se[12];
    if (matrix)
      for (int p = 0; p < 12; ++p)
        for (int q = 0; q < 12; ++q) Ae[p][q] = 0;
    newton_tet4(G, e.Ve(k), e.material(k), e.rho(k), step.gravity, step.integrator, step.dt, st, re,
                matrix ? Ae : nullptr, scale ? se : nullptr, e.massless(k) != 0);
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) {
        const int p = 3 * a + i, row = 3 * e.nodes(k, a) + i;
        scatter_add<Atomic>(out.r(row), re[p]);
        if (scale) scatter_add<Atomic>(out.s(row), se[p]);
        if (matrix)
          for (int q = 0; q < 12; ++q)
            scatter_add<Atomic>(out.values(out.offsets(k, p, q)), Ae[p][q]);
      }
  }
};

/// One tet's M_e v_e added into the rows (not for tets with massless nodes).
template <class MemorySpace, class Material>
struct Mass {
  TetElements<MemorySpace, Material> e;
  Dofs<MemorySpace> v;
  DofsOut<MemorySpace> Mv;

  template <bool Atomic>
  KOKKOS_INLINE_FUNCTION void element(const int k) const {
    if (e.massless(k)) return;
    double vk[4][3], pk[4][3];
    e.gather(v, k, vk);
    mass_times(e.rho(k), e.Ve(k), vk, pk);
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) scatter_add<Atomic>(Mv(3 * e.nodes(k, a) + i), pk[a][i]);
  }
};

}  // namespace elements_detail

/// Adds every tet's residual of eq. 20 (u0 = u_n, V0 = V_n, u1 = the iterate u_{n+1}) into
/// out.r, its round-off scale (docs/THEORY.md §1.6) into out.s if not empty, and its Newton
/// matrix (2/dt^2) M_e + K_e into out.values through out.offsets if values is not empty
/// ("emcontact::fem::em_tet4"); returns the smallest det F_{n+1} and its tet.
template <class ExecutionSpace, class MemorySpace, class Material>
MinDetF newton_tet4_assemble(const ExecutionSpace& space,
                             const TetElements<MemorySpace, Material>& elements,
                             const NewtonStep& step, const NonDeduced<Dofs<MemorySpace>>& u0,
                             const NonDeduced<Dofs<MemorySpace>>& V0,
                             const NonDeduced<Dofs<MemorySpace>>& u1,
                             const NonDeduced<NewtonRows<MemorySpace>>& out,
                             const NonDeduced<TetColouring<MemorySpace>>* colouring = nullptr) {
  check_access<ExecutionSpace, MemorySpace>();
  const elements_detail::Newton<MemorySpace, Material> body{elements, step, u0, V0, u1, out};
  return tet4_detail::reduce_min_tet(space, "emcontact::fem::em_tet4", body, elements.size(),
                                     colouring);
}

/// Mv += M v, the consistent mass of every tet without massless nodes (docs/THEORY.md §1.3;
/// "emcontact::fem::mass_tet4").
template <class ExecutionSpace, class MemorySpace, class Material>
void mass_tet4_apply(const ExecutionSpace& space,
                     const TetElements<MemorySpace, Material>& elements,
                     const NonDeduced<Dofs<MemorySpace>>& v,
                     const NonDeduced<DofsOut<MemorySpace>>& Mv,
                     const NonDeduced<TetColouring<MemorySpace>>* colouring = nullptr) {
  check_access<ExecutionSpace, MemorySpace>();
  const elements_detail::Mass<MemorySpace, Material> body{elements, v, Mv};
  tet4_detail::for_each_tet(space, "emcontact::fem::mass_tet4", body, elements.size(), colouring);
}

/// The monitored quantities of (u, V) summed over the tets (docs/THEORY.md §1.9, eq. 23-24;
/// "emcontact::fem::monitors_tet4"): a reduction, whose order of sums Kokkos sets.
template <class ExecutionSpace, class MemorySpace, class Material>
Monitors monitors_tet4_sum(const ExecutionSpace& space,
                           const TetElements<MemorySpace, Material>& elements,
                           const double gravity[3], const NonDeduced<Dofs<MemorySpace>>& u,
                           const NonDeduced<Dofs<MemorySpace>>& V) {
  check_access<ExecutionSpace, MemorySpace>();
  const TetElements<MemorySpace, Material> e = elements;
  const double g0 = gravity[0], g1 = gravity[1], g2 = gravity[2];
  Monitors sum;
  Kokkos::parallel_reduce(
      "emcontact::fem::monitors_tet4", range(space, e.size()),
      KOKKOS_LAMBDA(const int k, Monitors& m) {
        double x[4][3], G[4][3], uk[4][3], Vk[4][3];
        e.reference(k, x);
        e.gradients(k, G);
        e.gather(u, k, uk);
        e.gather(V, k, Vk);
        const double g[3] = {g0, g1, g2};
        monitors_tet4(x, G, e.Ve(k), e.material(k), e.rho(k), g, uk, Vk, m, e.massless(k) != 0);
      },
      sum);
  return sum;
}

/// vm(k) = the von Mises stress of tet k at the displacements u (its Cauchy stress from its
/// material's S at F = I + H; "emcontact::fem::von_mises_tet4").
template <class ExecutionSpace, class MemorySpace, class Material, class Out>
void von_mises_tet4(const ExecutionSpace& space, const TetElements<MemorySpace, Material>& elements,
                    const NonDeduced<Dofs<MemorySpace>>& u, const Out& vm) {
  check_access<ExecutionSpace, MemorySpace>();
  const TetElements<MemorySpace, Material> e = elements;
  Kokkos::parallel_for(
      "emcontact::fem::von_mises_tet4", range(space, e.size()), KOKKOS_LAMBDA(const int k) {
        double G[4][3], uk[4][3], H[3][3], F[3][3], E[3][3], S[3][3];
        e.gradients(k, G);
        e.gather(u, k, uk);
        displacement_gradient(G, uk, H);
        identity_plus(H, F);
        green_strain(H, E);
        stress(e.material(k), E, S);
        vm(k) = von_mises(F, S, det3(F));
      });
}

/// offsets(k, p, q) = the position of tet k's entry (p, q) in a CRS matrix whose rows are sorted
/// (row 3 nodes(k, a) + i for p = 3 a + i, column columns(k, q)), found by bisection
/// ("emcontact::fem::tet4_offsets"); returns how many entries are missing from the pattern
/// (their offsets are -1).
template <class ExecutionSpace, class MemorySpace, class Material, class RowMap, class Entries>
int tet4_offsets(
    const ExecutionSpace& space, const TetElements<MemorySpace, Material>& elements,
    const NonDeduced<Kokkos::View<const int* [12], Kokkos::LayoutRight, MemorySpace>>& columns,
    const RowMap& row_map, const Entries& entries,
    const NonDeduced<TetOffsets<MemorySpace>>& offsets) {
  check_access<ExecutionSpace, MemorySpace>();
  const auto nodes = elements.nodes;
  int missing = 0;
  Kokkos::parallel_reduce(
      "emcontact::fem::tet4_offsets", range(space, elements.size()),
      KOKKOS_LAMBDA(const int k, int& lost) {
        for (int p = 0; p < 12; ++p) {
          const int row = 3 * nodes(k, p / 3) + p % 3;
          for (int q = 0; q < 12; ++q) {
            const int c = columns(k, q);
            int lo = static_cast<int>(row_map(row)), hi = static_cast<int>(row_map(row + 1));
            while (lo < hi) {  // the first entry >= c
              const int mid = lo + (hi - lo) / 2;
              if (static_cast<int>(entries(mid)) < c)
                lo = mid + 1;
              else
                hi = mid;
            }
            const bool found =
                lo < static_cast<int>(row_map(row + 1)) && static_cast<int>(entries(lo)) == c;
            offsets(k, p, q) = found ? lo : -1;
            lost += found ? 0 : 1;
          }
        }
      },
      missing);
  return missing;
}

}  // namespace emc::kernels
