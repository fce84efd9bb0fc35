// docs/THEORY.md §8: the per-active-slave loops of contact (Kokkos, one entry per index).
#include "emcontact/contact/active_kernels.hpp"

namespace emc::contact {

namespace {

using Policy = Kokkos::RangePolicy<ExecSpace>;

int count(const Refs& refs) {
  return static_cast<int>(refs.extent(0));
}

/// An entry's slave and facet at t_n (y0, xm0) and at t_{n+1} (y1, xm1).
struct Geometry {
  double xm0[3][3], xm1[3][3], y0[3], y1[3];
  KOKKOS_INLINE_FUNCTION Geometry(const Positions& x0, const Positions& x1, const ActiveRef& a) {
    facet_at(x0, a, xm0);
    facet_at(x1, a, xm1);
    slave_at(x0, a, y0);
    slave_at(x1, a, y1);
  }
};

}  // namespace

void midpoint(Positions x0, Positions x1, Positions xh) {
  Kokkos::parallel_for(
      "emcontact::contact::midpoint", Policy(0, static_cast<int>(xh.extent(0))),
      KOKKOS_LAMBDA(const int l) {
        for (int i = 0; i < 3; ++i) xh(l, i) = 0.5 * (x0(l, i) + x1(l, i));
      });
}

// §4: the normal force on the facet at n+1/2.
void normal_forces(Refs refs, Positions x0, Positions x1, OwnedValues g, Values fN) {
  Kokkos::parallel_for(
      "emcontact::contact::normal_forces", Policy(0, count(refs)), KOKKOS_LAMBDA(const int k) {
        const ActiveRef a = refs(k);
        double xm0[3][3], xm1[3][3], xh[3][3];
        facet_at(x0, a, xm0);
        facet_at(x1, a, xm1);
        kernels::midpoint(xm0, xm1, xh);
        const kernels::Facet f = kernels::facet(xh);
        double s = 0;
        for (int i = 0; i < 3; ++i) s += g(a.dof[i], 0) * f.n[i];
        fN(k) = s;
      });
}

void gap_range(Refs refs, Positions x1, double& lo, double& hi) {
  Kokkos::MinMaxScalar<double> r;
  Kokkos::parallel_reduce(
      "emcontact::contact::gap_range", Policy(0, count(refs)),
      KOKKOS_LAMBDA(const int k, Kokkos::MinMaxScalar<double>& mm) {
        const ActiveRef a = refs(k);
        double xm[3][3], y[3], xi[2], gap;
        facet_at(x1, a, xm);
        slave_at(x1, a, y);
        if (!kernels::facet_cpp(y, xm, xi, gap)) return;  // degenerate facet
        if (gap < mm.min_val) mm.min_val = gap;
        if (gap > mm.max_val) mm.max_val = gap;
      },
      Kokkos::MinMax<double>(r));
  lo = count(refs) ? r.min_val : 1e300;
  hi = count(refs) ? r.max_val : -1e300;
  if (lo > hi) lo = 1e300, hi = -1e300;
}

void position_roundoff(Refs refs, Positions x1, Values r) {
  Kokkos::parallel_for(
      "emcontact::contact::position_roundoff", Policy(0, count(refs)), KOKKOS_LAMBDA(const int k) {
        const ActiveRef a = refs(k);
        double y[3];
        slave_at(x1, a, y);
        r(k) =
            kernels::epsilon() * (kernels::fabs(y[0]) + kernels::fabs(y[1]) + kernels::fabs(y[2]));
      });
}

void behind_facets(Refs refs, Positions x, Kokkos::View<int*, ExecSpace> behind) {
  Kokkos::parallel_for(
      "emcontact::contact::behind_facets", Policy(0, count(refs)), KOKKOS_LAMBDA(const int k) {
        const ActiveRef a = refs(k);
        double xm[3][3], y[3], xi[2], gap;
        facet_at(x, a, xm);
        slave_at(x, a, y);
        behind(k) = kernels::facet_cpp(y, xm, xi, gap) && gap < -gap_roundoff(a.edge, y);
      });
}

void facet_point_distances(Refs refs, Positions x, Kokkos::View<double* [2], ExecSpace> d) {
  Kokkos::parallel_for(
      "emcontact::contact::facet_point_distances", Policy(0, count(refs)),
      KOKKOS_LAMBDA(const int k) {
        const ActiveRef a = refs(k);
        double xm[3][3], y[3];
        facet_at(x, a, xm);
        slave_at(x, a, y);
        kernels::facet_point_distance(y, xm, a.xi, d(k, 0), d(k, 1));
      });
}

namespace {

template <class X1>
double stick_corrections_at(Refs refs, Positions x0, const X1 x1, Values3 d) {
  double moved = 0;
  Kokkos::parallel_reduce(
      "emcontact::contact::stick_corrections", Policy(0, count(refs)),
      KOKKOS_LAMBDA(const int k, double& mx) {
        const ActiveRef a = refs(k);
        double xm0[3][3], xm1[3][3], N[3];
        facet_at(x0, a, xm0);
        facet_at(x1, a, xm1);
        kernels::facet_shape(a.xi, N);
        for (int c = 0; c < 3; ++c) {
          // the differences first: where nothing moved, the target is x_{s,n} exactly
          double target = x0(a.s, c) + N[0] * (xm1[0][c] - xm0[0][c]) +
                          N[1] * (xm1[1][c] - xm0[1][c]) + N[2] * (xm1[2][c] - xm0[2][c]);
          if (a.closes) target = N[0] * xm1[0][c] + N[1] * xm1[1][c] + N[2] * xm1[2][c];
          d(k, c) = target - x1(a.s, c);
          const double m = kernels::fabs(d(k, c)) / a.edge;
          if (m > mx) mx = m;
        }
      },
      Kokkos::Max<double>(moved));
  return moved;
}

}  // namespace

double stick_corrections(Refs refs, Positions x0, Positions x1, Values3 d) {
  return stick_corrections_at(refs, x0, x1, d);
}

double stick_corrections(Refs refs, Positions x0, const NodePositions& x1, Values3 d) {
  return stick_corrections_at(refs, x0, x1, d);
}

void add_to_slaves(Refs refs, Values3 d, OwnedValuesRW u) {
  Kokkos::parallel_for(
      "emcontact::contact::add_to_slaves", Policy(0, count(refs)), KOKKOS_LAMBDA(const int k) {
        for (int c = 0; c < 3; ++c) u(refs(k).dof[c], 0) += d(k, c);
      });
}

void frictionless_projections(Refs refs, Positions x0, Positions x1, Values3 xs1,
                              Kokkos::View<double* [2], ExecSpace> xi, Values outside) {
  Kokkos::parallel_for(
      "emcontact::contact::frictionless_project", Policy(0, count(refs)),
      KOKKOS_LAMBDA(const int k) {
        const ActiveRef a = refs(k);
        Geometry e(x0, x1, a);
        double z[2] = {xi(k, 0), xi(k, 1)};
        outside(k) = kernels::frictionless_project(e.y0, e.y1, e.xm0, e.xm1, z, a.closes != 0);
        for (int c = 0; c < 3; ++c) xs1(k, c) = e.y1[c];
        xi(k, 0) = z[0];
        xi(k, 1) = z[1];
      });
}

void frictionless_switch(const FacetGrid& grid_h, const LocalSlaves& ls,
                         Kokkos::View<int* [3], ExecSpace> facets, Refs refs,
                         Kokkos::View<int*, ExecSpace> leaving,
                         Kokkos::View<int*, ExecSpace> slave_k,
                         Kokkos::View<int*, ExecSpace> current, Positions x0, Positions x1,
                         Positions xh, const EntryRule& rule, Values3 xs1,
                         Kokkos::View<double* [2], ExecSpace> xi, Values outside,
                         Kokkos::View<int*, ExecSpace> next) {
  const FacetGrid grid = grid_h;  // by value: Views only
  const LocalSlaves sl = ls;
  const EntryRule r = rule;
  Kokkos::parallel_for(
      "emcontact::contact::frictionless_switch", Policy(0, static_cast<int>(leaving.extent(0))),
      KOKKOS_LAMBDA(const int j) {
        const int k = leaving(j);
        ActiveRef a = refs(k);
        double n_s[3];
        slave_normal(sl, slave_k(j), xh, n_s);
        const double y[3] = {xh(a.s, 0), xh(a.s, 1), xh(a.s, 2)};
        const Hit h = next_facet(grid, y, n_s, r);
        next(j) = -1;
        if (h.facet < 0 || h.facet == current(j)) return;
        next(j) = h.facet;
        for (int i = 0; i < 3; ++i) a.m[i] = facets(h.facet, i);
        Geometry e(x0, x1, a);
        double z[2] = {h.xi[0], h.xi[1]};
        outside(k) = kernels::frictionless_project(e.y0, e.y1, e.xm0, e.xm1, z, a.closes != 0);
        for (int c = 0; c < 3; ++c) xs1(k, c) = e.y1[c];
        xi(k, 0) = z[0];
        xi(k, 1) = z[1];
      });
}

void frictionless_blocks(Refs refs, Positions x0, Positions x1, OwnedValues g,
                         Kokkos::View<kernels::FrictionlessBlocks*, ExecSpace> blocks) {
  Kokkos::parallel_for(
      "emcontact::contact::frictionless_blocks", Policy(0, count(refs)),
      KOKKOS_LAMBDA(const int k) {
        const ActiveRef a = refs(k);
        const Geometry e(x0, x1, a);
        double gs[3];
        for (int c = 0; c < 3; ++c) gs[c] = g(a.dof[c], 0);
        kernels::frictionless_blocks(e.y0, e.y1, e.xm0, e.xm1, a.xi, gs, blocks(k), a.closes != 0);
      });
}

void coulomb_slips(Refs refs, Positions x0, Positions x1, OwnedValues g, Values weight,
                   Kokkos::View<kernels::FrictionlessBlocks*, ExecSpace> blocks,
                   Kokkos::View<kernels::CoulombSlip*, ExecSpace> slips) {
  Kokkos::parallel_for(
      "emcontact::contact::coulomb_slips", Policy(0, count(refs)), KOKKOS_LAMBDA(const int k) {
        const ActiveRef a = refs(k);
        const Geometry e(x0, x1, a);
        double gs[3];
        for (int c = 0; c < 3; ++c) gs[c] = g(a.dof[c], 0);
        kernels::SlipLaw law;
        law.mu = a.mu;
        law.weight = weight(k);
        law.held = 64 * kernels::epsilon() * a.edge;  // position round-off, as §11.4's
        for (int c = 0; c < 3; ++c) law.hint[c] = a.dir[c];
        kernels::coulomb_slip(e.y0, e.y1, e.xm0, e.xm1, a.xi, gs, law, blocks(k), slips(k));
      });
}

void coulomb_states(Refs refs, Positions x0, Positions x1, OwnedValues g,
                    Kokkos::View<kernels::CoulombState*, ExecSpace> states) {
  Kokkos::parallel_for(
      "emcontact::contact::coulomb_states", Policy(0, count(refs)), KOKKOS_LAMBDA(const int k) {
        const ActiveRef a = refs(k);
        const Geometry e(x0, x1, a);
        double gs[3];
        for (int c = 0; c < 3; ++c) gs[c] = g(a.dof[c], 0);
        kernels::coulomb_state(e.y0, e.y1, e.xm0, e.xm1, a.xi, gs, states(k));
      });
}

void start_points(Refs refs, Positions x0, Kokkos::View<double* [2], ExecSpace> xi) {
  Kokkos::parallel_for(
      "emcontact::contact::start_points", Policy(0, count(refs)), KOKKOS_LAMBDA(const int k) {
        const ActiveRef a = refs(k);
        double xm[3][3], y[3], z[2], gap;
        facet_at(x0, a, xm);
        slave_at(x0, a, y);
        const bool ok = kernels::facet_cpp(y, xm, z, gap);
        xi(k, 0) = ok ? z[0] : a.xi[0];
        xi(k, 1) = ok ? z[1] : a.xi[1];
      });
}

// docs/THEORY.md §7.4.
ClosureTerms closure_terms(Refs refs, Positions x0, Positions x1, Values3 F, Values3 wn, Values3 N1,
                           Kokkos::View<int*, ExecSpace> unrestorable) {
  ClosureTerms sum;
  Kokkos::parallel_reduce(
      "emcontact::contact::closure_terms", Policy(0, count(refs)),
      KOKKOS_LAMBDA(const int k, double& work, double& roundoff) {
        const ActiveRef a = refs(k);
        const Geometry e(x0, x1, a);
        const auto& xm0 = e.xm0;
        const auto& xm1 = e.xm1;
        const auto& y0 = e.y0;
        const auto& y1 = e.y1;
        double N[3], w_e = 0;
        kernels::facet_shape(a.xi, N);
        for (int c = 0; c < 3; ++c) {
          double rel = y1[c] - y0[c];
          for (int i = 0; i < 3; ++i) rel -= N[i] * (xm1[i][c] - xm0[i][c]);
          w_e += F(k, c) * rel;
        }
        work += w_e;
        // closing a gap at the round-off of the coordinates moves nothing: W_c below the sum
        // of these is no energy to give back (nodes deeper keep their gap, §7.2)
        const double r_e =
            (kernels::fabs(F(k, 0)) + kernels::fabs(F(k, 1)) + kernels::fabs(F(k, 2))) *
            gap_roundoff(a.edge, y1);
        roundoff += r_e;
        // the impulse weight w = max(F . n, 0) and the CPP N' on the facet at n+1 (none where the
        // facet is degenerate: w = 0)
        double xi1[2], gap, w = 0, n1[3] = {0, 0, 0}, M[3] = {0, 0, 0};
        if (kernels::facet_cpp(y1, xm1, xi1, gap)) {
          const kernels::Facet f1 = kernels::facet(xm1);
          w = kernels::fmax(0.0, F(k, 0) * f1.n[0] + F(k, 1) * f1.n[1] + F(k, 2) * f1.n[2]);
          for (int c = 0; c < 3; ++c) n1[c] = f1.n[c];
          kernels::facet_shape(xi1, M);
        }
        for (int c = 0; c < 3; ++c) {
          wn(k, c) = w * n1[c];
          N1(k, c) = M[c];
        }
        // §7.2, the closure's fallback: energy this entry gave, or took with no impulse
        unrestorable(k) = w_e > r_e || (w == 0 && -w_e > r_e);
      },
      sum.work, sum.roundoff);
  return sum;
}

DiagonalOffsets diagonal_offsets(const Matrix& A, const Kokkos::View<const GO*, ExecSpace> dof) {
  const auto lA = A.getLocalMatrixDevice();
  const auto rows = A.getRowMap()->getLocalMap();
  const auto cols = A.getColMap()->getLocalMap();
  const bool sorted = A.getCrsGraph()->isSorted();  // a row's columns in order: bisection
  DiagonalOffsets at(Kokkos::ViewAllocateWithoutInitializing("emc::diagonal_offsets"),
                     dof.extent(0));
  Kokkos::parallel_for(
      "emcontact::contact::diagonal_offsets", Kokkos::RangePolicy<ExecSpace>(0, dof.extent(0)),
      KOKKOS_LAMBDA(const int i) {
        const GO g = dof(i);
        const LO row = rows.getLocalElement(g), col = cols.getLocalElement(g);
        auto j = lA.graph.row_map(row), end = lA.graph.row_map(row + 1);
        for (auto hi = end; sorted && j < hi;) {  // the first entry at or after col
          const auto mid = j + (hi - j) / 2;
          if (lA.graph.entries(mid) < col)
            j = mid + 1;
          else
            hi = mid;
        }
        at(i) = -1;
        for (; j < end && (!sorted || lA.graph.entries(j) <= col); ++j)
          if (lA.graph.entries(j) == col) {
            at(i) = static_cast<long long>(j);
            break;
          }
      });
  return at;
}

void dummy_betas_at(const Matrix& A, const DiagonalOffsets at, const Values beta) {
  const auto values = A.getLocalMatrixDevice().values;
  Kokkos::parallel_for(
      "emcontact::contact::dummy_betas", Kokkos::RangePolicy<ExecSpace>(0, beta.extent(0)),
      KOKKOS_LAMBDA(const int k) {
        double tr = 0;
        for (int c = 0; c < 3; ++c)
          if (at(3 * k + c) >= 0) tr += values(at(3 * k + c));
        beta(k) = tr / 3;
      });
}

void dummy_betas(const Matrix& A, const Kokkos::View<const GO*, ExecSpace> dof, const Values beta) {
  dummy_betas_at(A, diagonal_offsets(A, dof), beta);
}

void mean_diagonals(const Matrix& A, const Kokkos::View<const int*, ExecSpace> slave,
                    const Values beta) {
  const auto lA = A.getLocalMatrixDevice();
  const auto rows = A.getRowMap()->getLocalMap();
  const auto cols = A.getColMap()->getLocalMap();
  Kokkos::parallel_for(
      "emcontact::contact::mean_diagonals", Kokkos::RangePolicy<ExecSpace>(0, beta.extent(0)),
      KOKKOS_LAMBDA(const int k) {
        double b = 0;
        for (int c = 0; c < 3; ++c) {
          const GO g = 3 * static_cast<GO>(slave(k)) + c;  // fem::dof_gid
          const LO row = rows.getLocalElement(g), col = cols.getLocalElement(g);
          double d = 0;  // the row's first entry in column col, as a host row view reads it
          for (auto j = lA.graph.row_map(row); j < lA.graph.row_map(row + 1); ++j)
            if (lA.graph.entries(j) == col) {
              d = lA.values(j);
              break;
            }
          b += d / 3;
        }
        beta(k) = b;
      });
}

}  // namespace emc::contact
