#pragma once
// What the contact laws share (docs/THEORY.md §4, §5, §11): the full-stick rows and start of
// the entries of one pair type that stick, and the frictionless blocks, scatter and projections
// of those that slide. Full stick and frictionless use them for their own pairs, Coulomb for its
// sticking and sliding entries.
#include <vector>

#include "emcontact/contact/law.hpp"
#include "emcontact/contact/state.hpp"

namespace emc::contact {

/// docs/THEORY.md §3.1, §4.2: the rows of P of the entries of `active` of pairs of type `own`
/// that stick (du_s = N du_m, three dummies per slave; their beta from A if given).
void stick_rows(const LawState& s, Kind own, const std::vector<Active>& active, const Matrix* A,
                LawRows& out);
/// §4.1: Newton's start iterate satisfies those entries' stick constraints (collective).
void stick_start(const LawState& s, Kind own, const std::vector<Active>& active, Vector& u1);

/// §5 at the iterate, for my rows of the state of pairs of type `own` that slide (sel): their
/// frictionless blocks, beta (eq. 59) and position round-off, on the execution space and as
/// host copies for the scatter into P's rows; `entries` their host records (the chains' pass).
struct SlidingBlocks {
  Ints sel;
  Refs refs;
  Kokkos::View<kernels::FrictionlessBlocks*, ExecSpace> blocks;
  Values beta;
  Kokkos::View<kernels::FrictionlessBlocks*, ExecSpace>::HostMirror blocks_h;
  Values::HostMirror beta_h, roundoff_h;
  std::vector<Active> entries;
  int size() const { return static_cast<int>(sel.extent(0)); }
};
/// The blocks of my sliding rows of type `own` (none when there are none, or without g or A).
SlidingBlocks sliding_blocks(const LawState& s, Kind own, const Vector* g, const Matrix* A);

/// Scatters the blocks of one slave into P, Pt and X through the chains (§3); with `fr`, the
/// friction terms of docs/THEORY.md §11.3 (left factor rows, X terms, the friction loads).
void scatter(const LawState& s, const Active& a, const kernels::FrictionlessBlocks& b,
             const kernels::CoulombSlip* fr, LawRows& out);
/// Adds entry k's beta on its dummy (eq. 59) and its share of Newton's floor.
void add_beta(const SlidingBlocks& b, int k, LawRows& out);

/// docs/THEORY.md §5.3 update steps 2-3 (eq. 60-64) on my sliding rows of type `own`.
void project_sliding(const LawState& s, Kind own, Vector& u1);

/// docs/THEORY.md §11.4: after a failed solve, for the law of pairs of type `own`: if some of
/// its rows' slip turned against their direction at an iterate (on any rank), those sliding
/// entries return to stick, else the sliding entries that did not slide at t_n do (counted in
/// `returns`); the rows' reversal marks are cleared. Returns how many entries changed (local).
int stick_reversed(const LawState& s, Kind own, std::vector<Active>& active);

}  // namespace emc::contact
