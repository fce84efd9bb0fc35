// Full stick (docs/THEORY.md §4): du_s = N(xi) du_m with xi frozen at activation; the slave's
// three dofs become dummies with D = beta = tr(A_ss)/3 (eq. 44). With `close gap` (docs/THEORY.md
// §7.2) Newton starts the slave on its master point, where du_s = N du_m keeps it.
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_TimeMonitor.hpp>

#include "emcontact/contact/contact.hpp"
#include "emcontact/contact/law.hpp"

namespace emc::contact {

namespace {

class FullStick final : public Law {
 public:
  explicit FullStick(Kind own) : own_(own) {}
  Kind kind() const override { return own_; }
  double activation_weight() const override { return 0.0; }
  // docs/THEORY.md §7.2: a closing node keeps its CPP in the edge extension (closing to a
  // clamped xi drags it along the facet)
  bool clamps(const Pair& p) const override { return !p.close_gap; }
  bool iterate_dependent() const override { return false; }
  void rows(const LawState& s, const std::vector<Active>& active, const Vector* g, const Matrix* A,
            LawRows& out) const override;
  void start(const LawState& s, std::vector<Active>& active, Vector& u1) const override;
  void after_update(const LawState&, std::vector<Active>&, Vector&) const override {}
  bool releases(const Active&, double fN) const override { return fN < 0; }

 private:
  Kind own_;  ///< the pairs' type: full stick, or Coulomb's sticking entries (§11)
  bool mine(const Pair& p, const Active& a) const { return p.kind == own_ && sticks(p, a); }
};

// docs/THEORY.md §3.1, §4.2: du_s = N du_m; the slave's own column of P is zero (three dummies).
void FullStick::rows(const LawState& s, const std::vector<Active>& active, const Vector*,
                     const Matrix* A, LawRows& out) const {
  static auto timer = Teuchos::TimeMonitor::getNewTimer("emcontact: contact: chains and rows");
  Teuchos::TimeMonitor tm(*timer);  // the host pass (§3 chains, the rows of P)
  const auto& pairs = s.contact.pairs();
  std::vector<GO> dummies;
  for (const auto& a : active) {
    if (!mine(pairs[a.pair], a)) continue;
    const auto& f = pairs[a.pair].facets[a.facet];
    double N[3];
    kernels::facet_shape(a.xi, N);
    for (int c = 0; c < 3; ++c) {
      linalg::PRow r;
      r.row = fem::dof_gid(a.slave, c);
      std::vector<int> path = {a.slave};
      for (int k = 0; k < 3; ++k) s.contact.expand_node(f[k], c, N[k], s.index, s.xh, path, r);
      out.rows.push_back(std::move(r));
      dummies.push_back(fem::dof_gid(a.slave, c));
    }
  }
  if (A) {
    const auto beta = s.contact.dummy_values(*A, dummies);
    out.beta.insert(out.beta.end(), beta.begin(), beta.end());
  }
  out.dummies.insert(out.dummies.end(), dummies.begin(), dummies.end());
}

// docs/THEORY.md §7.2: a closing slave starts at x_{s,n+1} = N x_{m,n+1}. A master node that is
// a closing slave itself (a chain) moves in one sweep and its own slaves follow in the next.
void FullStick::start(const LawState& s, std::vector<Active>& active, Vector& u1) const {
  const Contact& contact = s.contact;
  const auto& m = contact.disc_model();
  std::vector<Active> closing;
  for (const auto& a : active)
    if (mine(contact.pairs()[a.pair], a) && contact.closes(a) && !m.fixed[a.slave])
      closing.push_back(a);
  if (contact.global_count(static_cast<int>(closing.size())) == 0) return;
  const Refs refs = contact.refs(closing);
  Values3 target("emc::stick_targets", closing.size());
  const auto& map = *contact.disc().owned_map();
  for (int sweep = 0; sweep < 8; ++sweep) {
    const double moved = master_points(refs, contact.positions(u1), target);
    auto th = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), target);
    auto uv = u1.getLocalViewHost(Tpetra::Access::ReadWrite);
    for (std::size_t k = 0; k < closing.size(); ++k)
      for (int c = 0; c < 3; ++c)
        uv(map.getLocalElement(fem::dof_gid(closing[k].slave, c)), 0) =
            th(k, c) - m.X[3 * closing[k].slave + c];
    double all = 0;
    Teuchos::reduceAll(*contact.disc_comm(), Teuchos::REDUCE_MAX, 1, &moved, &all);
    if (all <= 1e-13) break;  // round-off: every slave already sat on its master point
  }
}

}  // namespace

std::shared_ptr<const Law> make_full_stick(Kind own) {
  return std::make_shared<FullStick>(own);
}

}  // namespace emc::contact
