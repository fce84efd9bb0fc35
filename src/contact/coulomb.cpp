// Coulomb friction (docs/THEORY.md §11): an active slave sticks under the full-stick
// constraint of §4 or slides under the frictionless constraint of §5 with the tangential force
// mu |f_N| against its slip. The return map is done in the active-set loop of §6 (§11.4): after
// a converged solve a sticking entry whose trial tangential force leaves the cone slides, a
// sliding entry whose slip vanished or turned against its direction sticks (and stays stuck
// to the end of the step), and the step is solved again.
#include <Teuchos_TimeMonitor.hpp>
#include <cmath>

#include "emcontact/contact/contact.hpp"
#include "emcontact/views.hpp"
#include "law_parts.hpp"

namespace emc::contact {

namespace {
/// docs/THEORY.md §11.4: an entry returns to stick at most this often in a step, which bounds
/// the active-set loop (perf/README.md, "Constants of the code, measured")
constexpr int kMaxReturns = 5;

class Coulomb final : public Law {
 public:
  Kind kind() const override { return Kind::coulomb; }
  // a new entry sticks first (§11.4): xi as full stick's
  double activation_weight() const override { return 0.0; }
  bool clamps(const Pair& p) const override { return !p.close_gap; }
  bool iterate_dependent() const override { return true; }
  void rows(const LawState& s, const std::vector<Active>& active, const Vector* g, const Matrix* A,
            LawRows& out) const override;
  void start(const LawState& s, std::vector<Active>& active, Vector& u1) const override;
  void after_update(const LawState& s, std::vector<Active>&, Vector& u1) const override {
    project_sliding(s, Kind::coulomb, u1);
  }
  bool releases(const Active& a, double fN) const override { return fN < 0 || (a.slip && a.off); }
  int settle(const LawState& s, std::vector<Active>& active, const Vector& g) const override;
  int after_failure(const LawState& s, std::vector<Active>& active) const override;
  void activate(const LawState& s, std::vector<Active>& fresh, const Vector& g) const override;
  double dissipation(const LawState& s, const std::vector<Active>& active,
                     const Vector& g) const override;
};

// §4 rows of the sticking entries, then §5 rows of the sliding ones with the friction terms of
// docs/THEORY.md §11.3; the friction force's work and the slips that turned against their
// direction at this iterate go to the state (§11.4).
void Coulomb::rows(const LawState& s, const std::vector<Active>& active, const Vector* g,
                   const Matrix* A, LawRows& out) const {
  stick_rows(s, Kind::coulomb, active, A, out);
  ContactState& st = *s.state;
  Kokkos::deep_copy(st.slip_work, 0.0);
  const SlidingBlocks b = sliding_blocks(s, Kind::coulomb, g, A);
  const int n = b.size();
  if (n == 0) return;
  constexpr int kind = static_cast<int>(Kind::coulomb);
  st.sliding_now[kind] = true;
  Kokkos::View<kernels::CoulombSlip*, ExecSpace> slips("emc::coulomb_slips", n);
  coulomb_slips(b.refs, s.x0, s.x1, g->getLocalViewDevice(Tpetra::Access::ReadOnly), b.beta,
                b.blocks, slips);
  st.reversed_now[kind] = coulomb_iterate(st, b.sel, slips) > 0;
  auto fh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), slips);
  static auto timer = Teuchos::TimeMonitor::getNewTimer("emcontact: contact: chains and rows");
  Teuchos::TimeMonitor tm(*timer);  // the host pass (§3 chains, the scatter into P's rows)
  for (int k = 0; k < n; ++k) {
    scatter(s, b.entries[k], b.blocks_h(k), &fh(k), out);
    add_beta(b, k, out);
  }
}

void Coulomb::start(const LawState& s, std::vector<Active>& active, Vector& u1) const {
  stick_start(s, Kind::coulomb, active, u1);
  ContactState& st = *s.state;  // the reversals are the current solve's (§11.4)
  constexpr int kind = static_cast<int>(Kind::coulomb);
  clear_reversals(st, st.sliding[kind]);
  st.reversed_now[kind] = false;
  project_sliding(s, Kind::coulomb, u1);
}

/// My Coulomb entries of `active` (their index into it in `where`).
std::vector<Active> mine(const Contact& contact, const std::vector<Active>& active,
                         std::vector<std::size_t>& where) {
  std::vector<Active> out;
  for (std::size_t k = 0; k < active.size(); ++k)
    if (contact.pairs()[active[k].pair].kind == Kind::coulomb) {
      out.push_back(active[k]);
      where.push_back(k);
    }
  return out;
}

std::vector<kernels::CoulombState> states(const LawState& s, const std::vector<Active>& entries,
                                          const Vector& g) {
  Kokkos::View<kernels::CoulombState*, ExecSpace> st("emc::coulomb_states", entries.size());
  coulomb_states(s.contact.refs(entries), s.x0, s.x1,
                 g.getLocalViewDevice(Tpetra::Access::ReadOnly), st);
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), st);
  return std::vector<kernels::CoulombState>(h.data(), h.data() + h.extent(0));
}

/// docs/THEORY.md §11.4: a slip below a few ulps of the master's facet size is no slip (a sliding
/// entry with it returns to stick)
double vanishing_slip(const Pair& p) {
  return 64 * kernels::epsilon() * p.edge;
}

/// The tangential force that slides entry k of `entries` by the vanishing slip at most: its
/// stiffness (the mean diagonal entry of the Newton matrix at the slave's dofs, which no
/// neighbour's give softens; a kernel over those rows of A) times vanishing_slip. A sticking
/// entry outside the cone by less would slide by less than that and return to stick at once,
/// with nothing moved (docs/THEORY.md §11.4). All 0 without a matrix.
std::vector<double> slip_forces(const LawState& s, const std::vector<Active>& entries) {
  std::vector<double> out(entries.size(), 0.0);
  if (!s.A || entries.empty()) return out;
  std::vector<int> slaves;
  for (const auto& a : entries) slaves.push_back(a.slave);
  Values beta("emc::coulomb_beta", entries.size());
  mean_diagonals(*s.A, to_view("emc::coulomb_slaves", slaves), beta);
  const auto bh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), beta);
  for (std::size_t k = 0; k < entries.size(); ++k)
    out[k] = bh(k) * vanishing_slip(s.contact.pairs()[entries[k].pair]);
  return out;
}

/// A sliding entry returns to stick at the CPP of x_{s,n} on its facet at t_n (§4.1: the frozen
/// offset is then normal); after kMaxReturns returns in a step it sticks to the step's end.
void stick_at_start(const LawState& s, std::vector<Active>& active,
                    const std::vector<std::size_t>& which) {
  std::vector<Active> entries;
  for (std::size_t k : which) entries.push_back(active[k]);
  Kokkos::View<double* [2], ExecSpace> xi("emc::coulomb_xi0", entries.size());
  start_points(s.contact.refs(entries), s.x0, xi);
  auto h = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), xi);
  for (std::size_t j = 0; j < which.size(); ++j) {
    Active& a = active[which[j]];
    a.slip = false;
    ++a.returns;
    a.xi[0] = h(j, 0);
    a.xi[1] = h(j, 1);
  }
}

// docs/THEORY.md §11.4: the return map on the converged solve.
int Coulomb::settle(const LawState& s, std::vector<Active>& active, const Vector& g) const {
  std::vector<std::size_t> where;
  const auto entries = mine(s.contact, active, where);
  double& cone = s.state->cone;
  cone = 0;
  if (entries.empty()) return 0;
  const auto st = states(s, entries, g);
  const auto slip_force = slip_forces(s, entries);
  const auto slip_work =
      Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), s.state->slip_work);
  int changed = 0;
  std::vector<std::size_t> back;
  for (std::size_t k = 0; k < entries.size(); ++k) {
    Active& a = active[where[k]];
    const double mu = s.contact.pairs()[a.pair].mu;
    const kernels::CoulombState& c = st[k];
    if (!a.slip) {
      const double ft =
          std::sqrt(c.trial[0] * c.trial[0] + c.trial[1] * c.trial[1] + c.trial[2] * c.trial[2]);
      // out of the cone (beyond its round-off, and by more than the force of a slip that would
      // vanish) and not returned in this step: slide
      if (a.returns >= kMaxReturns || !(c.fN > 0) || !(ft > mu * c.fN * (1 + 1e-9)) ||
          !(ft - mu * c.fN > slip_force[k])) {
        if (c.fN > 0 && mu > 0) cone = std::max(cone, ft / (mu * c.fN));
        continue;
      }
      a.slip = true;
      for (int i = 0; i < 3; ++i) a.dir[i] = -c.trial[i] / ft;  // the slip the force resists
      ++changed;
      continue;
    }
    const double along = c.sT[0] * a.dir[0] + c.sT[1] * a.dir[1] + c.sT[2] * a.dir[2];
    // the slip vanished (below a few ulps of the facet's size), turned back, or goes along the
    // friction force (its work < 0: the converged state of a node that sticks, §11.4): stick
    if (mu > 0 && (c.slip <= vanishing_slip(s.contact.pairs()[a.pair]) || along < 0 ||
                   !(slip_work(where[k]) > 0))) {
      back.push_back(where[k]);
      ++changed;
      continue;
    }
    if (c.slip > 0)
      for (int i = 0; i < 3; ++i) a.dir[i] = c.sT[i] / c.slip;
  }
  if (!back.empty()) stick_at_start(s, active, back);
  return changed;
}

// docs/THEORY.md §11.4: an entry activated while moving along its facet over the step starts in
// slip in that direction (a stick solve first would stop it for a step, and the forces of that
// step would release its neighbours); one at rest sticks.
void Coulomb::activate(const LawState& s, std::vector<Active>& fresh, const Vector& g) const {
  std::vector<std::size_t> where;
  const auto entries = mine(s.contact, fresh, where);
  if (entries.empty()) return;
  const auto st = states(s, entries, g);
  for (std::size_t k = 0; k < entries.size(); ++k) {
    Active& a = fresh[where[k]];
    if (!(st[k].slip > vanishing_slip(s.contact.pairs()[a.pair]))) continue;
    a.slip = true;
    for (int i = 0; i < 3; ++i) a.dir[i] = st[k].sT[i] / st[k].slip;
  }
}

int Coulomb::after_failure(const LawState& s, std::vector<Active>& active) const {
  std::vector<Active> before = active;
  stick_reversed(s, Kind::coulomb, active);
  std::vector<std::size_t> back;
  for (std::size_t k = 0; k < active.size(); ++k)
    if (before[k].slip && !active[k].slip) {
      active[k] = before[k];
      back.push_back(k);
    }
  if (!back.empty()) stick_at_start(s, active, back);
  return static_cast<int>(back.size());
}

// docs/THEORY.md §11.2: D_{n+1} - D_n = the work -f_T . s of the friction forces of the
// sliding entries at the solution (the last iterate), = mu |f_N| |s_T| (> 0: the return map)
double Coulomb::dissipation(const LawState& s, const std::vector<Active>& active,
                            const Vector&) const {
  const auto work = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), s.state->slip_work);
  double d = 0;
  for (std::size_t k = 0; k < active.size(); ++k)
    if (active[k].slip) d += work(k);
  return d;
}

}  // namespace

std::shared_ptr<const Law> make_coulomb() {
  return std::make_shared<Coulomb>();
}

}  // namespace emc::contact
