#pragma once
// A static P1 block for closed-form and convergence checks of the element kernels: equilibrium
// f_int(u) = 0 on the free dofs of a Gmsh box, with some displacement components prescribed,
// solved by Newton with the kernels' exact tangent (the mid-point form of kernels/em_tet4.hpp at
// u_n = u_{n+1} = u is the static force, and its derivative in u_{n+1} half the static tangent)
// and a Jacobi-preconditioned conjugate gradient on a node-block sparse matrix.
#include <Teuchos_Array.hpp>
#include <Teuchos_ParameterList.hpp>
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "emcontact/mesh/body_mesh.hpp"
#include "emcontact/mesh/generate.hpp"
#include "kernels/em_tet4.hpp"
#include "kernels/tet4.hpp"

namespace emc::testing {

/// The mesh of the box [0, L]^2 x [0, H] with elements of about `size` (Gmsh, unstructured).
inline mesh::BodyMesh block_mesh(double L, double H, double size) {
  Teuchos::ParameterList p("Mesh");
  p.set("type", std::string("box"));
  p.set("size", size);
  p.set("lower corner", Teuchos::Array<double>(std::vector<double>{0.0, 0.0, 0.0}));
  p.set("upper corner", Teuchos::Array<double>(std::vector<double>{L, L, H}));
  return mesh::build_mesh(p, "", "static block");
}

template <class Material>
class StaticBlock {
 public:
  StaticBlock(mesh::BodyMesh m, const Material& material)
      : mesh_(std::move(m)), material_(material) {
    const int ne = mesh_.num_tets(), nn = mesh_.num_nodes();
    G_.resize(12 * ne);
    Ve_.resize(ne);
    for (int e = 0; e < ne; ++e) {
      double X[4][3], G[4][3];
      for (int a = 0; a < 4; ++a)
        for (int i = 0; i < 3; ++i) X[a][i] = mesh_.X[3 * mesh_.tets[4 * e + a] + i];
      Ve_[e] = kernels::tet_gradients(X, G);
      for (int a = 0; a < 4; ++a)
        for (int i = 0; i < 3; ++i) G_[12 * e + 3 * a + i] = G[a][i];
    }
    std::vector<std::vector<int>> adj(nn);
    for (int e = 0; e < ne; ++e)
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) adj[node(e, a)].push_back(node(e, b));
    row_.assign(nn + 1, 0);
    for (int n = 0; n < nn; ++n) {
      std::sort(adj[n].begin(), adj[n].end());
      adj[n].erase(std::unique(adj[n].begin(), adj[n].end()), adj[n].end());
      row_[n + 1] = row_[n] + static_cast<int>(adj[n].size());
      col_.insert(col_.end(), adj[n].begin(), adj[n].end());
    }
    val_.assign(9 * col_.size(), 0.0);
    u.assign(3 * nn, 0.0);
    fixed.assign(3 * nn, 0);
    force.assign(3 * nn, 0.0);
  }

  const mesh::BodyMesh& mesh() const { return mesh_; }
  int num_nodes() const { return mesh_.num_nodes(); }
  double X(int n, int i) const { return mesh_.X[3 * n + i]; }

  /// Newton on the free dofs from the current u (the fixed dofs keep their values) until the
  /// free residual is below `rtol` of the largest nodal force; throws if it does not get there.
  int solve(double rtol, int max_iterations = 30) {
    std::vector<double> r(u.size()), du(u.size());
    for (int it = 0; it < max_iterations; ++it) {
      const double scale = assemble();
      double rmax = 0;
      for (std::size_t d = 0; d < u.size(); ++d) {
        r[d] = fixed[d] ? 0.0 : -force[d];
        rmax = std::max(rmax, std::fabs(r[d]));
      }
      if (rmax <= rtol * scale) return it;
      conjugate_gradient(r, du);
      for (std::size_t d = 0; d < u.size(); ++d) u[d] += du[d];
    }
    throw std::runtime_error("static block: Newton did not converge");
  }

  /// Sum of the internal forces at the nodes of `nodes` in direction i (the reaction there).
  double resultant(const std::vector<int>& nodes, int i) const {
    double s = 0;
    for (int n : nodes) s += force[3 * n + i];
    return s;
  }

  /// The stored energy sum_e V_e W(E_e).
  double energy() const {
    double w = 0;
    for (int e = 0; e < mesh_.num_tets(); ++e) {
      double G[4][3], ue[4][3];
      element(e, G, ue);
      w += kernels::tet4_energy(G, Ve_[e], material_, ue);
    }
    return w;
  }

  std::vector<double> u;      ///< displacements, 3 per node
  std::vector<char> fixed;    ///< per dof: prescribed (to its value in u)
  std::vector<double> force;  ///< internal force at u, 3 per node (after solve)

 private:
  int node(int e, int a) const { return mesh_.tets[4 * e + a]; }
  void element(int e, double G[4][3], double ue[4][3]) const {
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) {
        G[a][i] = G_[12 * e + 3 * a + i];
        ue[a][i] = u[3 * node(e, a) + i];
      }
  }
  int block(int r, int c) const {
    const auto first = col_.begin() + row_[r], last = col_.begin() + row_[r + 1];
    return static_cast<int>(std::lower_bound(first, last, c) - col_.begin());
  }

  /// force = f_int(u), val_ = its exact derivative; returns the largest |force| component.
  double assemble() {
    std::fill(force.begin(), force.end(), 0.0);
    std::fill(val_.begin(), val_.end(), 0.0);
    for (int e = 0; e < mesh_.num_tets(); ++e) {
      double G[4][3], ue[4][3], f[12], K[12][12] = {};
      element(e, G, ue);
      kernels::em_tet4(G, Ve_[e], material_, kernels::Integrator::midpoint, ue, ue, f, K);
      for (int a = 0; a < 4; ++a) {
        for (int i = 0; i < 3; ++i) force[3 * node(e, a) + i] += f[3 * a + i];
        for (int b = 0; b < 4; ++b) {
          const int k = block(node(e, a), node(e, b));
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) val_[9 * k + 3 * i + j] += 2 * K[3 * a + i][3 * b + j];
        }
      }
    }
    double m = 0;
    for (double f : force) m = std::max(m, std::fabs(f));
    return m;
  }

  /// y = K x on the free dofs (x and y zero at the fixed ones).
  void multiply(const std::vector<double>& x, std::vector<double>& y) const {
    for (int n = 0; n + 1 < static_cast<int>(row_.size()); ++n)
      for (int i = 0; i < 3; ++i) {
        double s = 0;
        for (int k = row_[n]; k < row_[n + 1]; ++k)
          for (int j = 0; j < 3; ++j) s += val_[9 * k + 3 * i + j] * x[3 * col_[k] + j];
        y[3 * n + i] = fixed[3 * n + i] ? 0.0 : s;
      }
  }

  /// K x = b on the free dofs to 1e-10 of |b| (K symmetric positive definite there at a stable
  /// state of these tests; Newton converges on through the inexact solves).
  void conjugate_gradient(const std::vector<double>& b, std::vector<double>& x) const {
    const std::size_t n = b.size();
    std::vector<double> dinv(n, 0.0), r = b, z(n), p(n), q(n);
    for (int nd = 0; nd + 1 < static_cast<int>(row_.size()); ++nd)
      for (int i = 0; i < 3; ++i) {
        const double d = val_[9 * block(nd, nd) + 4 * i];
        dinv[3 * nd + i] = fixed[3 * nd + i] || d <= 0 ? 0.0 : 1.0 / d;
      }
    std::fill(x.begin(), x.end(), 0.0);
    auto dot = [&](const std::vector<double>& a, const std::vector<double>& c) {
      double s = 0;
      for (std::size_t k = 0; k < n; ++k) s += a[k] * c[k];
      return s;
    };
    for (std::size_t k = 0; k < n; ++k) z[k] = dinv[k] * r[k];
    p = z;
    double rz = dot(r, z);
    const double target = 1e-20 * dot(b, b);
    for (std::size_t it = 0; it < 20 * n && dot(r, r) > target; ++it) {
      multiply(p, q);
      const double alpha = rz / dot(p, q);
      for (std::size_t k = 0; k < n; ++k) {
        x[k] += alpha * p[k];
        r[k] -= alpha * q[k];
      }
      for (std::size_t k = 0; k < n; ++k) z[k] = dinv[k] * r[k];
      const double rz_next = dot(r, z);
      for (std::size_t k = 0; k < n; ++k) p[k] = z[k] + rz_next / rz * p[k];
      rz = rz_next;
    }
    if (!(dot(r, r) <= target))  // an indefinite K (an unstable iterate) or a NaN
      throw std::runtime_error("static block: CG stopped at " +
                               std::to_string(std::sqrt(dot(r, r) / dot(b, b))) + " of |b|");
  }

  mesh::BodyMesh mesh_;
  Material material_;
  std::vector<double> G_, Ve_;
  std::vector<int> row_, col_;
  std::vector<double> val_;
};

}  // namespace emc::testing
