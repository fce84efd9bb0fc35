#pragma once
// Element loops over a P1 tet mesh in a memory space (templated drivers of the kernels of
// kernels/em_tet4.hpp, labelled parallel kernels on the execution space given): the reference
// geometry, the energy-momentum internal force alone, and the force with its exact tangent
// added into a CRS matrix (docs/THEORY.md §1.1, §1.4). Nodal sums are atomic adds unless the
// execution space runs one thread (Serial), where they are plain adds in element order: bit for
// bit a host loop over the elements; on a threaded backend the order of a node's contributions,
// hence their sum's last bits, varies from run to run. With a TetColouring the loops run colour
// by colour with plain adds: the same bits on every host backend and number of threads.
#include <Kokkos_Core.hpp>
#include <algorithm>
#include <stdexcept>
#include <type_traits>
#include <vector>

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

/// The tets in chunks of consecutive ids (tets chunk j * chunk .. (j + 1) * chunk - 1, which a
/// thread runs in order: near in memory when the mesh is numbered along a curve), the chunks
/// in colours, no two chunks of a colour sharing a node: colour c is the chunks
/// chunks(start[c]) .. chunks(start[c + 1] - 1), ascending. A loop per colour adds into the nodes
/// with plain adds in a fixed order (colour by colour, then tet by tet) whatever the threads:
/// the same bits on every host backend and thread count, and no atomic operations (on a CPU a
/// compare-and-swap loop per double). For CPUs; on a GPU the atomic loops fit.
template <class MemorySpace>
struct TetColouring {
  Kokkos::View<int*, MemorySpace> chunks;
  std::vector<int> start;  ///< on the host: the loops' bounds
  int chunk = 1, num_tets = 0;

  TetColouring() = default;
  /// Greedy colouring on the host, chunk by chunk in ascending order: the lowest colour that no
  /// chunk sharing a node with it has yet.
  template <class ExecutionSpace>
  TetColouring(const ExecutionSpace& space, const Tetrahedra<MemorySpace>& tets, int num_nodes,
               int chunk = 64);
  int colours() const { return start.empty() ? 0 : static_cast<int>(start.size()) - 1; }
  /// The tets in the loops' order (colour by colour, chunk by chunk, tet by tet), on the host.
  std::vector<int> order() const;
};

namespace tet4_detail {

/// The chunks touching every node (CSR: node n's at at[first[n] .. first[n + 1]), each once,
/// ascending).
template <class Tets>
void node_chunks(const Tets& t, int num_nodes, int chunk, std::vector<int>& first,
                 std::vector<int>& at) {
  const int ne = static_cast<int>(t.extent(0));
  std::vector<int> last(num_nodes, -1);  // the last chunk counted at a node
  first.assign(num_nodes + 1, 0);
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<int> next(first.begin(), first.end() - 1);
    for (int k = 0; k < ne; ++k)
      for (int a = 0; a < 4; ++a) {
        const int n = t(k, a);
        if (last[n] == k / chunk) continue;
        last[n] = k / chunk;
        if (pass == 0)
          ++first[n + 1];
        else
          at[next[n]++] = k / chunk;
      }
    if (pass == 0) {
      for (int n = 0; n < num_nodes; ++n) first[n + 1] += first[n];
      at.resize(first[num_nodes]);
      std::fill(last.begin(), last.end(), -1);
    }
  }
}

/// The colour of every chunk, greedy in ascending chunk order; colours: how many.
template <class Tets>
std::vector<int> greedy_colours(const Tets& t, int num_nodes, int chunk, int& colours) {
  std::vector<int> first, at;
  node_chunks(t, num_nodes, chunk, first, at);
  const int ne = static_cast<int>(t.extent(0)), nc = (ne + chunk - 1) / chunk;
  std::vector<int> colour(nc, -1), taken;  // taken[c] == j: a neighbour of chunk j has colour c
  colours = 0;
  for (int j = 0; j < nc; ++j) {
    for (int k = j * chunk; k < ne && k < (j + 1) * chunk; ++k)
      for (int a = 0; a < 4; ++a) {
        const int n = t(k, a);
        for (int i = first[n]; i < first[n + 1]; ++i)
          if (colour[at[i]] >= 0) taken[colour[at[i]]] = j;
      }
    int c = 0;
    while (c < colours && taken[c] == j) ++c;
    if (c == colours) {
      taken.push_back(-1);
      ++colours;
    }
    colour[j] = c;
  }
  return colour;
}

}  // namespace tet4_detail

template <class MemorySpace>
template <class ExecutionSpace>
TetColouring<MemorySpace>::TetColouring(const ExecutionSpace& space,
                                        const Tetrahedra<MemorySpace>& t, int num_nodes, int size)
    : chunk(size), num_tets(static_cast<int>(t.extent(0))) {
  check_access<ExecutionSpace, MemorySpace>();
  if (chunk < 1) throw std::invalid_argument("TetColouring: chunk < 1");
  space.fence();
  const auto th = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), t);
  int colours = 0;
  const std::vector<int> colour = tet4_detail::greedy_colours(th, num_nodes, chunk, colours);
  const int nc = static_cast<int>(colour.size());
  start.assign(colours + 1, 0);
  for (int j = 0; j < nc; ++j) ++start[colour[j] + 1];
  for (int c = 0; c < colours; ++c) start[c + 1] += start[c];
  chunks = Kokkos::View<int*, MemorySpace>(
      Kokkos::ViewAllocateWithoutInitializing("emc::tet_colours"), nc);
  auto h = Kokkos::create_mirror_view(chunks);
  std::vector<int> next(start.begin(), start.end() - (colours ? 1 : 0));
  for (int j = 0; j < nc; ++j) h(next[colour[j]]++) = j;
  Kokkos::deep_copy(chunks, h);
}

template <class MemorySpace>
std::vector<int> TetColouring<MemorySpace>::order() const {
  const auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), chunks);
  std::vector<int> out;
  for (std::size_t i = 0; i < h.extent(0); ++i)
    for (int k = h(i) * chunk; k < (h(i) + 1) * chunk && k < num_tets; ++k) out.push_back(k);
  return out;
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

namespace tet4_detail {

/// One tet's energy-momentum force added into its nodes' f.
template <class MemorySpace>
struct Force {
  TetMesh<MemorySpace> m;
  Lame lm;
  Integrator integ;
  Points<MemorySpace> u0, u1;
  Vectors3<MemorySpace> f;
  template <bool Atomic>
  KOKKOS_INLINE_FUNCTION void element(const int k) const {
    double G[4][3], e0[4][3], e1[4][3], fe[12];
    tet4_detail::element(m, k, u0, u1, G, e0, e1);
    em_tet4(G, m.Ve(k), lm, integ, e0, e1, fe, nullptr);
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) scatter_add<Atomic>(f(m.tets(k, a), i), fe[3 * a + i]);
  }
};

/// The same force and its exact tangent added into the CRS values through the block positions.
template <class MemorySpace>
struct Tangent {
  Force<MemorySpace> force;
  Kokkos::View<int*, MemorySpace> row_map;
  Kokkos::View<double*, MemorySpace> values;
  Kokkos::View<int* [4][4], Kokkos::LayoutRight, MemorySpace> block;
  template <bool Atomic>
  KOKKOS_INLINE_FUNCTION void element(const int k) const {
    const TetMesh<MemorySpace>& m = force.m;
    double G[4][3], e0[4][3], e1[4][3], fe[12], Ke[12][12];
    tet4_detail::element(m, k, force.u0, force.u1, G, e0, e1);
    em_tet4(G, m.Ve(k), force.lm, force.integ, e0, e1, fe, Ke);
    for (int a = 0; a < 4; ++a) {
      const int n = m.tets(k, a);
      for (int i = 0; i < 3; ++i) {
        scatter_add<Atomic>(force.f(n, i), fe[3 * a + i]);
        const int row = row_map(3 * n + i);
        for (int b = 0; b < 4; ++b)
          for (int j = 0; j < 3; ++j)
            scatter_add<Atomic>(values(row + block(k, a, b) + j), Ke[3 * a + i][3 * b + j]);
      }
    }
  }
};

/// A colour's chunks: dynamic schedule (chunks cost alike but threads may not run alike).
template <class ExecutionSpace>
using ChunkPolicy = Kokkos::RangePolicy<ExecutionSpace, Kokkos::Schedule<Kokkos::Dynamic>>;

/// body.element<Atomic>(k) for every tet: without a colouring one loop over the tets (atomic
/// adds, plain on one thread), with one a loop per colour (plain adds).
template <class ExecutionSpace, class MemorySpace, class Body>
void for_each_tet(const ExecutionSpace& space, const char* label, const Body& body, int ne,
                  const TetColouring<MemorySpace>* colouring) {
  if (!colouring) {
    constexpr bool atomic = !one_thread<ExecutionSpace>();
    Kokkos::parallel_for(
        label, range(space, ne), KOKKOS_LAMBDA(const int k) { body.template element<atomic>(k); });
    return;
  }
  const auto chunks = colouring->chunks;
  const int size = colouring->chunk;
  for (int c = 0; c < colouring->colours(); ++c)
    Kokkos::parallel_for(
        label, ChunkPolicy<ExecutionSpace>(space, colouring->start[c], colouring->start[c + 1]),
        KOKKOS_LAMBDA(const int i) {
          const int first = chunks(i) * size, last = first + size < ne ? first + size : ne;
          for (int k = first; k < last; ++k) body.template element<false>(k);
        });
}

/// The same with body.element<Atomic>(k, mn), which lowers the MinLoc value mn: the smallest
/// over every tet and its tet (loc -1 if ne = 0). Min is exact: the same whatever the order.
template <class ExecutionSpace, class MemorySpace, class Body>
Kokkos::MinLoc<double, int>::value_type reduce_min_tet(const ExecutionSpace& space,
                                                       const char* label, const Body& body, int ne,
                                                       const TetColouring<MemorySpace>* colouring) {
  using MinLoc = Kokkos::MinLoc<double, int>;
  MinLoc::value_type worst;
  worst.val = Kokkos::reduction_identity<double>::min();
  worst.loc = -1;
  if (!colouring) {
    constexpr bool atomic = !one_thread<ExecutionSpace>();
    if (ne > 0)
      Kokkos::parallel_reduce(
          label, range(space, ne),
          KOKKOS_LAMBDA(const int k, MinLoc::value_type& mn) {
            body.template element<atomic>(k, mn);
          },
          MinLoc(worst));
    return worst;
  }
  const auto chunks = colouring->chunks;
  const int size = colouring->chunk;
  for (int c = 0; c < colouring->colours(); ++c) {
    MinLoc::value_type w;
    Kokkos::parallel_reduce(
        label, ChunkPolicy<ExecutionSpace>(space, colouring->start[c], colouring->start[c + 1]),
        KOKKOS_LAMBDA(const int i, MinLoc::value_type& mn) {
          const int first = chunks(i) * size, last = first + size < ne ? first + size : ne;
          for (int k = first; k < last; ++k) body.template element<false>(k, mn);
        },
        MinLoc(w));
    if (w.val < worst.val) worst = w;
  }
  return worst;
}

}  // namespace tet4_detail

/// f(n, i) += the energy-momentum internal force of every tet at node n (em_tet4 without its
/// tangent, docs/THEORY.md §1.4 eq. 18; u0 = u_n, u1 = u_{n+1}; one material) in a labelled
/// loop over the tets ("emcontact::fem::em_tet4_force"), or a loop per colour of colouring.
template <class ExecutionSpace, class MemorySpace>
void em_tet4_forces(const ExecutionSpace& space, const TetMesh<MemorySpace>& mesh,
                    const Lame& material, Integrator integ,
                    const NonDeduced<Points<MemorySpace>>& u0,
                    const NonDeduced<Points<MemorySpace>>& u1,
                    const NonDeduced<Vectors3<MemorySpace>>& f,
                    const NonDeduced<TetColouring<MemorySpace>>* colouring = nullptr) {
  check_access<ExecutionSpace, MemorySpace>();
  const tet4_detail::Force<MemorySpace> body{mesh, material, integ, u0, u1, f};
  tet4_detail::for_each_tet(space, "emcontact::fem::em_tet4_force", body, mesh.size(), colouring);
}

/// The same force into f and its exact tangent d f / d u_{n+1} (em_tet4's 12 x 12 element
/// matrices) added into the values of K, the pattern of these tets (TetPattern), through its
/// block positions: no row search ("emcontact::fem::em_tet4").
template <class ExecutionSpace, class MemorySpace>
void em_tet4_assemble(const ExecutionSpace& space, const TetMesh<MemorySpace>& mesh,
                      const Lame& material, Integrator integ,
                      const NonDeduced<Points<MemorySpace>>& u0,
                      const NonDeduced<Points<MemorySpace>>& u1,
                      const NonDeduced<Vectors3<MemorySpace>>& f,
                      const NonDeduced<TetPattern<MemorySpace>>& K,
                      const NonDeduced<TetColouring<MemorySpace>>* colouring = nullptr) {
  check_access<ExecutionSpace, MemorySpace>();
  const tet4_detail::Tangent<MemorySpace> body{
      {mesh, material, integ, u0, u1, f}, K.matrix.row_map, K.matrix.values, K.block};
  tet4_detail::for_each_tet(space, "emcontact::fem::em_tet4", body, mesh.size(), colouring);
}

}  // namespace emc::kernels
