#include "emcontact/contact/contact.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <set>

#include "emcontact/contact/search.hpp"
#include "kernels/facet.hpp"

namespace emc::contact {

using Teuchos::rcp;

Contact::Contact(const fem::Discretization& disc, std::vector<Pair> pairs)
    : disc_(disc), pairs_(std::move(pairs)) {
  const int rank = disc_.comm()->getRank();
  for (const auto& p : pairs_) {
    my_slaves_.emplace_back();
    for (int s : p.slaves)
      if (disc_.part().node_owner[s] == rank) my_slaves_.back().push_back(s);
  }
  if (pairs_.empty()) return;
  const GO n = 3LL * disc_.model().num_nodes();
  all_ = rcp(new Map(n, 0, disc_.comm(), Tpetra::LocallyReplicated));
  to_all_ = rcp(new Import(disc_.owned_map(), all_));
}

std::vector<double> Contact::replicate(const Vector& u) const {
  Vector all(all_);
  all.doImport(u, *to_all_, Tpetra::INSERT);
  auto h = all.getLocalViewHost(Tpetra::Access::ReadOnly);
  return std::vector<double>(h.data(), h.data() + h.extent(0));
}

int Contact::global_count(int local) const {
  int g = 0;
  Teuchos::reduceAll(*disc_.comm(), Teuchos::REDUCE_SUM, 1, &local, &g);
  return g;
}

void Contact::facet_coords(const Active& a, const std::vector<double>& x, double xm[3][3]) const {
  const auto& f = pairs_[a.pair].facets[a.facet];
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 3; ++i) xm[k][i] = x[3 * f[k] + i];
}

// ALGORITHM.md §6.3 with §4: activation at the end-of-step position, xi from the CPP at t_n.
std::vector<Active> Contact::detect(const std::vector<double>& x0, const std::vector<double>& x1,
                                    const std::vector<Active>& active) const {
  std::set<int> busy;
  for (const auto& a : active) busy.insert(a.slave);
  std::vector<Active> found;
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    const Pair& pr = pairs_[p];
    const auto& mine = my_slaves_[p];
    if (mine.empty()) continue;
    const FacetGrid grid1(pr.facets, x1, pr.dmax);
    const FacetGrid grid0(pr.facets, x0, pr.dmax);
    const int ns = static_cast<int>(mine.size());
    std::vector<Active> hit(ns);
    Kokkos::parallel_for(
        "emcontact::contact::detect", Kokkos::RangePolicy<Kokkos::DefaultHostExecutionSpace>(0, ns),
        [&, p](const int k) {
          const int s = mine[k];
          if (busy.count(s)) return;
          const Hit h1 = grid1.locate(&x1[3 * s]);
          if (h1.facet < 0 || !(h1.gap < 0 && h1.gap > -pr.dmax)) return;
          const Hit h0 = grid0.locate(&x0[3 * s], h1.facet, 1e-3);
          hit[k] = Active{s, static_cast<int>(p), h0.facet, {h0.xi[0], h0.xi[1]}};
        });
    for (const auto& a : hit)
      if (a.slave >= 0) {
        found.push_back(a);
        busy.insert(a.slave);  // a node in two pairs is taken by the first
      }
  }
  return found;
}

std::vector<double> Contact::normal_forces(const Vector& g, const std::vector<double>& x0,
                                           const std::vector<double>& x1,
                                           const std::vector<Active>& active) const {
  auto gv = g.getLocalViewHost(Tpetra::Access::ReadOnly);
  const auto& map = *disc_.owned_map();
  std::vector<double> fN(active.size());
  for (std::size_t k = 0; k < active.size(); ++k) {
    const Active& a = active[k];
    double xm0[3][3], xm1[3][3], xh[3][3];
    facet_coords(a, x0, xm0);
    facet_coords(a, x1, xm1);
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) xh[j][i] = 0.5 * (xm0[j][i] + xm1[j][i]);
    const kernels::Facet f = kernels::facet(xh);
    double s = 0;
    for (int i = 0; i < 3; ++i) s += gv(map.getLocalElement(fem::dof_gid(a.slave, i)), 0) * f.n[i];
    fN[k] = s;
  }
  return fN;
}

// ALGORITHM.md §3-§4: du_s = N du_m; the slave's own column of P is zero (three dummies).
void Contact::constraint_rows(const std::vector<Active>& active, std::vector<linalg::PRow>& rows,
                              std::vector<GO>& dummies) const {
  const auto& m = disc_.model();
  for (const auto& a : active) {
    const auto& f = pairs_[a.pair].facets[a.facet];
    double N[3];
    kernels::facet_shape(a.xi, N);
    for (int c = 0; c < 3; ++c) {
      linalg::PRow r;
      r.row = fem::dof_gid(a.slave, c);
      for (int k = 0; k < 3; ++k)
        if (f[k] < m.num_nodes() && !m.fixed[f[k]]) {  // rigid or fixed master: no column
          r.cols.push_back(fem::dof_gid(f[k], c));
          r.weights.push_back(N[k]);
        }
      rows.push_back(std::move(r));
      dummies.push_back(fem::dof_gid(a.slave, c));
    }
  }
}

std::vector<std::pair<GO, double>> Contact::dummy_values(const Matrix& A,
                                                         const std::vector<GO>& dummies) const {
  Vector d(A.getRowMap());
  A.getLocalDiagCopy(d);
  auto h = d.getLocalViewHost(Tpetra::Access::ReadOnly);
  const auto& map = *A.getRowMap();
  std::vector<std::pair<GO, double>> out;
  for (std::size_t k = 0; k + 2 < dummies.size(); k += 3) {  // a slave's three dofs in a row
    double tr = 0;
    for (int c = 0; c < 3; ++c) tr += h(map.getLocalElement(dummies[k + c]), 0);
    for (int c = 0; c < 3; ++c) out.emplace_back(dummies[k + c], tr / 3);
  }
  return out;
}

void Contact::gap_range(const std::vector<double>& x1, const std::vector<Active>& active,
                        double& lo, double& hi) const {
  double l = 1e300, h = -1e300;
  for (const auto& a : active) {
    double xm[3][3], xi[2], gap;
    facet_coords(a, x1, xm);
    kernels::facet_cpp(&x1[3 * a.slave], xm, xi, gap);
    l = std::min(l, gap);
    h = std::max(h, gap);
  }
  Teuchos::reduceAll(*disc_.comm(), Teuchos::REDUCE_MIN, 1, &l, &lo);
  Teuchos::reduceAll(*disc_.comm(), Teuchos::REDUCE_MAX, 1, &h, &hi);
}

}  // namespace emc::contact
