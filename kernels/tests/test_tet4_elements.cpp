// The solver's element loops (kernels/tet4_elements.hpp) on every enabled execution space against
// plain host loops over the elements of a box with a material, density and massless nodes per
// tet: the Newton residual, its round-off scale and matrix (docs/THEORY.md §1.4, §1.6), the mass
// times a vector (§1.3), the monitored sums (§1.9), the von Mises stress and the CRS positions of
// the element entries. Nodal sums: bit for bit on one thread (plain adds in element order) and
// colour by colour on every host backend (the host loop in colour order), within the bound of a
// reordered sum |s' - s| <= 2 (c - 1) eps sum |t| with atomic adds on threads; the reductions
// (monitors) within a reordered sum's bound.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <vector>

#include "kernels/tet4_elements.hpp"
#include "support/backends.hpp"
#include "support/meshes.hpp"
#include "support/sums.hpp"

namespace {

namespace k = emc::kernels;
namespace t = emc::kernels::test;
constexpr double eps = std::numeric_limits<double>::epsilon();

using Sum = t::Sum;

/// A box of 6 x 4^3 tets in large motion, each with its own material and density; every 7th
/// tet has massless nodes (its mass terms are the solver's moved mass, left out by the loops).
struct Problem {
  t::Box box{4};
  std::vector<double> u0 = t::random_values(box.X.size(), 0.1, 1);
  std::vector<double> V0 = t::random_values(box.X.size(), 2.0, 2);
  std::vector<double> u1 = t::random_values(box.X.size(), 0.1, 3);
  std::vector<double> young = t::random_values(box.num_tets(), 0.5e6, 4);
  std::vector<double> rho = t::random_values(box.num_tets(), 400, 5);
  k::NewtonStep step;

  Problem() {
    step.gravity[0] = 0.5;
    step.gravity[2] = -9.81;
    step.dt = 1e-3;
    for (double& y : young) y += 1e6;
    for (double& r : rho) r += 1000;
  }
  int massless(int e) const { return e % 7 == 3 ? 1 << (e % 4) : 0; }
  k::Lame lame(int e) const { return k::lame(young[e], 0.3); }
  /// Tet e's reference coordinates, gradients, volume and nodal values of v.
  double element(int e, double X[4][3], double G[4][3]) const {
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) X[a][i] = box.X[3 * box.tets[4 * e + a] + i];
    return k::tet_gradients(X, G);
  }
  void values(const std::vector<double>& v, int e, double out[4][3]) const {
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) out[a][i] = v[3 * box.tets[4 * e + a] + i];
  }
  int dof(int e, int p) const { return 3 * box.tets[4 * e + p / 3] + p % 3; }
};

template <class E>
class TetElements : public ::testing::Test {
 public:
  using M = typename E::memory_space;
  Problem p;

  /// The record of the box's tets on M.
  k::TetElements<M> elements() const {
    const int ne = p.box.num_tets();
    k::TetElements<M> e(ne);
    const k::TetElementsMirror<M, k::Lame> h(e);
    for (int k = 0; k < ne; ++k) {
      double x[4][3], g[4][3] = {};
      h.Ve(k) = p.element(k, x, g);
      for (int a = 0; a < 4; ++a) {
        h.nodes(k, a) = p.box.tets[4 * k + a];
        for (int i = 0; i < 3; ++i) h.X(k, a, i) = x[a][i], h.G(k, a, i) = g[a][i];
      }
      h.material(k) = p.lame(k);
      h.rho(k) = p.rho[k];
      h.massless(k) = p.massless(k);
    }
    h.copy_to(e);
    return e;
  }
  /// A dof vector on M holding v (zeros if v is empty, of the box's size).
  k::DofsOut<M> dofs(const std::vector<double>& v = {}) const {
    k::DofsOut<M> out("test::dofs", p.box.X.size());
    if (!v.empty())
      Kokkos::deep_copy(out, Kokkos::View<const double*, Kokkos::LayoutLeft, Kokkos::HostSpace,
                                          Kokkos::MemoryUnmanaged>(v.data(), v.size()));
    return out;
  }
  k::Tetrahedra<M> tets() const {
    return t::rows<int, 4, M>(p.box.tets.data(), p.box.num_tets(), "test::tets");
  }
  /// Tet k's 12 dof columns (the pattern's column of dof 3 n + c is 3 n + c).
  Kokkos::View<int* [12], Kokkos::LayoutRight, M> columns() const {
    std::vector<int> c(12 * p.box.num_tets());
    for (int e = 0; e < p.box.num_tets(); ++e)
      for (int q = 0; q < 12; ++q) c[12 * e + q] = p.dof(e, q);
    return t::rows<int, 12, M>(c.data(), p.box.num_tets(), "test::columns");
  }
};
TYPED_TEST_SUITE(TetElements, t::Backends, t::BackendName);

/// The host loop's residual, scale and matrix entries, over the tets in element order or in
/// `order`; its smallest det F_{n+1}.
double host_newton(const Problem& p, std::vector<Sum>& r, std::vector<Sum>& s,
                   std::map<std::pair<int, int>, Sum>& A, const std::vector<int>* order) {
  r.assign(p.box.X.size(), Sum{});
  s.assign(p.box.X.size(), Sum{});
  A.clear();
  double worst = 1e300;
  for (int n = 0; n < p.box.num_tets(); ++n) {
    const int e = order ? (*order)[n] : n;
    double X[4][3], G[4][3] = {}, re[12], se[12], Ae[12][12] = {};
    const double Ve = p.element(e, X, G);
    k::ElementState st;
    p.values(p.u0, e, st.u0);
    p.values(p.V0, e, st.V0);
    p.values(p.u1, e, st.u1);
    worst = std::min(worst, k::tet4_detF(G, st.u1));
    k::newton_tet4(G, Ve, p.lame(e), p.rho[e], p.step.gravity, p.step.integrator, p.step.dt, st, re,
                   Ae, se, p.massless(e) != 0);
    for (int a = 0; a < 12; ++a) {
      r[p.dof(e, a)].add(re[a]);
      s[p.dof(e, a)].add(se[a]);
      for (int b = 0; b < 12; ++b) A[{p.dof(e, a), p.dof(e, b)}].add(Ae[a][b]);
    }
  }
  return worst;
}

/// got == want's sum bit for bit if exact, else within a reordered sum's bound.
void expect_sum(double got, const Sum& want, bool exact, bool bitwise, const char* what, int i) {
  if (exact)
    ASSERT_EQ(got, want.value) << what << " " << i;
  else
    ASSERT_NEAR(got, want.value, want.tolerance(bitwise)) << what << " " << i;
}

// The element entries' CRS positions are those of the pattern's blocks; an entry the pattern
// lacks is counted and marked -1.
TYPED_TEST(TetElements, OffsetsAreThePatternsBlocks) {
  using E = TypeParam;
  using M = typename E::memory_space;
  const auto& box = this->p.box;
  const auto el = this->elements();
  const k::TetPattern<M> pattern(E(), this->tets(), box.num_nodes());
  k::TetOffsets<M> off("test::offsets", box.num_tets());
  ASSERT_EQ(k::tet4_offsets(E(), el, this->columns(), pattern.matrix.row_map,
                            pattern.matrix.entries, off),
            0);
  const auto oh = t::on_host(off);
  const auto row_map = t::on_host(pattern.matrix.row_map);
  const auto block = t::on_host(pattern.block);
  for (int e = 0; e < box.num_tets(); ++e)
    for (int p = 0; p < 12; ++p)
      for (int q = 0; q < 12; ++q)
        ASSERT_EQ(oh(e, p, q), row_map(this->p.dof(e, p)) + block(e, p / 3, q / 3) + q % 3);
  // tet 0 with a column no row holds: its 12 entries in that column are missing
  auto cols = t::on_host(this->columns());
  cols(0, 5) = 3 * box.num_nodes() + 7;
  Kokkos::View<int* [12], Kokkos::LayoutRight, M> bad("test::bad", box.num_tets());
  Kokkos::deep_copy(bad, cols);
  EXPECT_EQ(k::tet4_offsets(E(), el, bad, pattern.matrix.row_map, pattern.matrix.entries, off), 12);
  EXPECT_EQ(t::on_host(off)(0, 0, 5), -1);
}

/// The residual, scale and matrix of the loops (colouring: or none) against the host loop.
template <class E, class Fixture>
void check_newton(const Fixture& fx, const k::TetColouring<typename E::memory_space>* col) {
  using M = typename E::memory_space;
  const auto& p = fx.p;
  const auto el = fx.elements();
  const k::TetPattern<M> pattern(E(), fx.tets(), p.box.num_nodes());
  k::NewtonRows<M> out{fx.dofs(), fx.dofs(), pattern.matrix.values,
                       k::TetOffsets<M>("test::offsets", p.box.num_tets())};
  k::tet4_offsets(E(), el, fx.columns(), pattern.matrix.row_map, pattern.matrix.entries,
                  out.offsets);
  const auto worst = k::newton_tet4_assemble(E(), el, p.step, fx.dofs(p.u0), fx.dofs(p.V0),
                                             fx.dofs(p.u1), out, col);
  std::vector<Sum> r, s;
  std::map<std::pair<int, int>, Sum> A;
  const std::vector<int> order = col ? col->order() : std::vector<int>{};
  const double detF = host_newton(p, r, s, A, col ? &order : nullptr);
  EXPECT_EQ(worst.val, detF);  // a min: exact in any order
  ASSERT_GE(worst.loc, 0);
  const bool bitwise = t::bitwise<E>(), exact = col ? bitwise : k::one_thread<E>();
  const auto rh = t::on_host(out.r), sh = t::on_host(out.s);
  for (std::size_t i = 0; i < r.size(); ++i) {
    expect_sum(rh(i), r[i], exact, bitwise, "residual dof", static_cast<int>(i));
    expect_sum(sh(i), s[i], exact, bitwise, "scale dof", static_cast<int>(i));
  }
  const auto row_map = t::on_host(pattern.matrix.row_map);
  const auto entries = t::on_host(pattern.matrix.entries);
  const auto values = t::on_host(pattern.matrix.values);
  for (int row = 0; row < pattern.matrix.num_rows(); ++row)
    for (int q = row_map(row); q < row_map(row + 1); ++q)
      expect_sum(values(q), A.at({row, entries(q)}), exact, bitwise, "matrix entry", q);
}

// One loop (atomic adds, plain on one thread) and the coloured loops.
TYPED_TEST(TetElements, NewtonSystemMatchesHostLoop) {
  check_newton<TypeParam>(*this, nullptr);
}
TYPED_TEST(TetElements, ColouredNewtonSystemMatchesHostLoopInColourOrder) {
  using E = TypeParam;
  for (const int chunk : {1, 8}) {
    const k::TetColouring<typename E::memory_space> col(E(), this->tets(), this->p.box.num_nodes(),
                                                        chunk);
    check_newton<E>(*this, &col);
  }
}

// M v: the host loop's sums (the tets with massless nodes add nothing), one loop and coloured.
TYPED_TEST(TetElements, MassTimesVectorMatchesHostLoop) {
  using E = TypeParam;
  using M = typename E::memory_space;
  const auto& p = this->p;
  const k::TetColouring<M> col(E(), this->tets(), p.box.num_nodes(), 8);
  for (const k::TetColouring<M>* c : {static_cast<const k::TetColouring<M>*>(nullptr), &col}) {
    const auto Mv = this->dofs();
    k::mass_tet4_apply(E(), this->elements(), this->dofs(p.V0), Mv, c);
    const std::vector<int> order = c ? c->order() : std::vector<int>{};
    std::vector<Sum> want(p.box.X.size());
    for (int n = 0; n < p.box.num_tets(); ++n) {
      const int e = c ? order[n] : n;
      if (p.massless(e)) continue;
      double X[4][3], G[4][3] = {}, v[4][3], pe[4][3];
      const double Ve = p.element(e, X, G);
      p.values(p.V0, e, v);
      k::mass_times(p.rho[e], Ve, v, pe);
      for (int a = 0; a < 12; ++a) want[p.dof(e, a)].add(pe[a / 3][a % 3]);
    }
    const bool bitwise = t::bitwise<E>(), exact = c ? bitwise : k::one_thread<E>();
    const auto h = t::on_host(Mv);
    for (std::size_t i = 0; i < want.size(); ++i)
      expect_sum(h(i), want[i], exact, bitwise, "dof", static_cast<int>(i));
  }
}

// The monitored sums: the host loop's within a reordered sum's bound (a reduction).
TYPED_TEST(TetElements, MonitorsMatchHostLoop) {
  using E = TypeParam;
  const auto& p = this->p;
  const k::Monitors m = k::monitors_tet4_sum(E(), this->elements(), p.step.gravity,
                                             this->dofs(p.u1), this->dofs(p.V0));
  k::Monitors want, size;
  for (int e = 0; e < p.box.num_tets(); ++e) {
    double X[4][3], G[4][3] = {}, u[4][3], V[4][3];
    const double Ve = p.element(e, X, G);
    p.values(p.u1, e, u);
    p.values(p.V0, e, V);
    k::Monitors one;
    k::monitors_tet4(X, G, Ve, p.lame(e), p.rho[e], p.step.gravity, u, V, one, p.massless(e) != 0);
    want += one;
    size.kinetic += std::fabs(one.kinetic), size.elastic += std::fabs(one.elastic);
    size.potential += std::fabs(one.potential), size.mass += std::fabs(one.mass);
    for (int i = 0; i < 3; ++i) {
      size.L[i] += std::fabs(one.L[i]), size.J[i] += std::fabs(one.J[i]);
      size.moment[i] += std::fabs(one.moment[i]);
    }
  }
  const double tol = 2 * p.box.num_tets() * eps * (t::bitwise<E>() ? 1 : 1e4);
  EXPECT_NEAR(m.kinetic, want.kinetic, tol * size.kinetic);
  EXPECT_NEAR(m.elastic, want.elastic, tol * size.elastic);
  EXPECT_NEAR(m.potential, want.potential, tol * size.potential);
  EXPECT_NEAR(m.mass, want.mass, tol * size.mass);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(m.L[i], want.L[i], tol * size.L[i]);
    EXPECT_NEAR(m.J[i], want.J[i], tol * size.J[i]);
    EXPECT_NEAR(m.moment[i], want.moment[i], tol * size.moment[i]);
  }
  EXPECT_GT(want.kinetic, 0);
  EXPECT_GT(want.elastic, 0);
}

// The von Mises stress per tet: the host's bits (a device: to 1e-13 relative).
TYPED_TEST(TetElements, VonMisesMatchesHost) {
  using E = TypeParam;
  using M = typename E::memory_space;
  const auto& p = this->p;
  Kokkos::View<double*, M> vm("test::von_mises", p.box.num_tets());
  k::von_mises_tet4(E(), this->elements(), this->dofs(p.u1), vm);
  const auto h = t::on_host(vm);
  for (int e = 0; e < p.box.num_tets(); ++e) {
    double X[4][3], G[4][3] = {}, u[4][3], H[3][3], F[3][3], Es[3][3], S[3][3];
    p.element(e, X, G);
    p.values(p.u1, e, u);
    k::displacement_gradient(G, u, H);
    k::identity_plus(H, F);
    k::green_strain(H, Es);
    k::svk_stress(p.lame(e), Es, S);
    const double want = k::von_mises(F, S, k::det3(F));
    if (t::bitwise<E>())
      ASSERT_EQ(h(e), want) << "tet " << e;
    else
      ASSERT_NEAR(h(e), want, 1e-13 * std::fabs(want)) << "tet " << e;
  }
}

// More colours than a word of bits: 300 tets around one node (a fan), chunks of one tet, need
// 300 colours; the coloured loops still give the host loop's sums in colour order.
TYPED_TEST(TetElements, ColouringOfAFanAroundOneNode) {
  using E = TypeParam;
  using M = typename E::memory_space;
  const int nt = 300;
  std::vector<int> tets;
  for (int k = 0; k < nt; ++k) tets.insert(tets.end(), {0, 1 + 3 * k, 2 + 3 * k, 3 + 3 * k});
  const auto tv = t::rows<int, 4, M>(tets.data(), nt, "test::fan");
  const k::TetColouring<M> col(E(), tv, 1 + 3 * nt, 1);
  EXPECT_EQ(col.colours(), nt);
  const auto order = col.order();
  for (int k = 0; k < nt; ++k) ASSERT_EQ(order[k], k);
}

}  // namespace
