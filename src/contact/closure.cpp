// docs/THEORY.md §7: the work of the contact forces that the closure of gaps makes nonzero, for
// the velocity update that gives it back.
#include <Teuchos_CommHelpers.hpp>
#include <algorithm>

#include "emcontact/contact/contact.hpp"
#include "emcontact/parallel.hpp"

namespace emc::contact {

// §7.4: W_c = sum_e F_e . ((x_{s,n+1} - x_{s,n}) - N (x_{m,n+1} - x_{m,n})) over the active
// entries of closing pairs, and p: +w_e n_e on the slave, -w_e N'_i n_e on its free master
// nodes, w_e = max(F_e . n_e, 0), n_e and N' the facet's normal and the slave's CPP at t_{n+1}.
ClosureWork Contact::closure_work(const Vector& g, Positions x0, Positions x1,
                                  const std::vector<Active>& active, Vector& p) const {
  const auto& m = disc_.model();
  const auto F = transmitted_forces(g, gather_all(active));
  std::vector<Active> closed;
  for (const auto& a : active)
    if (closes(a)) closed.push_back(a);
  const int n = static_cast<int>(closed.size());
  Values3 Fv("emc::closure_F", n), wn("emc::closure_wn", n), N1("emc::closure_N1", n);
  Kokkos::View<int*, ExecSpace> unrestorable("emc::closure_unrestorable", n);
  auto Fh = Kokkos::create_mirror_view(Fv);
  for (int k = 0; k < n; ++k)
    for (int c = 0; c < 3; ++c) Fh(k, c) = F.at(closed[k].slave)[c];
  Kokkos::deep_copy(Fv, Fh);
  const ClosureTerms terms = closure_terms(refs(closed), x0, x1, Fv, wn, N1, unrestorable);
  auto wh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), wn);
  auto Nh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), N1);
  std::vector<double> send;  // (dof, value) pairs of p
  for (int k = 0; k < n; ++k) {
    const auto& f = pairs_[closed[k].pair].facets[closed[k].facet];
    if (wh(k, 0) == 0 && wh(k, 1) == 0 && wh(k, 2) == 0) continue;
    for (int c = 0; c < 3; ++c) {
      send.insert(send.end(), {double(fem::dof_gid(closed[k].slave, c)), wh(k, c)});
      for (int i = 0; i < 3; ++i)
        if (f[i] < m.num_nodes() && !m.is_fixed(f[i]))
          send.insert(send.end(), {double(fem::dof_gid(f[i], c)), -Nh(k, i) * wh(k, c)});
    }
  }
  const auto all = allgather(*disc_.comm(), send);
  p.putScalar(0.0);
  auto pv = p.getLocalViewHost(Tpetra::Access::ReadWrite);
  const auto& map = *disc_.owned_map();
  for (std::size_t k = 0; k + 1 < all.size(); k += 2) {
    const LO l = map.getLocalElement(static_cast<GO>(all[k]));
    if (l != Tpetra::Details::OrdinalTraits<LO>::invalid()) pv(l, 0) += all[k + 1];
  }
  ClosureWork total;
  auto uh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), unrestorable);
  for (int k = 0; k < n; ++k)
    if (uh(k)) total.unrestorable.push_back(closed[k].slave);
  double sums[2] = {terms.work, terms.roundoff}, all_sums[2];
  Teuchos::reduceAll(*disc_.comm(), Teuchos::REDUCE_SUM, 2, sums, all_sums);
  total.work = all_sums[0];
  total.roundoff = all_sums[1];
  return total;
}

bool Contact::closes_gaps() const {
  return std::any_of(pairs_.begin(), pairs_.end(), [](const Pair& p) { return p.close_gap; });
}

}  // namespace emc::contact
