#pragma once
// The per-active-slave computations of contact as Kokkos loops over the active entries
// (docs/THEORY.md §8): each entry reads its slave's and facet's positions from the rank's
// contact nodes and writes a fixed-width block of its own; no entry writes another's.
#include <Kokkos_Core.hpp>

#include "emcontact/contact/detection.hpp"
#include "emcontact/contact/nodes.hpp"
#include "emcontact/contact/search.hpp"
#include "kernels/coulomb.hpp"
#include "kernels/facet.hpp"
#include "kernels/frictionless.hpp"

namespace emc::contact {

/// An active entry in the numbering of the rank's contact nodes, for kernels.
struct ActiveRef {
  int s = -1;                 ///< contact-node index of the slave
  int m[3] = {-1, -1, -1};    ///< of its facet's nodes
  int dof[3] = {-1, -1, -1};  ///< the slave's dofs in the owned map (local ids)
  double xi[2] = {0, 0};      ///< frozen (stick) or current (frictionless) point on the facet
  double edge = 0;            ///< the pair's mean facet size (docs/THEORY.md §7.2 round-off)
  int closes = 0;             ///< the gap is closed (docs/THEORY.md §7.2)
  int frictionless = 0;       ///< slides under §5's constraint (frictionless, Coulomb in slip)
  double mu = 0;              ///< Coulomb friction coefficient (docs/THEORY.md §11)
  double dir[3] = {0, 0, 0};  ///< Coulomb: the direction of the entry's last slip (§11.4)
};

using Refs = Kokkos::View<ActiveRef*, ExecSpace>;
using Values = Kokkos::View<double*, ExecSpace>;
using Values3 = Kokkos::View<double* [3], ExecSpace>;
using OwnedValues = Kokkos::View<const double**, Kokkos::LayoutLeft, ExecSpace>;

/// The facet nodes of entry a in configuration x; at the mid-point of x0 and x1.
template <class X>
KOKKOS_INLINE_FUNCTION void facet_at(const X& x, const ActiveRef& a, double xm[3][3]) {
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 3; ++i) xm[k][i] = x(a.m[k], i);
}
template <class X>
KOKKOS_INLINE_FUNCTION void slave_at(const X& x, const ActiveRef& a, double y[3]) {
  for (int i = 0; i < 3; ++i) y[i] = x(a.s, i);
}

/// xh = (x0 + x1) / 2 of every contact node (the configuration at n+1/2, §5).
void midpoint(Positions x0, Positions x1, Positions xh);

/// §4: f_N = g_s . n_{n+1/2} per entry; g an owned vector's values (the contactless residual).
void normal_forces(Refs refs, Positions x0, Positions x1, OwnedValues g, Values fN);

/// g_N at n+1 of every entry on its facet's plane: (min, max) over the entries (+-1e300 if
/// none or every facet is degenerate).
void gap_range(Refs refs, Positions x1, double& lo, double& hi);
/// r(k): the round-off of entry k's slave position at x1 (an ulp of its coordinates), which a
/// projection of the slave onto its facet cannot go below (Newton's floor, docs/THEORY.md §1.6).
void position_roundoff(Refs refs, Positions x1, Values r);

/// docs/THEORY.md §7.2: 1 where the slave lies behind its facet at x deeper than the round-off.
void behind_facets(Refs refs, Positions x, Kokkos::View<int*, ExecSpace> behind);

/// d(k, 0): the distance at x from entry k's slave to its facet's point at xi; d(k, 1): the
/// facet's longest edge (a restored entry lies at its point: full stick keeps the offset of its
/// activation, frictionless and slip entries their gap, each within the activation's bounds).
void facet_point_distances(Refs refs, Positions x, Kokkos::View<double* [2], ExecSpace> d);

/// §4.1, docs/THEORY.md §7.2: the move d(k) that puts entry k's slave where its stick
/// constraint wants it at x1: x_{s,n} + N (x_{m,n+1} - x_{m,n}) (the offset of t_n kept; exactly
/// x_{s,n} where the masters did not move), or N x_{m,n+1} for a closing entry; returns the
/// largest |d| in units of the facet size.
double stick_corrections(Refs refs, Positions x0, Positions x1, Values3 d);
/// The same with x1 read where needed (the same bits: NodePositions and fill).
double stick_corrections(Refs refs, Positions x0, const NodePositions& x1, Values3 d);

/// u(a.dof[c]) += d(k, c) for every entry k (the slaves' own dofs in an owned vector's values).
using OwnedValuesRW = Kokkos::View<double**, Kokkos::LayoutLeft, ExecSpace>;
void add_to_slaves(Refs refs, Values3 d, OwnedValuesRW u);

/// §5 steps 2-3 on each frictionless entry's current facet: xi and x_{s,n+1} in place
/// (xs1 starts at x1's slave), outside = how far xi lies outside the facet.
void frictionless_projections(Refs refs, Positions x0, Positions x1, Values3 xs1,
                              Kokkos::View<double* [2], ExecSpace> xi, Values outside);

/// §5 step 2 for entries of one pair that left their facet beyond the hysteresis (refs(leaving(j)),
/// my slaves' index slave_k(j) in `ls`): the facet facing the slave whose CPP at n+1/2 is inside,
/// the nearest (next_facet on grid_h, the pair's facets at xh = n+1/2; local index current(j) is
/// the entry's own); if another is found, xi, xs1 and outside become those of steps 2-3 on it
/// and next(j) its local index, else next(j) = -1.
void frictionless_switch(const FacetGrid& grid_h, const LocalSlaves& ls,
                         Kokkos::View<int* [3], ExecSpace> facets, Refs refs,
                         Kokkos::View<int*, ExecSpace> leaving,
                         Kokkos::View<int*, ExecSpace> slave_k,
                         Kokkos::View<int*, ExecSpace> current, Positions x0, Positions x1,
                         Positions xh, const EntryRule& rule, Values3 xs1,
                         Kokkos::View<double* [2], ExecSpace> xi, Values outside,
                         Kokkos::View<int*, ExecSpace> next);

/// §5 blocks P, Pt, X of every frictionless entry at (x0, x1), g the contactless residual.
void frictionless_blocks(Refs refs, Positions x0, Positions x1, OwnedValues g,
                         Kokkos::View<kernels::FrictionlessBlocks*, ExecSpace> blocks);

/// docs/THEORY.md §11.3: the friction force and its derivative terms of every sliding Coulomb
/// entry (blocks: its frictionless blocks at the same state, weight: the slip's weight c of
/// §11.1 per entry).
void coulomb_slips(Refs refs, Positions x0, Positions x1, OwnedValues g, Values weight,
                   Kokkos::View<kernels::FrictionlessBlocks*, ExecSpace> blocks,
                   Kokkos::View<kernels::CoulombSlip*, ExecSpace> slips);
/// docs/THEORY.md §11.4: f_N, the trial tangential force, the slip and xi at t_n per entry.
void coulomb_states(Refs refs, Positions x0, Positions x1, OwnedValues g,
                    Kokkos::View<kernels::CoulombState*, ExecSpace> states);

/// §4.1: the CPP of x_{s,n} on the facet at t_n per entry (unchanged xi if degenerate).
void start_points(Refs refs, Positions x0, Kokkos::View<double* [2], ExecSpace> xi);

/// docs/THEORY.md §7.4 per closed entry, with F its transmitted force: the work
/// F . (dx_s - N dx_m) and its round-off (sums), and the impulse weight w n at n+1 and the
/// CPP N' at n+1 (w = 0: no impulse); unrestorable(k) = 1 where the entry's own work is beyond
/// its round-off and no impulse gives it back: energy it gave (work > 0), or took with w = 0
/// (§7.2, the closure's fallback).
struct ClosureTerms {
  double work = 0, roundoff = 0;
};
ClosureTerms closure_terms(Refs refs, Positions x0, Positions x1, Values3 F, Values3 wn, Values3 N1,
                           Kokkos::View<int*, ExecSpace> unrestorable);

/// Where A's diagonal entry of each owned dof(i) lies in A's values (-1: the row has none). It
/// holds as long as A's graph does: the Newton matrix keeps its graph over a run.
using DiagonalOffsets = Kokkos::View<long long*, ExecSpace>;
DiagonalOffsets diagonal_offsets(const Matrix& A, Kokkos::View<const GO*, ExecSpace> dof);

/// docs/THEORY.md §3.2 (eq. 44): beta(k) = tr(A_ss) / 3 for the slave whose owned dofs are
/// dof(3k .. 3k + 2), read from their rows of A (only those rows: the whole diagonal would cost a
/// pass over A at every Newton iterate); a row without a diagonal entry adds 0.
void dummy_betas(const Matrix& A, Kokkos::View<const GO*, ExecSpace> dof, Values beta);
/// The same with the offsets of the dofs' diagonal entries (diagonal_offsets, for A's graph).
void dummy_betas_at(const Matrix& A, DiagonalOffsets at, Values beta);
/// docs/THEORY.md §5.4 (eq. 59): beta(k), the mean of the diagonal entries of A at the three dofs
/// of owned slave node slave(k), each divided by 3 and summed in dof order, read from those rows
/// of A's local matrix (a row without a diagonal entry adds 0).
void mean_diagonals(const Matrix& A, Kokkos::View<const int*, ExecSpace> slave, Values beta);

}  // namespace emc::contact
