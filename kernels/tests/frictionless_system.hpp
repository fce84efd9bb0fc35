#pragma once
// The dense 4-node frictionless system shared by test_frictionless and test_coulomb (slave =
// node 0, masters = nodes 1..3, 12 dofs node-major 3A+i; synthetic residual g(u) = A0 (u - u_n)
// + b + a cubic term with its exact Jacobian): small dense linear algebra, the system, its
// projection state and the kernel's blocks as dense matrices.
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "kernels/frictionless.hpp"

namespace emc::test::frictionless_system {

namespace k = emc::kernels;

constexpr int kN = 12;
using Vec = std::array<double, kN>;
using Mat = std::array<Vec, kN>;

/// The 11 non-dummy reduced unknowns: dxi, deta and the 9 master dofs.
inline const std::vector<int> kRed = {0, 1, 3, 4, 5, 6, 7, 8, 9, 10, 11};

inline Mat zeros() {
  Mat A{};
  for (auto& r : A) r.fill(0.0);
  return A;
}

inline Mat identity() {
  Mat A = zeros();
  for (int i = 0; i < kN; ++i) A[i][i] = 1;
  return A;
}

inline Mat mul(const Mat& A, const Mat& B) {
  Mat C = zeros();
  for (int i = 0; i < kN; ++i)
    for (int l = 0; l < kN; ++l)
      for (int j = 0; j < kN; ++j) C[i][j] += A[i][l] * B[l][j];
  return C;
}

inline Mat transpose(const Mat& A) {
  Mat T = zeros();
  for (int i = 0; i < kN; ++i)
    for (int j = 0; j < kN; ++j) T[i][j] = A[j][i];
  return T;
}

inline Vec mulv(const Mat& A, const Vec& x) {
  Vec y{};
  for (int i = 0; i < kN; ++i)
    for (int j = 0; j < kN; ++j) y[i] += A[i][j] * x[j];
  return y;
}

inline double norm(const Vec& v) {
  double s = 0;
  for (double x : v) s += x * x;
  return std::sqrt(s);
}

/// ||A - B||_F / ||B||_F over rows x cols.
inline double rel_diff(const Mat& A, const Mat& B, const std::vector<int>& rows,
                       const std::vector<int>& cols) {
  double d = 0, s = 0;
  for (int i : rows)
    for (int j : cols) {
      d += (A[i][j] - B[i][j]) * (A[i][j] - B[i][j]);
      s += B[i][j] * B[i][j];
    }
  return std::sqrt(d / s);
}

/// Dense solve with partial pivoting.
inline Vec solve(Mat A, Vec b) {
  for (int c = 0; c < kN; ++c) {
    int p = c;
    for (int r = c + 1; r < kN; ++r)
      if (std::fabs(A[r][c]) > std::fabs(A[p][c])) p = r;
    std::swap(A[c], A[p]);
    std::swap(b[c], b[p]);
    for (int r = c + 1; r < kN; ++r) {
      const double f = A[r][c] / A[c][c];
      for (int j = c; j < kN; ++j) A[r][j] -= f * A[c][j];
      b[r] -= f * b[c];
    }
  }
  Vec x{};
  for (int r = kN - 1; r >= 0; --r) {
    double s = b[r];
    for (int j = r + 1; j < kN; ++j) s -= A[r][j] * x[j];
    x[r] = s / A[r][r];
  }
  return x;
}

inline void cross(const double a[3], const double b[3], double c[3]) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

inline double dot(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// The tiny system: reference positions, u at t_n, g(u) = A0 (u - u0) + b + cubic (u - u0)^3.
struct System {
  double X[4][3];
  Vec u0;
  Mat A0;
  Vec b;
  double cubic = 0;
  bool close = false;  ///< step 3 closes the gap at t_{n+1} (docs/THEORY.md §7.3)

  Vec g(const Vec& u) const {
    Vec du{};
    for (int i = 0; i < kN; ++i) du[i] = u[i] - u0[i];
    Vec r = mulv(A0, du);
    for (int i = 0; i < kN; ++i) r[i] += b[i] + cubic * du[i] * du[i] * du[i];
    return r;
  }
  Mat A(const Vec& u) const {  // exact Jacobian of g
    Mat J = A0;
    for (int i = 0; i < kN; ++i) J[i][i] += 3 * cubic * (u[i] - u0[i]) * (u[i] - u0[i]);
    return J;
  }
  /// Slave and master positions of displacement u.
  void positions(const Vec& u, double xs[3], double xm[3][3]) const {
    for (int c = 0; c < 3; ++c) {
      xs[c] = X[0][c] + u[c];
      for (int i = 0; i < 3; ++i) xm[i][c] = X[i + 1][c] + u[3 * (i + 1) + c];
    }
  }
};

/// Current iterate of t_{n+1} with the slave's facet coordinates.
struct State {
  Vec u;
  double xi[2];
};

/// Update steps 2-3 (frictionless_project) on the slave of state st; returns -min N.
inline double project(const System& sys, State& st) {
  double xs0[3], xm0[3][3], xs1[3], xm1[3][3];
  sys.positions(sys.u0, xs0, xm0);
  sys.positions(st.u, xs1, xm1);
  const double out = k::frictionless_project(xs0, xs1, xm0, xm1, st.xi, sys.close);
  for (int c = 0; c < 3; ++c) st.u[c] = xs1[c] - sys.X[0][c];
  return out;
}

inline k::FrictionlessBlocks blocks(const System& sys, const State& st) {
  double xs0[3], xm0[3][3], xs1[3], xm1[3][3];
  sys.positions(sys.u0, xs0, xm0);
  sys.positions(st.u, xs1, xm1);
  const Vec g = sys.g(st.u);
  k::FrictionlessBlocks b;
  EXPECT_TRUE(k::frictionless_blocks(xs0, xs1, xm0, xm1, st.xi, g.data(), b, sys.close));
  return b;
}

/// Global dense P, Pt, X from the blocks (slave rows 0..2, q columns 0, 1; dummy column 2 zero).
struct Dense {
  Mat P, Pt, X;
};

inline Dense dense(const k::FrictionlessBlocks& b) {
  Dense d{identity(), identity(), zeros()};
  for (int r = 0; r < 3; ++r) {
    d.P[r][r] = d.Pt[r][r] = 0;
    for (int j = 0; j < 9; ++j) {
      d.P[r][3 + j] = b.Pm[r][j];
      d.Pt[r][3 + j] = b.Ptm[r][j];
    }
    for (int q = 0; q < 2; ++q) {
      d.P[r][q] = b.Pq[r][q];
      d.Pt[r][q] = b.Ptq[r][q];
    }
  }
  for (int q = 0; q < 2; ++q)
    for (int j = 0; j < 9; ++j) {
      d.X[q][3 + j] = b.Xsq[q][j];
      d.X[3 + j][q] = b.Xmq[j][q];
    }
  for (int i = 0; i < 9; ++i)
    for (int j = 0; j < 9; ++j) d.X[3 + i][3 + j] = b.Xmm[i][j];
  return d;
}

}  // namespace emc::test::frictionless_system
