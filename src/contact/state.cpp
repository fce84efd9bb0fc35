// The contact state on the execution space (state.hpp): made from the active-set loop's host
// list once per set, updated by kernels at Newton's iterates.
#include "emcontact/contact/state.hpp"

#include "emcontact/contact/contact.hpp"
#include "emcontact/contact/detection.hpp"
#include "emcontact/views.hpp"

namespace emc::contact {

namespace {

using Policy = Kokkos::RangePolicy<ExecSpace>;

int flags_of(const Active& a) {
  return (a.off ? flag::off : 0) | (a.keep_gap ? flag::keep_gap : 0) | (a.slip ? flag::slip : 0) |
         (a.slid ? flag::slid : 0);
}

/// The rows of `mine` then `ghosts` into the state's entry Views (one host pass, one copy).
void fill_rows(ContactState& s, const std::vector<Active>& mine,
               const std::vector<Active>& ghosts) {
  const std::size_t n = mine.size() + ghosts.size();
  s.local = static_cast<int>(mine.size());
  s.slave = Ints("emcontact::contact::state_slave", n);
  s.pair = Ints("emcontact::contact::state_pair", n);
  s.facet = Ints("emcontact::contact::state_facet", n);
  s.flags = Ints("emcontact::contact::state_flags", n);
  s.returns = Ints("emcontact::contact::state_returns", n);
  s.xi = Xis("emcontact::contact::state_xi", n);
  s.dir = Values3("emcontact::contact::state_dir", n);
  s.normal_force = Values("emcontact::contact::state_normal_force", n);
  auto slave = Kokkos::create_mirror_view(s.slave);
  auto pair = Kokkos::create_mirror_view(s.pair);
  auto facet = Kokkos::create_mirror_view(s.facet);
  auto flags = Kokkos::create_mirror_view(s.flags);
  auto returns = Kokkos::create_mirror_view(s.returns);
  auto xi = Kokkos::create_mirror_view(s.xi);
  auto dir = Kokkos::create_mirror_view(s.dir);
  for (std::size_t k = 0; k < n; ++k) {
    const Active& a = k < mine.size() ? mine[k] : ghosts[k - mine.size()];
    slave(k) = a.slave;
    pair(k) = a.pair;
    facet(k) = a.facet;
    flags(k) = flags_of(a);
    returns(k) = a.returns;
    for (int i = 0; i < 2; ++i) xi(k, i) = a.xi[i];
    for (int i = 0; i < 3; ++i) dir(k, i) = a.dir[i];
  }
  Kokkos::deep_copy(s.slave, slave);
  Kokkos::deep_copy(s.pair, pair);
  Kokkos::deep_copy(s.facet, facet);
  Kokkos::deep_copy(s.flags, flags);
  Kokkos::deep_copy(s.returns, returns);
  Kokkos::deep_copy(s.xi, xi);
  Kokkos::deep_copy(s.dir, dir);
}

/// My rows' reference slave positions, release edges and per-kind sliding rows.
void fill_local(ContactState& s, const Contact& contact, const std::vector<Active>& mine) {
  const std::size_t n = mine.size();
  const auto& m = contact.disc_model();
  s.X = Values3("emcontact::contact::state_X", n);
  s.release_edge = Values("emcontact::contact::state_release_edge", n);
  auto X = Kokkos::create_mirror_view(s.X);
  auto edge = Kokkos::create_mirror_view(s.release_edge);
  std::vector<int> sliding[3];
  for (std::size_t k = 0; k < n; ++k) {
    const Active& a = mine[k];
    const Pair& p = contact.pairs()[a.pair];
    const double* Xs = m.x(a.slave);
    for (int c = 0; c < 3; ++c) X(k, c) = Xs[c];
    edge(k) = entry_rule(p).edge;
    if (slides(p, a)) sliding[static_cast<int>(p.kind)].push_back(static_cast<int>(k));
  }
  s.reversed = Ints("emcontact::contact::state_reversed", n);
  s.slip_work = Values("emcontact::contact::state_slip_work", n);
  Kokkos::deep_copy(s.X, X);
  Kokkos::deep_copy(s.release_edge, edge);
  for (int l = 0; l < 3; ++l)
    s.sliding[l] = to_view("emcontact::contact::state_sliding", sliding[l]);
}

}  // namespace

ContactState make_state(const Contact& contact, const std::vector<Active>& mine,
                        const std::vector<Active>& ghosts) {
  ContactState s;
  fill_rows(s, mine, ghosts);
  fill_local(s, contact, mine);
  s.refs = contact.refs(mine);
  return s;
}

namespace {

/// v with my rows kept and `ghosts` rows after them (value(h, j, ...) sets ghost j of the host
/// copy h of the ghost rows only).
template <class V, class F>
V with_ghosts(const V& v, int local, std::size_t ghosts, const F& value) {
  V out(v.label(), local + ghosts);
  const auto mine = std::make_pair(0, local);
  const auto theirs = std::make_pair(static_cast<std::size_t>(local), local + ghosts);
  if constexpr (V::rank == 1) {
    Kokkos::deep_copy(Kokkos::subview(out, mine), Kokkos::subview(v, mine));
    const auto part = Kokkos::subview(out, theirs);
    auto h = Kokkos::create_mirror_view(part);
    for (std::size_t j = 0; j < ghosts; ++j) value(h, j);
    Kokkos::deep_copy(part, h);
  } else {
    Kokkos::deep_copy(Kokkos::subview(out, mine, Kokkos::ALL),
                      Kokkos::subview(v, mine, Kokkos::ALL));
    const auto part = Kokkos::subview(out, theirs, Kokkos::ALL);
    auto h = Kokkos::create_mirror_view(part);
    for (std::size_t j = 0; j < ghosts; ++j) value(h, j);
    Kokkos::deep_copy(part, h);
  }
  return out;
}

}  // namespace

void set_ghosts(ContactState& s, const std::vector<Active>& ghosts) {
  const std::size_t n = ghosts.size();
  const int l = s.local;
  s.slave = with_ghosts(s.slave, l, n, [&](auto& h, std::size_t j) { h(j) = ghosts[j].slave; });
  s.pair = with_ghosts(s.pair, l, n, [&](auto& h, std::size_t j) { h(j) = ghosts[j].pair; });
  s.facet = with_ghosts(s.facet, l, n, [&](auto& h, std::size_t j) { h(j) = ghosts[j].facet; });
  s.flags = with_ghosts(s.flags, l, n, [&](auto& h, std::size_t j) { h(j) = flags_of(ghosts[j]); });
  s.returns = with_ghosts(s.returns, l, n, [&](auto& h, std::size_t j) { h(j) = 0; });
  s.xi = with_ghosts(s.xi, l, n, [&](auto& h, std::size_t j) {
    for (int i = 0; i < 2; ++i) h(j, i) = ghosts[j].xi[i];
  });
  s.dir = with_ghosts(s.dir, l, n, [&](auto& h, std::size_t j) {
    for (int i = 0; i < 3; ++i) h(j, i) = ghosts[j].dir[i];
  });
  s.normal_force = with_ghosts(s.normal_force, l, n, [&](auto& h, std::size_t j) { h(j) = 0; });
}

std::vector<Active> host_entries(const ContactState& s, int first, int count) {
  const auto range = std::make_pair(first, first + count);
  const auto slave =
      Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), Kokkos::subview(s.slave, range));
  const auto pair =
      Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), Kokkos::subview(s.pair, range));
  const auto facet =
      Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), Kokkos::subview(s.facet, range));
  const auto flags =
      Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), Kokkos::subview(s.flags, range));
  const auto returns =
      Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), Kokkos::subview(s.returns, range));
  const auto xi = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(),
                                                      Kokkos::subview(s.xi, range, Kokkos::ALL));
  const auto dir = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(),
                                                       Kokkos::subview(s.dir, range, Kokkos::ALL));
  std::vector<Active> out(count);
  for (int k = 0; k < count; ++k) {
    Active& a = out[k];
    a.slave = slave(k);
    a.pair = pair(k);
    a.facet = facet(k);
    a.off = (flags(k) & flag::off) != 0;
    a.keep_gap = (flags(k) & flag::keep_gap) != 0;
    a.slip = (flags(k) & flag::slip) != 0;
    a.slid = (flags(k) & flag::slid) != 0;
    a.returns = returns(k);
    for (int i = 0; i < 2; ++i) a.xi[i] = xi(k, i);
    for (int i = 0; i < 3; ++i) a.dir[i] = dir(k, i);
  }
  return out;
}

void to_host(const ContactState& s, std::vector<Active>& mine) {
  const auto rows = host_entries(s, 0, s.local);
  for (int k = 0; k < s.local; ++k) {
    mine[k].facet = rows[k].facet;
    mine[k].xi[0] = rows[k].xi[0];
    mine[k].xi[1] = rows[k].xi[1];
    mine[k].off = rows[k].off;
  }
}

void set_normal_forces(ContactState& s, const std::vector<double>& fN) {
  const auto mine = Kokkos::subview(s.normal_force, std::make_pair(0, s.local));
  Kokkos::deep_copy(mine, Kokkos::View<const double*, Kokkos::HostSpace>(fN.data(), fN.size()));
}

Refs gather_refs(const ContactState& s, Ints sel) {
  Refs out(Kokkos::ViewAllocateWithoutInitializing("emcontact::contact::refs"), sel.extent(0));
  const Refs refs = s.refs;
  const Xis xi = s.xi;
  Kokkos::parallel_for(
      "emcontact::contact::gather_refs", Policy(0, static_cast<int>(sel.extent(0))),
      KOKKOS_LAMBDA(const int j) {
        ActiveRef a = refs(sel(j));
        a.xi[0] = xi(sel(j), 0);
        a.xi[1] = xi(sel(j), 1);
        out(j) = a;
      });
  return out;
}

Xis gather_xi(const ContactState& s, Ints sel) {
  Xis out(Kokkos::ViewAllocateWithoutInitializing("emcontact::contact::xi"), sel.extent(0));
  const Xis xi = s.xi;
  Kokkos::parallel_for(
      "emcontact::contact::gather_xi", Policy(0, static_cast<int>(sel.extent(0))),
      KOKKOS_LAMBDA(const int j) {
        for (int i = 0; i < 2; ++i) out(j, i) = xi(sel(j), i);
      });
  return out;
}

Ints gather_slaves(const ContactState& s, Ints sel) {
  Ints out(Kokkos::ViewAllocateWithoutInitializing("emcontact::contact::slaves"), sel.extent(0));
  const Ints slave = s.slave;
  Kokkos::parallel_for(
      "emcontact::contact::gather_slaves", Policy(0, static_cast<int>(sel.extent(0))),
      KOKKOS_LAMBDA(const int j) { out(j) = slave(sel(j)); });
  return out;
}

// docs/THEORY.md §5.3 update step 3: the projected xi and slave position; kept with the
// extrapolated xi up to the edge extension of activation (§6.3), so that a node is not
// released where it would be caught again, beyond it released at the end of the step.
void store_projections(ContactState& s, Ints sel, Xis xi, Values outside, Values3 xs1,
                       OwnedValuesRW u) {
  const Refs refs = s.refs;
  const Xis state_xi = s.xi;
  const Ints flags = s.flags;
  const Values3 X = s.X;
  const Values edge = s.release_edge;
  Kokkos::parallel_for(
      "emcontact::contact::store_projections", Policy(0, static_cast<int>(sel.extent(0))),
      KOKKOS_LAMBDA(const int j) {
        const int k = sel(j);
        for (int i = 0; i < 2; ++i) {
          state_xi(k, i) = xi(j, i);
          refs(k).xi[i] = xi(j, i);
        }
        flags(k) = outside(j) > edge(k) ? (flags(k) | flag::off) : (flags(k) & ~flag::off);
        for (int c = 0; c < 3; ++c) u(refs(k).dof[c], 0) = xs1(j, c) - X(k, c);
      });
}

int coulomb_iterate(ContactState& s, Ints sel,
                    Kokkos::View<kernels::CoulombSlip*, ExecSpace> slips) {
  const Refs refs = s.refs;
  const Values3 dir = s.dir;
  const Ints reversed = s.reversed;
  const Values work = s.slip_work;
  int n = 0;
  Kokkos::parallel_reduce(
      "emcontact::contact::coulomb_iterate", Policy(0, static_cast<int>(sel.extent(0))),
      KOKKOS_LAMBDA(const int j, int& c) {
        const int k = sel(j);
        const kernels::CoulombSlip& fr = slips(j);
        work(k) = fr.work;
        const double along = fr.dir[0] * dir(k, 0) + fr.dir[1] * dir(k, 1) + fr.dir[2] * dir(k, 2);
        if (along < 0 && refs(k).mu > 0) {
          reversed(k) = 1;
          ++c;
        }
      },
      n);
  return n;
}

void clear_reversals(ContactState& s, Ints sel) {
  const Ints reversed = s.reversed;
  Kokkos::parallel_for(
      "emcontact::contact::clear_reversals", Policy(0, static_cast<int>(sel.extent(0))),
      KOKKOS_LAMBDA(const int j) { reversed(sel(j)) = 0; });
}

int count_beyond(Values outside, double tol) {
  int n = 0;
  Kokkos::parallel_reduce(
      "emcontact::contact::count_beyond", Policy(0, static_cast<int>(outside.extent(0))),
      KOKKOS_LAMBDA(const int j, int& c) { c += outside(j) > tol ? 1 : 0; }, n);
  return n;
}

}  // namespace emc::contact
