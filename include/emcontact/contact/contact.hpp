#pragma once
// The active set of contact (ALGORITHM.md §4, §6) and the rows it adds to the elimination
// operator P (§3). Each rank handles the slave nodes it owns; positions are replicated.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <vector>

#include "emcontact/contact/pairs.hpp"
#include "emcontact/fem/discretization.hpp"
#include "emcontact/linalg/elimination.hpp"

namespace emc::contact {

/// An active slave node: its pair, master facet and the frozen xi (full stick, §4).
struct Active {
  int slave = -1;
  int pair = -1;
  int facet = -1;
  double xi[2] = {0, 0};
  bool off = false;  ///< frictionless: outside every facet by more than tol_f (released at the end)
  bool keep_gap = false;  ///< not closed although its pair closes gaps (re-activated, §7.2)
  bool operator<(const Active& o) const { return slave < o.slave; }
};

/// Every rank's active entries by slave node (replicated), to compose chains (§3): a master
/// node that is itself an active slave elsewhere contributes its own row of P.
struct ActiveIndex {
  std::map<int, Active> by_slave;
  mutable int cycles = 0;  ///< chains that looped back and were cut
};

struct StepContactStats {
  int active = 0;                   ///< global number of active slave nodes at the accepted step
  int resolves = 0;                 ///< extra solves of the step for activation / release
  int reactivated = 0;              ///< nodes released and activated again within the step (kept)
  double gap_min = 0, gap_max = 0;  ///< g_N at n+1 of the active nodes (global)
  double normal_force_min = 0;      ///< smallest f_N of the nodes active at the accepted solve
};

/// docs/THEORY.md §7.2: the round-off of a gap g_N of a slave node at x on a facet of pair p
/// (64 eps of the coordinates' and the facet's size): closing a gap below it moves nothing.
inline double gap_roundoff(const Pair& p, const double x[3]) {
  const double xmax = std::max({std::fabs(x[0]), std::fabs(x[1]), std::fabs(x[2])});
  return 64 * std::numeric_limits<double>::epsilon() * (xmax + p.edge);
}

/// docs/THEORY.md §7.4: the contact work of a step's closure and its round-off (global).
struct ClosureWork {
  double work = 0;      ///< W_c
  double roundoff = 0;  ///< |W_c| below this is round-off: nothing to give back
};

class Contact {
 public:
  Contact(const fem::Discretization& disc, std::vector<Pair> pairs);

  bool empty() const { return pairs_.empty(); }
  const fem::Model& disc_model() const { return disc_.model(); }
  Teuchos::RCP<const Comm> disc_comm() const { return disc_.comm(); }
  const std::vector<Pair>& pairs() const { return pairs_; }

  /// Every node's displacement on every rank (3 N), from an owned vector.
  std::vector<double> replicate(const Vector& u) const;

  /// §6.3: my inactive slave nodes that enter a master facet over the step (entered_facet),
  /// with that facet and xi (clamped to it) of the CPP at t_n (§4) or of the trial mid-point
  /// (§5). x0, x1: positions at t_n and t_{n+1}.
  std::vector<Active> detect(const std::vector<double>& x0, const std::vector<double>& x1,
                             const std::vector<Active>& active) const;

  /// §6.6: throws InputError (naming `file`, the pair, the node count and the depth) if a
  /// slave node penetrates its master in configuration x (collective).
  void check_initial_penetration(const std::vector<double>& x, const std::string& file) const;

  /// f_N = g_s . n_{n+1/2} of each active entry (§4); g is the contactless residual.
  std::vector<double> normal_forces(const Vector& g, const std::vector<double>& x0,
                                    const std::vector<double>& x1,
                                    const std::vector<Active>& active) const;

  /// All ranks' active entries (collective).
  ActiveIndex gather(const std::vector<Active>& mine) const;

  /// Rows of P for the active stick slaves (frictionless ones are skipped) (du_s = N du_m, §3-§4)
  /// and their dummy dofs; columns of fixed master dofs are dropped (their column of P is zero).
  void constraint_rows(const std::vector<Active>& active, const ActiveIndex& index,
                       const std::vector<double>& x0, const std::vector<double>& x1,
                       std::vector<linalg::PRow>& rows, std::vector<GO>& dummies) const;

  /// The facet nodes' coordinates of an active entry in configuration x.
  void facet_coords(const Active& a, const std::vector<double>& x, double xm[3][3]) const;
  /// Adds w du_{node,c} to row r in terms of q: the dof itself if free, nothing if rigid or
  /// fixed, or the node's own row of P if it is an active slave (chains, §3; a cycle is cut).
  void expand_node(int node, int c, double w, const ActiveIndex& index,
                   const std::vector<double>& x0, const std::vector<double>& x1,
                   std::vector<int>& path, linalg::PRow& r) const;
  /// Frictionless (§5): adds P, Pt and X of the active frictionless slaves at the state
  /// (x0, x1), with g the contactless residual; dummy_beta gets (dummy dof, beta).
  void frictionless_rows(const std::vector<Active>& active, const ActiveIndex& index,
                         const std::vector<double>& x0, const std::vector<double>& x1,
                         const Vector& g, const Matrix& A, std::vector<linalg::PRow>& rows,
                         std::vector<linalg::PRow>& pt_rows, std::vector<linalg::Entry>& X,
                         std::vector<std::pair<GO, double>>& dummy_beta) const;
  /// Update steps 2-3 of §5 for my frictionless slaves: facet (hysteresis tol_f = 1e-3, §5
  /// step 2), xi, and the normal correction of u1's slave dofs.
  void frictionless_project(std::vector<Active>& active, const std::vector<double>& x0,
                            const std::vector<double>& x1, Vector& u1) const;

  /// beta = tr(A_ss)/3 for each dummy's slave (eq. 44), from A's diagonal.
  std::vector<std::pair<GO, double>> dummy_values(const Matrix& A,
                                                  const std::vector<GO>& dummies) const;

  /// docs/THEORY.md §7.2: moves the slave dofs of u1 of my active full-stick entries of
  /// closing pairs onto their master point, x_{s,n+1} = N x_{m,n+1} (collective).
  void close_stick(const std::vector<Active>& active, Vector& u1) const;
  /// docs/THEORY.md §7.4: the work W_c the contact forces of the closing pairs' active
  /// entries did over the step (global; g = the contactless residual at the solution) and
  /// the impulse direction p (owned dofs) that gives energy back along the contact normals
  /// (collective).
  ClosureWork closure_work(const Vector& g, const std::vector<double>& x0,
                           const std::vector<double>& x1, const std::vector<Active>& active,
                           Vector& p) const;
  /// docs/THEORY.md §7.2: at the end of a step, entries of closing pairs behind their facet at
  /// x1 keep their gap in the next step, the others are closed.
  void mark_kept_gaps(std::vector<Active>& active, const std::vector<double>& x1) const;
  /// The force F_s each entry of `index` transmits to its facet: g_s plus what its own slaves
  /// transmit to it (chains, §3); g the contactless residual (collective).
  std::map<int, std::array<double, 3>> transmitted_forces(const Vector& g,
                                                          const ActiveIndex& index) const;
  /// Whether any pair has `close gap`; whether entry a is closed (docs/THEORY.md §7.2).
  bool closes_gaps() const;
  bool closes(const Active& a) const { return pairs_[a.pair].close_gap && !a.keep_gap; }

  /// g_N at n+1 of the active entries on their facet's plane: global min and max.
  void gap_range(const std::vector<double>& x1, const std::vector<Active>& active, double& lo,
                 double& hi) const;

  int global_count(int local) const;

 private:
  void check_facing(const Pair& pr, const std::vector<double>& x, const std::string& file) const;
  const fem::Discretization& disc_;
  std::vector<Pair> pairs_;
  std::vector<std::vector<int>> my_slaves_;  ///< per pair: the slave nodes this rank owns
  Teuchos::RCP<const Map> all_;              ///< every dof on every rank
  Teuchos::RCP<const Import> to_all_;
};

}  // namespace emc::contact
