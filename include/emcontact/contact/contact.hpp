#pragma once
// Contact between the pairs' slave nodes and master facets (docs/THEORY.md §2-§6): the rank's
// contact nodes (docs/THEORY.md §8), activation (§6.3), the quantities the active-set loop
// reads (normal forces, gaps), the chains of P (§3) and the closure's energy (docs/THEORY.md
// §7). What a law constrains lives in its Law (law.hpp); the §6 loop in active_set.hpp.
#include <algorithm>
#include <array>
#include <map>
#include <memory>
#include <vector>

#include "emcontact/contact/active.hpp"
#include "emcontact/contact/active_kernels.hpp"
#include "emcontact/contact/nodes.hpp"
#include "emcontact/contact/pairs.hpp"
#include "emcontact/fem/discretization.hpp"
#include "emcontact/linalg/elimination.hpp"

namespace emc::contact {

class Law;

/// docs/THEORY.md §6.3: the slave nodes that crossed a master facet over a step and end behind
/// it deeper than the pair's max penetration (global), and the deepest of them.
struct DeepCrossings {
  int count = 0;
  double gap = 0;      ///< the deepest one's g_N at t_{n+1} (negative)
  double closing = 0;  ///< its g_N at t_n minus that
  int pair = -1, node = -1;
};

/// A_ii of an owned dof i of A (0 if the row stores no diagonal entry), read from its host row:
/// a reference for tests (the laws read A's diagonal with mean_diagonals, dummy_betas).
double diagonal_entry(const Matrix& A, GO i);

class Contact {
 public:
  Contact(const fem::Discretization& disc, std::vector<Pair> pairs);
  ~Contact();

  bool empty() const { return pairs_.empty(); }
  const fem::Model& disc_model() const { return disc_.model(); }
  const fem::Discretization& disc() const { return disc_; }
  Teuchos::RCP<const Comm> disc_comm() const { return disc_.comm(); }
  const std::vector<Pair>& pairs() const { return pairs_; }
  /// The law of a pair (one object per law, shared by the pairs of that type).
  const Law& law(int pair) const { return *laws_[pair]; }
  const std::vector<const Law*>& laws() const { return distinct_laws_; }
  ContactNodes& nodes() const { return nodes_; }

  /// docs/THEORY.md §8: selects this rank's contact nodes for the step from u0 to u1 and the
  /// chains of `index` (collective).
  void select(const Vector& u0, const Vector& u1, const ActiveIndex& index) const {
    nodes_.select(u0, u1, index);
  }
  /// The same for the sweeps of one step from u0 (ContactNodes::Sweep), and for the last sweep.
  ContactNodes::Sweep sweep_from(const Vector& u0) const { return nodes_.sweep_from(u0); }
  void select(const ContactNodes::Sweep& from, const Vector& u1, const ActiveIndex& index) const {
    nodes_.select(from, u1, index);
  }
  void reselect(const ActiveIndex& index) const { nodes_.reselect(index); }
  /// Positions X + u of the contact nodes (collective).
  Positions positions(const Vector& u) const;

  /// The entries in contact-node indices (every node must be one of mine: select first).
  Refs refs(const std::vector<Active>& active) const;

  /// §6.3: my inactive slave nodes that enter a master facet over the step (entered_facet),
  /// with that facet and xi from their law's activation point. x0, x1: positions at t_n, t_{n+1}.
  std::vector<Active> detect(Positions x0, Positions x1, const std::vector<Active>& active) const;

  /// §6.3: my slave nodes, not among `active` (global ids of the entries active at the step's
  /// accepted solve), that crossed a master facet over the step from x0 to x1 and end behind it
  /// deeper than the pair's max penetration (detection.hpp crossed_too_deep), on all ranks
  /// (collective). Activation cannot catch them: the step must be cut.
  DeepCrossings crossed_too_deep(Positions x0, Positions x1, const std::vector<int>& active) const;

  /// §6.6: throws InputError (naming `file`, the pair, the node count and the depth) if a
  /// slave node penetrates its master at t = 0, lies inside the master body, or a node of the
  /// master surface lies inside the slave body (collective).
  void check_initial_penetration(const std::string& file) const;

  /// f_N = g_s . n_{n+1/2} of each active entry (§4); g is the contactless residual.
  std::vector<double> normal_forces(const Vector& g, Positions x0, Positions x1,
                                    const std::vector<Active>& active) const;

  /// The index of my entries `mine` and of the other ranks' entries whose slave is a master node
  /// (the chains' links, §3): only those rows cross ranks (collective).
  ActiveIndex gather(const std::vector<Active>& mine) const;
  /// All ranks' active entries (collective): the transmitted forces (closure, docs/THEORY.md
  /// §7.4) follow chains backwards, from a master node to every entry on its facets.
  ActiveIndex gather_all(const std::vector<Active>& mine) const;
  /// Whether global node n is a node of some pair's master facets (a chain's link, §3).
  bool master_node(int n) const {
    return std::binary_search(master_nodes_.begin(), master_nodes_.end(), n);
  }

  /// Adds w du_{node,c} to row r in terms of q: the dof itself if free, nothing if rigid or
  /// fixed, or the node's own row of P if it is an active slave (chains, §3; a cycle is cut).
  /// xh: positions at n+1/2 (frictionless chains add T dq there; empty: P is built without).
  void expand_node(int node, int c, double w, const ActiveIndex& index,
                   const Positions::HostMirror& xh, std::vector<int>& path, linalg::PRow& r) const;

  /// beta = tr(A_ss)/3 for each dummy's slave (eq. 44), from A's diagonal.
  std::vector<std::pair<GO, double>> dummy_values(const Matrix& A,
                                                  const std::vector<GO>& dummies) const;

  /// docs/THEORY.md §7.4: the work W_c the contact forces of the closing pairs' active
  /// entries did over the step (global; g = the contactless residual at the solution) and
  /// the impulse direction p (owned dofs) that gives energy back along the contact normals
  /// (collective).
  ClosureWork closure_work(const Vector& g, Positions x0, Positions x1,
                           const std::vector<Active>& active, Vector& p) const;
  /// docs/THEORY.md §7.2: at the end of a step, entries of closing pairs behind their facet at
  /// x1 keep their gap in the next step, the others are closed.
  void mark_kept_gaps(std::vector<Active>& active, Positions x1) const;
  /// The force F_s each entry of `index` transmits to its facet: g_s plus what its own slaves
  /// transmit to it (chains, §3); g the contactless residual (collective).
  std::map<int, std::array<double, 3>> transmitted_forces(const Vector& g,
                                                          const ActiveIndex& index) const;
  /// g_s of every entry of `index` (collective).
  std::map<int, std::array<double, 3>> active_residuals(const Vector& g,
                                                        const ActiveIndex& index) const;
  /// Whether any pair has `close gap`; whether entry a is closed (docs/THEORY.md §7.2).
  bool closes_gaps() const;
  bool closes(const Active& a) const { return pairs_[a.pair].close_gap && !a.keep_gap; }

  /// Per entry of `active` (mine): the distance at x from its slave to its facet's point at
  /// xi, and the facet's longest edge (facet_point_distances; select first).
  std::vector<std::array<double, 2>> facet_point_distances(Positions x,
                                                           const std::vector<Active>& active) const;

  /// g_N at n+1 of the active entries on their facet's plane: global min and max.
  void gap_range(Positions x1, const std::vector<Active>& active, double& lo, double& hi) const;

  int global_count(int local) const;

 private:
  const fem::Discretization& disc_;
  std::vector<Pair> pairs_;
  std::vector<std::shared_ptr<const Law>> laws_;
  std::vector<const Law*> distinct_laws_;
  mutable ContactNodes nodes_;
  std::vector<int> master_nodes_;  ///< the deformable nodes of the pairs' master facets, sorted
  void check_facing(const Pair& pr, const std::vector<double>& x, const std::string& file) const;
  void check_overlap(const Pair& pr, const std::vector<double>& x, const std::string& file) const;
  std::vector<Active> detect_pair(int p, Positions x0, Positions x1,
                                  Kokkos::View<int*, ExecSpace> busy) const;
};

}  // namespace emc::contact
