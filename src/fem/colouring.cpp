// The greedy chunk colouring of the deterministic scatter (include/emcontact/fem/colouring.hpp).
#include "emcontact/fem/colouring.hpp"

#include <algorithm>
#include <type_traits>
#include <vector>

#include "emcontact/error.hpp"
#include "emcontact/types.hpp"

namespace emc::fem {

namespace {

constexpr bool serial_backend() {
#ifdef KOKKOS_ENABLE_SERIAL
  return std::is_same_v<ExecSpace, Kokkos::Serial>;
#else
  return false;
#endif
}

}  // namespace

Scatter resolve_scatter(ScatterChoice choice) {
  // auto: atomic adds in the Serial backend, where they are plain adds in loop order
  // (reproducible, and faster: perf/README.md "OpenMP threads"); the coloured loops on a threaded
  // backend, where threads would reorder the adds and where an atomic add stays a locked
  // instruction even on one thread (3-4x slower than the coloured loops there)
  if (choice == ScatterChoice::automatic)
    return serial_backend() ? Scatter::atomic : Scatter::coloured;
  return choice == ScatterChoice::coloured ? Scatter::coloured : Scatter::atomic;
}

namespace {

/// The chunks touching every node (CSR: those of node n are at[start[n] .. start[n+1]), each
/// once, ascending).
void node_chunks(const Kokkos::View<const int* [4], Kokkos::HostSpace>& lid, int num_nodes,
                 int chunk, std::vector<int>& start, std::vector<int>& at) {
  const int ne = static_cast<int>(lid.extent(0));
  std::vector<int> last(num_nodes, -1);  // the last chunk counted at a node
  start.assign(num_nodes + 1, 0);
  for (int k = 0; k < ne; ++k)
    for (int a = 0; a < 4; ++a)
      if (last[lid(k, a)] != k / chunk) {
        last[lid(k, a)] = k / chunk;
        ++start[lid(k, a) + 1];
      }
  for (int n = 0; n < num_nodes; ++n) start[n + 1] += start[n];
  at.resize(start[num_nodes]);
  std::vector<int> next(start.begin(), start.end() - 1);
  std::fill(last.begin(), last.end(), -1);
  for (int k = 0; k < ne; ++k)
    for (int a = 0; a < 4; ++a)
      if (last[lid(k, a)] != k / chunk) {
        last[lid(k, a)] = k / chunk;
        at[next[lid(k, a)]++] = k / chunk;
      }
}

/// Colour per chunk, greedy in ascending chunk order; `colours` in all.
std::vector<int> greedy(const Kokkos::View<const int* [4], Kokkos::HostSpace>& lid, int num_nodes,
                        int chunk, int& colours) {
  std::vector<int> start, at;
  node_chunks(lid, num_nodes, chunk, start, at);
  const int ne = static_cast<int>(lid.extent(0));
  const int nc = (ne + chunk - 1) / chunk;
  std::vector<int> colour(nc, -1), taken;  // taken[c] == j: a neighbour of chunk j has colour c
  colours = 0;
  for (int j = 0; j < nc; ++j) {
    for (int k = j * chunk; k < std::min(ne, (j + 1) * chunk); ++k)
      for (int a = 0; a < 4; ++a) {
        const int n = lid(k, a);
        for (int i = start[n]; i < start[n + 1]; ++i)
          if (colour[at[i]] >= 0) taken[colour[at[i]]] = j;
      }
    int c = 0;
    while (c < colours && taken[c] == j) ++c;
    if (c == colours) {
      taken.push_back(-1);
      ++colours;
    }
    colour[j] = c;
  }
  return colour;
}

}  // namespace

Colouring colour_chunks(const Kokkos::View<const int* [4], Kokkos::HostSpace>& node_lid,
                        int num_nodes, int chunk) {
  if (chunk < 1) throw Error("internal: colour chunk " + std::to_string(chunk) + " < 1");
  int colours = 0;
  const std::vector<int> colour = greedy(node_lid, num_nodes, chunk, colours);
  Colouring out;
  out.list.chunk = chunk;
  out.list.num_elements = static_cast<int>(node_lid.extent(0));
  out.offsets = decltype(out.offsets)("emc::colour_offsets", colours + 1);
  for (int c : colour) ++out.offsets(c + 1);
  for (int c = 0; c < colours; ++c) out.offsets(c + 1) += out.offsets(c);
  auto& chunks = out.list.chunks;
  chunks = Kokkos::View<int*, ExecSpace>("emc::colour_chunks", colour.size());
  auto h = Kokkos::create_mirror_view(chunks);
  std::vector<int> next(colours);
  for (int c = 0; c < colours; ++c) next[c] = out.offsets(c);
  for (std::size_t j = 0; j < colour.size(); ++j) h(next[colour[j]]++) = static_cast<int>(j);
  Kokkos::deep_copy(chunks, h);
  return out;
}

}  // namespace emc::fem
