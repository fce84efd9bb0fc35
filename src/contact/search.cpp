#include "emcontact/contact/search.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "kernels/facet.hpp"

namespace emc::contact {

// The record of facet f: grown box, nodes and the CPP's metric (ALGORITHM.md §2).
void FacetGrid::precompute(int f, double margin) {
  FacetData& d = data_[f];
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i < 3; ++i) d.xm[a][i] = x_[3 * facets_[f][a] + i];
  d.metric = kernels::facet_metric(d.xm);
  for (int i = 0; i < 3; ++i) {
    d.box[i] = std::min({d.xm[0][i], d.xm[1][i], d.xm[2][i]}) - margin;
    d.box[3 + i] = std::max({d.xm[0][i], d.xm[1][i], d.xm[2][i]}) + margin;
  }
}

FacetGrid::FacetGrid(const std::vector<std::array<int, 3>>& facets, const std::vector<double>& x,
                     double margin)
    : facets_(facets), x_(x) {
  const int nf = static_cast<int>(facets.size());
  data_.resize(nf);
  double hi[3] = {-1e300, -1e300, -1e300}, ext_sum = 0;
  for (int i = 0; i < 3; ++i) lo_[i] = 1e300;
  for (int f = 0; f < nf; ++f) {
    precompute(f, margin);
    const double* b = data_[f].box;
    for (int i = 0; i < 3; ++i) {
      ext_sum += b[3 + i] - b[i] - 2 * margin;
      lo_[i] = std::min(lo_[i], b[i]);
      hi[i] = std::max(hi[i], b[3 + i]);
    }
  }
  // cells about the mean facet extent, at most 128 per direction
  double h = nf ? std::max(ext_sum / (3.0 * nf), 1e-12) + 2 * margin : 1.0;
  for (int i = 0; i < 3; ++i) h = std::max(h, (hi[i] - lo_[i]) / 128.0);
  h_ = h;
  for (int i = 0; i < 3; ++i) dims_[i] = nf ? std::max(1, int(std::ceil((hi[i] - lo_[i]) / h))) : 1;
  const std::size_t ncell = std::size_t(dims_[0]) * dims_[1] * dims_[2];
  // CSR: count, prefix sum, fill in facet order (so every cell's list is sorted by facet id)
  std::vector<int> count(ncell + 1, 0);
  auto range = [&](int f, int i, int& a, int& b) {
    a = std::clamp(int(std::floor((data_[f].box[i] - lo_[i]) / h_)), 0, dims_[i] - 1);
    b = std::clamp(int(std::floor((data_[f].box[3 + i] - lo_[i]) / h_)), 0, dims_[i] - 1);
  };
  auto visit = [&](int f, auto&& fn) {
    int a[3], b[3];
    for (int i = 0; i < 3; ++i) range(f, i, a[i], b[i]);
    for (int k = a[2]; k <= b[2]; ++k)
      for (int j = a[1]; j <= b[1]; ++j)
        for (int i = a[0]; i <= b[0]; ++i) fn((std::size_t(k) * dims_[1] + j) * dims_[0] + i);
  };
  for (int f = 0; f < nf; ++f) visit(f, [&](std::size_t c) { ++count[c + 1]; });
  for (std::size_t c = 0; c < ncell; ++c) count[c + 1] += count[c];
  cell_start_ = Kokkos::View<int*, Kokkos::HostSpace>("emc::grid_start", ncell + 1);
  cell_facets_ = Kokkos::View<int*, Kokkos::HostSpace>("emc::grid_facets", count[ncell]);
  for (std::size_t c = 0; c <= ncell; ++c) cell_start_(c) = count[c];
  std::vector<int> fill(count.begin(), count.end() - 1);
  for (int f = 0; f < nf; ++f) visit(f, [&](std::size_t c) { cell_facets_(fill[c]++) = f; });
}

int FacetGrid::cell_of(const double y[3], int d[3]) const {
  for (int i = 0; i < 3; ++i) {
    const double t = std::floor((y[i] - lo_[i]) / h_);
    if (!(t >= 0 && t < dims_[i])) return -1;
    d[i] = int(t);
  }
  return (d[2] * dims_[1] + d[1]) * dims_[0] + d[0];
}

// kernels::facet_cpp with the facet's metric computed once.
bool FacetGrid::cpp(int f, const double y[3], Hit& h) const {
  h.facet = f;
  return kernels::facet_cpp(y, data_[f].xm, data_[f].metric, h.xi, h.gap);
}

// ALGORITHM.md §2 (choice of facet) and §5 step 2 (keep the current facet up to hyst).
Hit FacetGrid::locate(const double y[3], int current, double hyst) const {
  const double tol = 1e-9;
  if (current >= 0) {
    Hit h;
    if (cpp(current, y, h) && kernels::facet_outside(h.xi) <= std::max(hyst, tol)) {
      h.inside = true;
      return h;
    }
  }
  Hit best, least;
  double least_out = 1e300;
  for_each_candidate(y, [&](const Hit& h, double out) {
    if (out <= tol && (best.facet < 0 || std::fabs(h.gap) < std::fabs(best.gap) - 1e-14 * h_)) {
      best = h;
      best.inside = true;
    }
    if (out < least_out) {
      least_out = out;
      least = h;
    }
  });
  if (best.facet >= 0 || current < 0) return best;
  if (least.facet < 0) {  // nothing near: keep the current facet, extrapolated
    cpp(current, y, least);
    least_out = kernels::facet_outside(least.xi);
  }
  least.inside = least_out <= hyst;
  return least;
}

}  // namespace emc::contact

namespace emc::contact {

// ALGORITHM.md §2 for each point (locate), in an order that reuses the cache.
void FacetGrid::locate_all(const double* y, std::size_t n, std::vector<Hit>& hits) const {
  hits.assign(n, Hit{});
  // keys: the Morton code of the cell (at most 128 = 2^7 cells per direction: 21 bits),
  // points outside the grid last; two 11-bit passes
  auto spread = [](std::uint32_t v) {  // bit b of v to bit 3b
    std::uint32_t r = 0;
    for (int b = 0; b < 7; ++b) r |= ((v >> b) & 1u) << (3 * b);
    return r;
  };
  const std::uint32_t outside = 1u << 21;
  std::vector<std::uint32_t> key(n), order(n), next(n);
  for (std::size_t k = 0; k < n; ++k) {
    int d[3];
    const int c = cell_of(&y[3 * k], d);
    key[k] = c < 0 ? outside : spread(d[0]) | spread(d[1]) << 1 | spread(d[2]) << 2;
    order[k] = static_cast<std::uint32_t>(k);
  }
  for (int shift = 0; shift < 22; shift += 11) {  // LSD radix sort, stable
    std::vector<std::size_t> start(2049, 0);
    for (std::size_t k = 0; k < n; ++k) ++start[((key[order[k]] >> shift) & 2047) + 1];
    for (int b = 0; b < 2048; ++b) start[b + 1] += start[b];
    for (std::size_t k = 0; k < n; ++k) next[start[(key[order[k]] >> shift) & 2047]++] = order[k];
    order.swap(next);
  }
  for (std::uint32_t k : order) hits[k] = locate(&y[3 * k]);
}

}  // namespace emc::contact
