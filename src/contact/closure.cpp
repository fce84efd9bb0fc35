// docs/THEORY.md §7: active nodes closed onto their master at t_{n+1} (`close gap`), and the
// work of the contact forces that the closure makes nonzero, for the velocity update that
// gives it back.
#include <Teuchos_CommHelpers.hpp>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>

#include "emcontact/contact/contact.hpp"
#include "emcontact/parallel.hpp"
#include "kernels/facet.hpp"

namespace emc::contact {

// §7.2: a closing full-stick slave starts Newton at x_{s,n+1} = N x_{m,n+1}; du_s = N du_m
// keeps it there. A master node that is a closing slave itself (a chain) moves in one sweep
// and its own slaves follow in the next.
void Contact::close_stick(const std::vector<Active>& active, Vector& u1) const {
  const auto& m = disc_.model();
  const auto& map = *disc_.owned_map();
  for (int sweep = 0; sweep < 8; ++sweep) {
    const auto x1 = positions(m, replicate(u1));
    auto uv = u1.getLocalViewHost(Tpetra::Access::ReadWrite);
    double moved = 0;  // in units of the facet size
    for (const auto& a : active) {
      const Pair& pr = pairs_[a.pair];
      if (pr.kind != Kind::full_stick || !closes(a) || m.fixed[a.slave]) continue;
      double xm[3][3], N[3];
      facet_coords(a, x1, xm);
      kernels::facet_shape(a.xi, N);
      for (int c = 0; c < 3; ++c) {
        const double target = N[0] * xm[0][c] + N[1] * xm[1][c] + N[2] * xm[2][c];
        moved = std::max(moved, std::fabs(target - x1[3 * a.slave + c]) / pr.edge);
        uv(map.getLocalElement(fem::dof_gid(a.slave, c)), 0) = target - m.X[3 * a.slave + c];
      }
    }
    double all = 0;
    Teuchos::reduceAll(*disc_.comm(), Teuchos::REDUCE_MAX, 1, &moved, &all);
    if (all <= 1e-13) break;  // round-off: every slave already sat on its master point
  }
}

// §7.4: W_c = sum_e F_e . ((x_{s,n+1} - x_{s,n}) - N (x_{m,n+1} - x_{m,n})) over the active
// entries of closing pairs, and p: +w_e n_e on the slave, -w_e N'_i n_e on its free master
// nodes, w_e = max(F_e . n_e, 0), n_e and N' the facet's normal and the slave's CPP at t_{n+1}.
ClosureWork Contact::closure_work(const Vector& g, const std::vector<double>& x0,
                                  const std::vector<double>& x1, const std::vector<Active>& active,
                                  Vector& p) const {
  const auto& m = disc_.model();
  const auto F = transmitted_forces(g, gather(active));
  double sums[2] = {0, 0};   // W_c and its round-off
  std::vector<double> send;  // (dof, value) pairs of p
  for (const auto& a : active) {
    const Pair& pr = pairs_[a.pair];
    if (!closes(a)) continue;
    const auto& f = pr.facets[a.facet];
    const auto& Fe = F.at(a.slave);
    double xm0[3][3], xm1[3][3], N[3];
    facet_coords(a, x0, xm0);
    facet_coords(a, x1, xm1);
    kernels::facet_shape(a.xi, N);
    for (int c = 0; c < 3; ++c) {
      double rel = x1[3 * a.slave + c] - x0[3 * a.slave + c];
      for (int i = 0; i < 3; ++i) rel -= N[i] * (xm1[i][c] - xm0[i][c]);
      sums[0] += Fe[c] * rel;
    }
    // what closing a gap at the round-off of the coordinates moves: W_c below the sum of these
    // is no energy to give back (nodes deeper keep their gap, §7.2)
    sums[1] += (std::fabs(Fe[0]) + std::fabs(Fe[1]) + std::fabs(Fe[2])) *
               gap_roundoff(pr, &x1[3 * a.slave]);
    double xi1[2], gap;
    if (!kernels::facet_cpp(&x1[3 * a.slave], xm1, xi1, gap)) continue;
    const kernels::Facet f1 = kernels::facet(xm1);
    const double w = std::max(0.0, Fe[0] * f1.n[0] + Fe[1] * f1.n[1] + Fe[2] * f1.n[2]);
    if (w == 0) continue;
    double N1[3];
    kernels::facet_shape(xi1, N1);
    for (int c = 0; c < 3; ++c) {
      send.insert(send.end(), {double(fem::dof_gid(a.slave, c)), w * f1.n[c]});
      for (int i = 0; i < 3; ++i)
        if (f[i] < m.num_nodes() && !m.fixed[f[i]])
          send.insert(send.end(), {double(fem::dof_gid(f[i], c)), -w * N1[i] * f1.n[c]});
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
  double all_sums[2];
  Teuchos::reduceAll(*disc_.comm(), Teuchos::REDUCE_SUM, 2, sums, all_sums);
  total.work = all_sums[0];
  total.roundoff = all_sums[1];
  return total;
}

bool Contact::closes_gaps() const {
  return std::any_of(pairs_.begin(), pairs_.end(), [](const Pair& p) { return p.close_gap; });
}

}  // namespace emc::contact
