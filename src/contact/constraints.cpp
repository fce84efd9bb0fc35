#include "emcontact/contact/constraints.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_TimeMonitor.hpp>

#include "emcontact/parallel.hpp"

namespace emc::contact {

ActiveConstraints::ActiveConstraints(const Contact& contact, linalg::Elimination& elim,
                                     std::vector<GO> fixed)
    : contact_(contact), elim_(elim), fixed_(std::move(fixed)) {
  elim_.set_constraints(fixed_, {}, {});
}

LawState ActiveConstraints::law_state(Positions x1) {
  LawState s{contact_, index_, x0_, x1, {}};
  s.state = &state_;
  if (iterate_dependent_ && x1.extent(0) > 0) {  // n+1/2 for the chains' tangents (§5)
    Positions xh = contact_.nodes().new_positions("emc::xh");
    midpoint(x0_, x1, xh);
    s.xh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), xh);
  }
  return s;
}

// docs/THEORY.md §3, §4.2: rebuild P only when the active set changes (on any rank: collective).
bool ActiveConstraints::use(std::vector<Active>* trial, ActiveIndex index) {
  trial_ = trial;
  std::vector<std::array<double, 5>> key;
  std::vector<std::array<int, 2>> members;
  std::vector<int> count(contact_.laws().size(), 0);
  for (const auto& a : *trial) {
    key.push_back({double(a.slave), double(a.facet), a.xi[0], a.xi[1], double(a.slip)});
    members.push_back({a.slave, a.slip ? 1 : 0});
    const Law* law = &contact_.law(a.pair);
    for (std::size_t l = 0; l < count.size(); ++l) count[l] += contact_.laws()[l] == law;
  }
  present_.clear();
  iterate_dependent_ = false;
  for (std::size_t l = 0; l < count.size(); ++l)
    if (contact_.global_count(count[l]) > 0) {
      present_.push_back(contact_.laws()[l]);
      iterate_dependent_ |= contact_.laws()[l]->iterate_dependent();
    }
  index_ = std::move(index);
  state_ = make_state(contact_, *trial, index_.ghosts);
  const bool new_members = contact_.global_count(members == members_ ? 0 : 1) > 0;
  members_ = std::move(members);
  if (iterate_dependent_) applied_.clear();  // P is rebuilt at every iterate anyway
  if (contact_.global_count(key == applied_ ? 0 : 1) == 0) return false;
  if (!iterate_dependent_) {  // an iterate-dependent P is set by before_reduce at each iterate
    LawRows out;
    const LawState s = law_state({});
    for (const Law* law : present_) law->rows(s, *trial, nullptr, nullptr, out);
    elim_.set_constraints(fixed_, out.rows, {});
    elim_.set_dummies(out.dummies);  // beta on them at every iterate (before_reduce)
    dummy_dofs_ = Kokkos::View<GO*, ExecSpace>(
        Kokkos::ViewAllocateWithoutInitializing("emc::dummies"), out.dummies.size());
    Kokkos::deep_copy(dummy_dofs_, Kokkos::View<const GO*, Kokkos::HostSpace>(out.dummies.data(),
                                                                              out.dummies.size()));
    beta_ = Values(Kokkos::ViewAllocateWithoutInitializing("emc::beta"), out.dummies.size() / 3);
    dummy_graph_ = Teuchos::null;  // their diagonal entries are found at the next iterate
  }
  applied_ = std::move(key);
  return !iterate_dependent_ || new_members;
}

// §5: the start iterate is projected (update steps 2-3), so that it satisfies (a) and (b);
// docs/THEORY.md §7.2: closing full-stick slaves start on their master point.
void ActiveConstraints::start(const Vector&, Vector& u1) {
  if (present_.empty()) return;  // x0_: set_start_positions
  const LawState s = law_state({});
  for (const Law* law : present_) law->start(s, *trial_, u1);
  if (iterate_dependent_) exchange();  // facets and xi moved
}

void ActiveConstraints::before_reduce(const Vector&, const Vector& u1, Vector& g, const Matrix& A) {
  static auto timer = Teuchos::TimeMonitor::getNewTimer("emcontact: contact: Newton iterates");
  Teuchos::TimeMonitor tm(*timer);  // beta, and the rows that follow the iterate
  roundoff_ = 0;
  A_ = &A;
  if (!iterate_dependent_) {  // P is fixed during the step, beta follows A (eq. 44)
    if (dummy_graph_.get() != A.getCrsGraph().get()) {  // a new set (or a new matrix)
      dummy_diagonal_ = diagonal_offsets(A, dummy_dofs_);
      dummy_graph_ = A.getCrsGraph();
    }
    dummy_betas_at(A, dummy_diagonal_, beta_);  // docs/THEORY.md §3.2
    elim_.set_dummy_betas(beta_);
    return;
  }
  // P depends on the iterate (frictionless: N, tau at n+1/2, the facet): rebuild every time
  LawRows out;
  const LawState s = law_state(contact_.positions(u1));
  for (const Law* law : present_) law->rows(s, *trial_, &g, &A, out);
  roundoff_ = out.roundoff;
  elim_.set_constraints(fixed_, out.rows, out.beta);
  elim_.set_linearisation(out.pt_rows, out.X, out.pl_rows);
  subtract_loads(out.load, g);
}

// docs/THEORY.md §11.1: g -= the friction forces (a master dof may be owned by another rank).
void ActiveConstraints::subtract_loads(const std::vector<std::pair<GO, double>>& load,
                                       Vector& g) const {
  if (contact_.global_count(static_cast<int>(load.size())) == 0) return;
  std::vector<double> send;
  for (const auto& [dof, v] : load) send.insert(send.end(), {double(dof), v});
  const auto all = allgather(*contact_.disc_comm(), send);
  auto gv = g.getLocalViewHost(Tpetra::Access::ReadWrite);
  const auto& map = *g.getMap();
  for (std::size_t k = 0; k + 1 < all.size(); k += 2) {
    const LO l = map.getLocalElement(static_cast<GO>(all[k]));
    if (l != Tpetra::Details::OrdinalTraits<LO>::invalid()) gv(l, 0) -= all[k + 1];
  }
}

// docs/THEORY.md §11.4: a Coulomb entry still sliding against its direction after 4 iterations,
// or a solve with sliding entries 8 iterations without 6 decades (Newton is quadratic where
// the sliding solution exists), has no sliding solution: the active-set loop makes the entries
// that did not slide at t_n stick.
bool ActiveConstraints::abandon(int iteration, double r, double r0) {
  if (iteration < 4) return false;
  int stalls = 0, slides = 0;
  for (const Law* law : present_) {
    stalls += state_.reversed_now[static_cast<int>(law->kind())] ? 1 : 0;
    slides += state_.sliding_now[static_cast<int>(law->kind())] ? 1 : 0;
  }
  int flags[2] = {stalls, slides}, all[2];
  Teuchos::reduceAll(*contact_.disc_comm(), Teuchos::REDUCE_SUM, 2, flags, all);
  return all[0] > 0 || (iteration >= 8 && all[1] > 0 && r > 1e-6 * r0);
}

void ActiveConstraints::after_update(const Vector&, Vector& u1) {
  if (!iterate_dependent_) return;
  const LawState s = law_state({});
  for (const Law* law : present_) law->after_update(s, *trial_, u1);
  exchange();  // xi and facets moved: chains use the new ones
}

// §3: the chains' index from my rows of the state (a host copy: the chains are a host pass),
// the other ranks' links into the state's ghost rows.
void ActiveConstraints::exchange() {
  index_ = contact_.gather(host_entries(state_, 0, state_.local));
  set_ghosts(state_, index_.ghosts);
}

}  // namespace emc::contact
