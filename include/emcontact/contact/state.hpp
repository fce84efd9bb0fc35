#pragma once
// The contact state of the rank's active set on the execution space (docs/THEORY.md §4-§6,
// §11): the active slave entries of this rank (its local rows) and the ghost rows its chains
// (§3) need, the entries of other ranks whose slave is a master node. Newton's iterates read
// and update these Views with kernels; the host list of Active entries is the active-set
// loop's, synchronised with the state once per solve (ContactState::to_host).
#include <Kokkos_Core.hpp>
#include <array>
#include <vector>

#include "emcontact/contact/active.hpp"
#include "emcontact/contact/active_kernels.hpp"

namespace emc::contact {

class Contact;

/// The status flags of an entry (ContactState::flags, bits).
namespace flag {
constexpr int off = 1;       ///< frictionless: outside every facet by more than tol_f (§5)
constexpr int keep_gap = 2;  ///< not closed although its pair closes gaps (§7.2)
constexpr int slip = 4;      ///< Coulomb: slides (§11)
constexpr int slid = 8;      ///< Coulomb: slid at t_n (§11.4)
}  // namespace flag

using Ints = Kokkos::View<int*, ExecSpace>;
using Xis = Kokkos::View<double* [2], ExecSpace>;

struct ContactState {
  /// Rows [0, local) are my entries (the order of the active-set loop's list, ascending
  /// slave), rows [local, size) the ghost rows (ascending slave).
  Ints slave, pair, facet, flags, returns;
  Xis xi;
  Values3 dir;          ///< Coulomb: the direction of the entry's last slip (§11.4)
  Values normal_force;  ///< f_N at the last solve's solution (0 until then; ghosts 0)
  int local = 0;

  /// Of my rows, in contact-node numbering (kernels; their xi follows xi): valid for the
  /// contact nodes of the solve (ActiveConstraints::use makes the state anew for each solve).
  Refs refs;
  /// My rows' slave reference positions, and how far xi may lie outside the facet before the
  /// entry is released (the pair's edge extension of activation, §6.3).
  Values3 X;
  Values release_edge;
  /// Per law kind (Kind as an index): my rows of that kind that slide under §5's constraint
  /// (frictionless, Coulomb in slip); they do not change within a solve.
  std::array<Ints, 3> sliding;

  /// The laws' state at Newton's iterates (docs/THEORY.md §11.4), of my rows: marked where the
  /// slip turned against the entry's direction at an iterate of the current solve; the work
  /// -f_T . s of the friction force at the last iterate (0 where none slides with friction).
  Ints reversed;
  Values slip_work;
  /// Per law kind, at the last iterate: some slip turned back; some entry slides with friction.
  bool reversed_now[3] = {false, false, false};
  bool sliding_now[3] = {false, false, false};
  /// The largest |f_T| / (mu f_N) of the sticking entries the last return map kept (§11.4).
  double cone = 0;

  int size() const { return static_cast<int>(slave.extent(0)); }
};

/// The state of my entries `mine` and the ghost rows `ghosts` (host lists; once per set), with
/// my rows bound to the contact nodes (select first).
ContactState make_state(const Contact& contact, const std::vector<Active>& mine,
                        const std::vector<Active>& ghosts);

/// The ghost rows become `ghosts` (the other ranks' links of the chains, ActiveIndex::ghosts);
/// my rows are kept.
void set_ghosts(ContactState& s, const std::vector<Active>& ghosts);

/// My rows' facet, xi and off flag back into `mine` (the list the state was made from).
void to_host(const ContactState& s, std::vector<Active>& mine);

/// Rows [first, first + count) of the state as host records.
std::vector<Active> host_entries(const ContactState& s, int first, int count);

/// My rows' normal force f_N (§4) at the solution of a solve, fN in row order.
void set_normal_forces(ContactState& s, const std::vector<double>& fN);

/// refs(sel(j)) with its xi from the state, for kernels over a subset of my rows.
Refs gather_refs(const ContactState& s, Ints sel);
/// xi(j) = s.xi(sel(j)).
Xis gather_xi(const ContactState& s, Ints sel);
/// The slaves of rows sel.
Ints gather_slaves(const ContactState& s, Ints sel);

/// §5 update step 3 on the state: rows sel(j) take xi(j) (also in refs), the off flag where
/// outside(j) exceeds their release edge, and the slave's dofs of u the displacement of xs1(j).
void store_projections(ContactState& s, Ints sel, Xis xi, Values outside, Values3 xs1,
                       OwnedValuesRW u);

/// docs/THEORY.md §11.4 at an iterate, for my sliding Coulomb rows sel(j) and their friction
/// terms slips(j): the rows' slip work, and the reversal mark of those whose slip goes against
/// their direction (mu > 0); returns how many did at this iterate.
int coulomb_iterate(ContactState& s, Ints sel,
                    Kokkos::View<kernels::CoulombSlip*, ExecSpace> slips);
/// Clears the reversal marks of rows sel.
void clear_reversals(ContactState& s, Ints sel);

/// How many of outside(j) exceed tol.
int count_beyond(Values outside, double tol);

}  // namespace emc::contact
