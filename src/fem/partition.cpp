#include "emcontact/fem/partition.hpp"

#include <algorithm>
#include <cstdint>
#include <numeric>

namespace emc::fem {

namespace {

/// Spreads the low 21 bits of v so that two zero bits separate consecutive bits.
std::uint64_t spread3(std::uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

std::vector<std::uint64_t> morton_keys(const Model& m) {
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (int n = 0; n < m.num_nodes(); ++n)
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], m.X[3 * n + i]);
      hi[i] = std::max(hi[i], m.X[3 * n + i]);
    }
  double ext = 0;
  for (int i = 0; i < 3; ++i) ext = std::max(ext, hi[i] - lo[i]);
  const double scale = ext > 0 ? ((1 << 21) - 1) / ext : 0;
  std::vector<std::uint64_t> key(m.num_tets());
  for (int e = 0; e < m.num_tets(); ++e) {
    std::uint64_t k = 0;
    for (int i = 0; i < 3; ++i) {
      double c = 0;
      for (int a = 0; a < 4; ++a) c += 0.25 * m.X[3 * m.tets[4 * e + a] + i];
      k |= spread3(static_cast<std::uint64_t>((c - lo[i]) * scale)) << i;
    }
    key[e] = k;
  }
  return key;
}

}  // namespace

Partition partition(const Model& m, int rank, int num_ranks) {
  const int ne = m.num_tets();
  const auto key = morton_keys(m);
  std::vector<int> order(ne);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return key[a] < key[b]; });

  Partition p;
  p.node_owner.assign(m.num_nodes(), -1);
  for (int r = num_ranks - 1; r >= 0; --r) {  // lowest rank wins: visit it last
    const long long b = static_cast<long long>(ne) * r / num_ranks;
    const long long e = static_cast<long long>(ne) * (r + 1) / num_ranks;
    for (long long k = b; k < e; ++k)
      for (int a = 0; a < 4; ++a) p.node_owner[m.tets[4 * order[k] + a]] = r;
  }
  const long long b = static_cast<long long>(ne) * rank / num_ranks;
  const long long e = static_cast<long long>(ne) * (rank + 1) / num_ranks;
  p.my_tets.assign(order.begin() + b, order.begin() + e);
  std::vector<int> used;
  used.reserve(4 * p.my_tets.size());
  for (int t : p.my_tets)
    for (int a = 0; a < 4; ++a) used.push_back(m.tets[4 * t + a]);
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  for (int n : used) (p.node_owner[n] == rank ? p.owned_nodes : p.shared_nodes).push_back(n);
  return p;
}

}  // namespace emc::fem
