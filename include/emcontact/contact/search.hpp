#pragma once
// Contact search (ALGORITHM.md §2): a uniform grid of the master facets' bounding boxes
// (expanded by a margin), rebuilt from the current positions whenever it is needed, and the
// projection of a point on the closest valid facet among the candidates of its cell.
#include <Kokkos_Core.hpp>
#include <array>
#include <vector>

#include "kernels/facet.hpp"

namespace emc::contact {

struct Hit {
  int facet = -1;
  double xi[2] = {0, 0};
  double gap = 0;
  bool inside = false;  ///< CPP inside the facet (up to the tolerance asked)
};

class FacetGrid {
 public:
  /// Bins the facets (geometry node ids into x, 3 per node) with their boxes grown by margin.
  FacetGrid(const std::vector<std::array<int, 3>>& facets, const std::vector<double>& x,
            double margin);

  /// The closest valid facet to y (§2): among the candidates whose CPP lies inside up to
  /// 1e-9, the smallest |g_N|, ties to the lowest facet id. If `current` >= 0 it is kept while
  /// its CPP is inside up to `hyst`. If none is valid and `current` >= 0, the candidate least
  /// outside is returned with inside = (outside <= hyst); otherwise facet = -1.
  Hit locate(const double y[3], int current = -1, double hyst = 0) const;

  /// locate(y_k) for n points (3 coordinates each): hits[k] for point k, the same bits, but
  /// visited in the Morton order of their grid cells (a radix sort), so that
  /// consecutive queries read the same cell lists and facet records, as tree searches sort
  /// their queries (ArborX). For many queries in no particular order.
  void locate_all(const double* y, std::size_t n, std::vector<Hit>& hits) const;

  std::size_t num_cells() const { return cell_start_.extent(0) - 1; }

  /// Calls fn(hit, outside) for every facet whose grown box holds y, with its CPP (hit.gap,
  /// hit.xi) and kernels::facet_outside(hit.xi); degenerate facets are skipped. Facets come in
  /// increasing id order.
  template <class F>
  void for_each_candidate(const double y[3], F&& fn) const {
    int d[3];
    const int c = cell_of(y, d);
    if (c < 0) return;
    for (int k = cell_start_(c); k < cell_start_(c + 1); ++k) {
      const int f = cell_facets_(k);
      const double* b = data_[f].box;
      if (y[0] < b[0] || y[0] > b[3] || y[1] < b[1] || y[1] > b[4] || y[2] < b[2] || y[2] > b[5])
        continue;
      Hit h;
      if (cpp(f, y, h)) fn(h, kernels::facet_outside(h.xi));
    }
  }

  /// The frame and metric of facet f in the grid's configuration.
  const kernels::FacetMetric& metric(int f) const { return data_[f].metric; }

 private:
  const std::vector<std::array<int, 3>>& facets_;
  const std::vector<double>& x_;
  double lo_[3], h_;
  int dims_[3];
  Kokkos::View<int*, Kokkos::HostSpace> cell_start_, cell_facets_;
  /// Per facet, in one record (one cache-friendly read per candidate): the grown bounding box
  /// and what the CPP of §2 needs, computed once per grid: the nodes, tau_xi, tau_eta, n and
  /// the 2x2 metric (g11, g12, g22, det), so that cpp() gives kernels::facet_cpp's bits.
  struct FacetData {
    double box[6];
    double xm[3][3];
    kernels::FacetMetric metric;
  };
  std::vector<FacetData> data_;
  void precompute(int f, double margin);

  int cell_of(const double y[3], int d[3]) const;
  bool cpp(int f, const double y[3], Hit& h) const;
};

}  // namespace emc::contact
