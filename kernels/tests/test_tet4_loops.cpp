// The element-loop drivers of kernels/tet4_loops.hpp and kernels/crs.hpp on every enabled
// execution space against plain host loops over the elements (docs/THEORY.md §1.1, §1.4):
// the reference geometry and the CRS pattern bit for bit (deterministic); the nodal sums of the
// force and of the tangent bit for bit on one thread (Serial: plain adds in element order) and,
// on a threaded backend (atomic adds in any order), within the bound of a reordered sum:
// |s' - s| <= 2 (c - 1) eps sum |t| for c terms t; colour by colour (plain adds) bit for bit
// the host loop in colour order on every host backend.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "kernels/tet4_loops.hpp"
#include "support/backends.hpp"
#include "support/meshes.hpp"
#include "support/sums.hpp"

namespace {

namespace k = emc::kernels;
namespace t = emc::kernels::test;

using Sum = t::Sum;

/// A small box with a random large deformation (u0, u1 up to 0.1 of the box), on the host.
struct Problem {
  t::Box box{4};
  std::vector<double> u0 = t::random_values(box.X.size(), 0.1, 1);
  std::vector<double> u1 = t::random_values(box.X.size(), 0.1, 2);
  k::Lame material = k::lame(1e6, 0.3);
  k::Integrator integ = k::Integrator::energy_momentum;

  /// Element k's G, V_e and nodal values, as TetMesh and the loops read them.
  double element(int e, double G[4][3], double a0[4][3], double a1[4][3]) const {
    double x[4][3];
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) {
        const int n = box.tets[4 * e + a];
        x[a][i] = box.X[3 * n + i];
        a0[a][i] = u0[3 * n + i];
        a1[a][i] = u1[3 * n + i];
      }
    return k::tet_gradients(x, G);
  }
};

template <class E>
class TetLoops : public ::testing::Test {
 public:
  using M = typename E::memory_space;
  Problem p;
  k::Tetrahedra<M> tets() const {
    return t::rows<int, 4, M>(p.box.tets.data(), p.box.num_tets(), "test::tets");
  }
  k::Points<M> points(const std::vector<double>& v) const {
    return t::rows<double, 3, M>(v.data(), v.size() / 3, "test::points");
  }
};
TYPED_TEST_SUITE(TetLoops, t::Backends, t::BackendName);

// Per tet its shape gradients and volume, the bits of tet_gradients on the host; the smallest
// volume (a min reduction: exact) 1/(6 4^3).
TYPED_TEST(TetLoops, GeometryMatchesHostLoop) {
  using E = TypeParam;
  const k::TetMesh<typename E::memory_space> mesh(E(), this->tets(), this->points(this->p.box.X));
  EXPECT_EQ(mesh.min_volume, 1.0 / (6 * 64));
  const auto G = t::on_host(mesh.G);
  const auto Ve = t::on_host(mesh.Ve);
  for (int e = 0; e < this->p.box.num_tets(); ++e) {
    double g[4][3], a0[4][3], a1[4][3];
    const double v = this->p.element(e, g, a0, a1);
    if (t::bitwise<E>()) {
      ASSERT_EQ(Ve(e), v) << "tet " << e;
      for (int a = 0; a < 4; ++a)
        for (int i = 0; i < 3; ++i) ASSERT_EQ(G(e, a, i), g[a][i]) << "tet " << e;
    } else {
      ASSERT_NEAR(Ve(e), v, 1e-15);
    }
  }
}

// The pattern holds, in every dof row, exactly the dofs of the nodes that share a tet with the
// row's node, sorted; each tet's block positions point at its own columns.
TYPED_TEST(TetLoops, PatternIsTheTetsCouplings) {
  using E = TypeParam;
  const auto& box = this->p.box;
  const k::TetPattern<typename E::memory_space> pattern(E(), this->tets(), box.num_nodes());
  std::vector<std::set<int>> couple(box.num_nodes());
  for (int e = 0; e < box.num_tets(); ++e)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) couple[box.tets[4 * e + a]].insert(box.tets[4 * e + b]);
  const auto row_map = t::on_host(pattern.matrix.row_map);
  const auto entries = t::on_host(pattern.matrix.entries);
  const auto block = t::on_host(pattern.block);
  ASSERT_EQ(pattern.matrix.num_rows(), 3 * box.num_nodes());
  ASSERT_EQ(row_map(0), 0);
  for (int n = 0; n < box.num_nodes(); ++n)
    for (int c = 0; c < 3; ++c) {
      std::vector<int> want;
      for (int m : couple[n])
        for (int d = 0; d < 3; ++d) want.push_back(3 * m + d);
      const int r = 3 * n + c;
      ASSERT_EQ(row_map(r + 1) - row_map(r), static_cast<int>(want.size())) << "row " << r;
      for (std::size_t q = 0; q < want.size(); ++q) ASSERT_EQ(entries(row_map(r) + q), want[q]);
    }
  EXPECT_EQ(static_cast<std::size_t>(row_map(3 * box.num_nodes())), entries.extent(0));
  for (int e = 0; e < box.num_tets(); ++e)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        for (int c = 0; c < 3; ++c)
          for (int d = 0; d < 3; ++d)
            ASSERT_EQ(entries(row_map(3 * box.tets[4 * e + a] + c) + block(e, a, b) + d),
                      3 * box.tets[4 * e + b] + d);
}

/// The host loop's nodal forces (and, if K, the tangent's entries by (row, column)), over the
/// tets in element order or in `order`.
void host_assembly(const Problem& p, std::vector<Sum>& f, std::map<std::pair<int, int>, Sum>* K,
                   const std::vector<int>* order = nullptr) {
  f.assign(p.box.X.size(), Sum{});
  for (int t = 0; t < p.box.num_tets(); ++t) {
    const int e = order ? (*order)[t] : t;
    double G[4][3], a0[4][3], a1[4][3], fe[12], Ke[12][12];
    const double Ve = p.element(e, G, a0, a1);
    k::em_tet4(G, Ve, p.material, p.integ, a0, a1, fe, K ? Ke : nullptr);
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) {
        const int row = 3 * p.box.tets[4 * e + a] + i;
        f[row].add(fe[3 * a + i]);
        if (K)
          for (int b = 0; b < 4; ++b)
            for (int j = 0; j < 3; ++j)
              (*K)[{row, 3 * p.box.tets[4 * e + b] + j}].add(Ke[3 * a + i][3 * b + j]);
      }
  }
}

// The force-only loop: every node's force is the host loop's sum.
TYPED_TEST(TetLoops, ForcesMatchHostLoop) {
  using E = TypeParam;
  using M = typename E::memory_space;
  const k::TetMesh<M> mesh(E(), this->tets(), this->points(this->p.box.X));
  k::Vectors3<M> f("test::f", this->p.box.num_nodes());
  k::em_tet4_forces(E(), mesh, this->p.material, this->p.integ, this->points(this->p.u0),
                    this->points(this->p.u1), f);
  std::vector<Sum> want;
  host_assembly(this->p, want, nullptr);
  const auto fh = t::on_host(f);
  const bool exact = k::one_thread<E>();
  int most = 0;
  for (std::size_t r = 0; r < want.size(); ++r) {
    most = std::max(most, want[r].terms);
    if (exact)
      ASSERT_EQ(fh(r / 3, r % 3), want[r].value) << "dof " << r;
    else
      ASSERT_NEAR(fh(r / 3, r % 3), want[r].value, want[r].tolerance(t::bitwise<E>()))
          << "dof " << r;
  }
  EXPECT_EQ(most, 24);  // an inner node of the Kuhn box lies in 24 tets
}

// Force and exact tangent into the CRS matrix: the host loop's sums in every entry of the
// pattern (and the same forces as the force-only loop).
TYPED_TEST(TetLoops, TangentMatchesHostLoop) {
  using E = TypeParam;
  using M = typename E::memory_space;
  const auto& box = this->p.box;
  const k::TetMesh<M> mesh(E(), this->tets(), this->points(box.X));
  const k::TetPattern<M> pattern(E(), this->tets(), box.num_nodes());
  k::Vectors3<M> f("test::f", box.num_nodes());
  k::em_tet4_assemble(E(), mesh, this->p.material, this->p.integ, this->points(this->p.u0),
                      this->points(this->p.u1), f, pattern);
  std::vector<Sum> want;
  std::map<std::pair<int, int>, Sum> K;
  host_assembly(this->p, want, &K);
  const bool exact = k::one_thread<E>();
  const auto fh = t::on_host(f);
  for (std::size_t r = 0; r < want.size(); ++r) {
    if (exact)
      ASSERT_EQ(fh(r / 3, r % 3), want[r].value) << "dof " << r;
    else
      ASSERT_NEAR(fh(r / 3, r % 3), want[r].value, want[r].tolerance(t::bitwise<E>()));
  }
  const auto row_map = t::on_host(pattern.matrix.row_map);
  const auto entries = t::on_host(pattern.matrix.entries);
  const auto values = t::on_host(pattern.matrix.values);
  std::size_t seen = 0;
  int most = 0;
  for (int r = 0; r < pattern.matrix.num_rows(); ++r)
    for (int q = row_map(r); q < row_map(r + 1); ++q) {
      const auto it = K.find({r, entries(q)});
      ASSERT_NE(it, K.end()) << "entry (" << r << ", " << entries(q) << ") of no tet";
      const Sum& s = it->second;
      most = std::max(most, s.terms);
      if (exact)
        ASSERT_EQ(values(q), s.value) << "entry (" << r << ", " << entries(q) << ")";
      else
        ASSERT_NEAR(values(q), s.value, s.tolerance(t::bitwise<E>()));
      ++seen;
    }
  EXPECT_EQ(seen, K.size());
  EXPECT_GE(most, 20);  // diagonal blocks of inner nodes: sums over 24 tets
}

}  // namespace

namespace {

// Every tet in exactly one chunk of consecutive tets, every chunk in one colour, ascending within
// it; no two chunks of a colour share a node.
TYPED_TEST(TetLoops, ColouringIsValid) {
  using E = TypeParam;
  const auto& box = this->p.box;
  for (const int size : {1, 8}) {
    const k::TetColouring<typename E::memory_space> col(E(), this->tets(), box.num_nodes(), size);
    const auto chunks = t::on_host(col.chunks);
    ASSERT_EQ(col.start.front(), 0);
    ASSERT_EQ(col.start.back(), (box.num_tets() + size - 1) / size);
    EXPECT_LE(col.colours(), 64);
    EXPECT_GE(col.colours(), size == 1 ? 24 : 4);  // the 24 tets around an inner node
    std::vector<int> seen(box.num_tets(), 0);
    for (int c = 0; c < col.colours(); ++c) {
      std::set<int> nodes;
      for (int i = col.start[c]; i < col.start[c + 1]; ++i) {
        if (i > col.start[c]) {
          ASSERT_LT(chunks(i - 1), chunks(i));
        }
        std::set<int> mine;
        for (int e = chunks(i) * size; e < (chunks(i) + 1) * size && e < box.num_tets(); ++e) {
          ++seen[e];
          for (int a = 0; a < 4; ++a) mine.insert(box.tets[4 * e + a]);
        }
        for (int n : mine) ASSERT_TRUE(nodes.insert(n).second) << "colour " << c << " node " << n;
      }
    }
    for (int e = 0; e < box.num_tets(); ++e) ASSERT_EQ(seen[e], 1) << "tet " << e;
    EXPECT_EQ(col.order().size(), static_cast<std::size_t>(box.num_tets()));
  }
}

// Colour by colour with plain adds: forces and tangent the host loop's sums in the colouring's
// order, bit for bit on every host backend (a device: within the fused-product tolerance).
TYPED_TEST(TetLoops, ColouredLoopsMatchHostLoopInColourOrder) {
  using E = TypeParam;
  using M = typename E::memory_space;
  const auto& box = this->p.box;
  const k::TetMesh<M> mesh(E(), this->tets(), this->points(box.X));
  const k::TetPattern<M> pattern(E(), this->tets(), box.num_nodes());
  const k::TetColouring<M> col(E(), this->tets(), box.num_nodes(), 8);
  k::Vectors3<M> f("test::f", box.num_nodes()), g("test::g", box.num_nodes());
  k::em_tet4_forces(E(), mesh, this->p.material, this->p.integ, this->points(this->p.u0),
                    this->points(this->p.u1), g, &col);
  k::em_tet4_assemble(E(), mesh, this->p.material, this->p.integ, this->points(this->p.u0),
                      this->points(this->p.u1), f, pattern, &col);
  const std::vector<int> order = col.order();
  std::vector<Sum> want;
  std::map<std::pair<int, int>, Sum> K;
  host_assembly(this->p, want, &K, &order);
  const auto fh = t::on_host(f);
  const auto gh = t::on_host(g);
  const bool exact = t::bitwise<E>();
  for (std::size_t r = 0; r < want.size(); ++r) {
    if (exact) {
      ASSERT_EQ(fh(r / 3, r % 3), want[r].value) << "dof " << r;
      ASSERT_EQ(gh(r / 3, r % 3), want[r].value) << "dof " << r;
    } else {
      ASSERT_NEAR(fh(r / 3, r % 3), want[r].value, want[r].tolerance(false));
      ASSERT_NEAR(gh(r / 3, r % 3), want[r].value, want[r].tolerance(false));
    }
  }
  const auto row_map = t::on_host(pattern.matrix.row_map);
  const auto entries = t::on_host(pattern.matrix.entries);
  const auto values = t::on_host(pattern.matrix.values);
  for (int r = 0; r < pattern.matrix.num_rows(); ++r)
    for (int q = row_map(r); q < row_map(r + 1); ++q) {
      const Sum& s = K.at({r, entries(q)});
      if (exact)
        ASSERT_EQ(values(q), s.value) << "entry (" << r << ", " << entries(q) << ")";
      else
        ASSERT_NEAR(values(q), s.value, s.tolerance(false));
    }
}

}  // namespace
