// The force an active slave transmits to its master facet along chains (docs/THEORY.md §3.5:
// P = P_1 P_2 ...): its own contactless residual plus what its own slaves transmit to it.
#include <set>

#include "emcontact/contact/contact.hpp"
#include "emcontact/parallel.hpp"
#include "kernels/facet.hpp"

namespace emc::contact {

namespace {

struct Transmitted {
  const std::map<int, std::array<double, 3>>& g;               // g_s of every active slave
  std::map<int, std::vector<std::pair<int, double>>> carried;  // node -> (its slave, N_i)
  std::map<int, std::array<double, 3>> memo;
  std::set<int> visiting;

  std::array<double, 3> operator()(int s) {
    auto it = memo.find(s);
    if (it != memo.end()) return it->second;
    std::array<double, 3> F = g.at(s);
    if (!visiting.insert(s).second) return F;  // a cycle (cut in P too): stop here
    auto c = carried.find(s);
    if (c != carried.end())
      for (const auto& [slave, w] : c->second) {
        const auto f = (*this)(slave);
        for (int i = 0; i < 3; ++i) F[i] += w * f[i];
      }
    visiting.erase(s);
    return memo[s] = F;
  }
};

}  // namespace

// g_s of every entry of the index, from the rank that owns its slave (collective).
std::map<int, std::array<double, 3>> Contact::active_residuals(const Vector& g,
                                                               const ActiveIndex& index) const {
  const int rank = disc_.comm()->getRank();
  const auto& map = *disc_.owned_map();
  auto gv = g.getLocalViewHost(Tpetra::Access::ReadOnly);
  std::vector<double> send;
  for (const auto& [s, a] : index.by_slave)
    if (disc_.part().owner(disc_.model(), s) == rank) {
      send.push_back(s);
      for (int c = 0; c < 3; ++c) send.push_back(gv(map.getLocalElement(fem::dof_gid(s, c)), 0));
    }
  const auto all = allgather(*disc_.comm(), send);
  std::map<int, std::array<double, 3>> out;
  for (std::size_t k = 0; k + 3 < all.size(); k += 4)
    out[static_cast<int>(all[k])] = {all[k + 1], all[k + 2], all[k + 3]};
  return out;
}

std::map<int, std::array<double, 3>> Contact::transmitted_forces(const Vector& g,
                                                                 const ActiveIndex& index) const {
  const auto& m = disc_.model();
  const auto all = active_residuals(g, index);
  Transmitted F{all, {}, {}, {}};
  for (const auto& [s, a] : index.by_slave) {
    const auto& f = pairs_[a.pair].facets[a.facet];
    double N[3];
    kernels::facet_shape(a.xi, N);
    for (int i = 0; i < 3; ++i)
      if (f[i] < m.num_nodes()) F.carried[f[i]].emplace_back(s, N[i]);
  }
  std::map<int, std::array<double, 3>> out;
  for (const auto& [s, a] : index.by_slave) out[s] = F(s);
  return out;
}

}  // namespace emc::contact
