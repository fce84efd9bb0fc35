// Full stick (docs/THEORY.md §4): du_s = N(xi) du_m with xi frozen at activation; the slave's
// three dofs become dummies with D = beta = tr(A_ss)/3 (eq. 44). Newton starts the slave where
// its constraint wants it (on its master point with `close gap`, docs/THEORY.md §7.2), and
// du_s = N du_m keeps it there.
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_TimeMonitor.hpp>

#include "emcontact/contact/contact.hpp"
#include "law_parts.hpp"

namespace emc::contact {

namespace {

class FullStick final : public Law {
 public:
  Kind kind() const override { return Kind::full_stick; }
  double activation_weight() const override { return 0.0; }
  // docs/THEORY.md §7.2: a closing node keeps its CPP in the edge extension (closing to a
  // clamped xi drags it along the facet)
  bool clamps(const Pair& p) const override { return !p.close_gap; }
  bool iterate_dependent() const override { return false; }
  void rows(const LawState& s, const std::vector<Active>& active, const Vector*, const Matrix* A,
            LawRows& out) const override {
    stick_rows(s, Kind::full_stick, active, A, out);
  }
  void start(const LawState& s, std::vector<Active>& active, Vector& u1) const override {
    stick_start(s, Kind::full_stick, active, u1);
  }
  void after_update(const LawState&, std::vector<Active>&, Vector&) const override {}
  bool releases(const Active&, double fN) const override { return fN < 0; }
};

/// Whether entry a of pair p is one of the sticking entries of pairs of type own.
bool sticking(const Pair& p, const Active& a, Kind own) {
  return p.kind == own && sticks(p, a);
}

}  // namespace

// docs/THEORY.md §3.1, §4.2: du_s = N du_m; the slave's own column of P is zero (three dummies).
void stick_rows(const LawState& s, Kind own, const std::vector<Active>& active, const Matrix* A,
                LawRows& out) {
  static auto timer = Teuchos::TimeMonitor::getNewTimer("emcontact: contact: chains and rows");
  Teuchos::TimeMonitor tm(*timer);  // the host pass (§3 chains, the rows of P)
  const auto& pairs = s.contact.pairs();
  std::vector<GO> dummies;
  for (const auto& a : active) {
    if (!sticking(pairs[a.pair], a, own)) continue;
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

// §4.1: the start iterate satisfies every stick constraint: a slave starts at
// x_{s,n} + N (x_{m,n+1} - x_{m,n}) of the start iterate (nothing moves where it is u_n; a re-solve
// started from the last solution moves the entries activated since, docs/THEORY.md §6.1-§6.2),
// a closing slave at x_{s,n+1} = N x_{m,n+1} (docs/THEORY.md §7.2). A master node that is a
// slave itself (a chain) moves in one sweep and its own slaves follow in the next.
void stick_start(const LawState& s, Kind own, const std::vector<Active>& active, Vector& u1) {
  const Contact& contact = s.contact;
  const auto& m = contact.disc_model();
  std::vector<Active> entries;
  for (const auto& a : active)
    if (sticking(contact.pairs()[a.pair], a, own) && !m.is_fixed(a.slave)) entries.push_back(a);
  if (contact.global_count(static_cast<int>(entries.size())) == 0) return;
  const Refs refs = contact.refs(entries);
  Values3 d("emc::stick_corrections", entries.size());
  for (int sweep = 0; sweep < 8; ++sweep) {
    const double moved = stick_corrections(refs, s.x0, contact.nodes().lazy_positions(u1), d);
    add_to_slaves(refs, d, u1.getLocalViewDevice(Tpetra::Access::ReadWrite));
    double all = 0;
    Teuchos::reduceAll(*contact.disc_comm(), Teuchos::REDUCE_MAX, 1, &moved, &all);
    if (all <= 1e-13) break;  // round-off: every slave already sat where it must
  }
}

std::shared_ptr<const Law> make_full_stick() {
  return std::make_shared<FullStick>();
}

}  // namespace emc::contact
