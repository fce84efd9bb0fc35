#pragma once
// The active set of contact (docs/THEORY.md §4, §6) as plain records, and what a step reports
// of it.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <vector>

#include "emcontact/contact/pairs.hpp"
#include "kernels/math.hpp"

namespace emc::contact {

/// An active slave node: its pair, master facet and the frozen xi (full stick, §4).
struct Active {
  int slave = -1;  ///< global node id
  int pair = -1;
  int facet = -1;  ///< facet id in the pair
  double xi[2] = {0, 0};
  bool off = false;  ///< frictionless: outside every facet by more than tol_f (released at the end)
  bool keep_gap = false;  ///< not closed although its pair closes gaps (§7.2: behind its facet,
                          ///< or kept by the closure's fallback)
  // Coulomb friction (docs/THEORY.md §11)
  bool slip = false;          ///< slides (frictionless constraint plus friction) or sticks
  int returns = 0;            ///< returns to stick in this step (§11.4, at most kMaxReturns)
  bool slid = false;          ///< slid at t_n (the state the step started with)
  double dir[3] = {0, 0, 0};  ///< the slip direction of the last solve (or the trial's)
  bool operator<(const Active& o) const { return slave < o.slave; }
};

/// Whether entry a of pair p slides under the frictionless constraint of §5 (frictionless, or
/// Coulomb in slip) or sticks under the full-stick constraint of §4 (docs/THEORY.md §11).
inline bool slides(const Pair& p, const Active& a) {
  return p.kind == Kind::frictionless || (p.kind == Kind::coulomb && a.slip);
}
inline bool sticks(const Pair& p, const Active& a) {
  return !slides(p, a);
}

/// The doubles an entry packs into (slave, pair, facet, xi, eta): how it travels between ranks
/// and into the checkpoint (output::Checkpoint::active).
constexpr std::size_t kPackedActive = 5;

/// Appends the kPackedActive values of `a` to `out`.
inline void pack(const Active& a, std::vector<double>& out) {
  out.insert(out.end(), {double(a.slave), double(a.pair), double(a.facet), a.xi[0], a.xi[1]});
}

/// The entry packed at `p` (kPackedActive values).
inline Active unpack(const double* p) {
  Active a;
  a.slave = static_cast<int>(p[0]);
  a.pair = static_cast<int>(p[1]);
  a.facet = static_cast<int>(p[2]);
  a.xi[0] = p[3];
  a.xi[1] = p[4];
  return a;
}

/// The doubles of an entry's state that a step starts from besides the kPackedActive values
/// (slip 1 or stick 0, the direction of its last slip, off 1 or 0; docs/THEORY.md §11.4): what
/// the checkpoint stores with them (output::Checkpoint::state, §11.7).
constexpr std::size_t kPackedState = 5;

/// Appends the kPackedState values of `a` to `out`.
inline void pack_state(const Active& a, std::vector<double>& out) {
  out.insert(out.end(), {a.slip ? 1.0 : 0.0, a.dir[0], a.dir[1], a.dir[2], a.off ? 1.0 : 0.0});
}

/// Sets the state of `a` from the kPackedState values at `p`.
inline void unpack_state(const double* p, Active& a) {
  a.slip = p[0] != 0;
  for (int i = 0; i < 3; ++i) a.dir[i] = p[1 + i];
  a.off = p[4] != 0;
}

/// The active entries a rank's chains (§3) can reach, by slave node: its own and the other ranks'
/// entries whose slave is a master node (a master node that is itself an active slave elsewhere
/// contributes its own row of P). Contact::gather_all makes one of every rank's entries.
struct ActiveIndex {
  std::map<int, Active> by_slave;
  std::vector<Active> ghosts;  ///< the other ranks' entries of by_slave (ascending slave)
  mutable int cycles = 0;      ///< chains that looped back and were cut
};

struct StepContactStats {
  int active = 0;                   ///< global number of active slave nodes at the accepted step
  int resolves = 0;                 ///< extra solves of the step for activation / release
  int reactivated = 0;              ///< nodes released and activated again within the step (kept)
  double gap_min = 0, gap_max = 0;  ///< g_N at n+1 of the active nodes (global)
  double normal_force_min = 0;      ///< smallest f_N of the nodes active at the accepted solve
  /// Coulomb (docs/THEORY.md §11.4): the largest |f_T| / (mu f_N) of the sticking entries with
  /// f_N > 0 at the accepted solve (global; 0 without any)
  double cone_ratio = 0;
};

/// docs/THEORY.md §7.2: the round-off of a gap g_N of a slave node at x on a facet of pair p
/// (64 eps of the coordinates' and the facet's size): closing a gap below it moves nothing.
KOKKOS_INLINE_FUNCTION double gap_roundoff(double edge, const double x[3]) {
  const double a = kernels::fabs(x[0]), b = kernels::fabs(x[1]), c = kernels::fabs(x[2]);
  const double xmax = a > b ? (a > c ? a : c) : (b > c ? b : c);
  return 64 * kernels::epsilon() * (xmax + edge);
}
inline double gap_roundoff(const Pair& p, const double x[3]) {
  return gap_roundoff(p.edge, x);
}

/// docs/THEORY.md §7.4: the contact work of a step's closure and its round-off (global).
struct ClosureWork {
  double work = 0;      ///< W_c
  double roundoff = 0;  ///< |W_c| below this is round-off: nothing to give back
  /// my closed slaves whose own closure work no impulse gives back (docs/THEORY.md §7.2, the
  /// closure's fallback: energy they gave, or took without a compressive force)
  std::vector<int> unrestorable;
};

}  // namespace emc::contact
