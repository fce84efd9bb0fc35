#pragma once
// The colouring of the deterministic scatter (Solver/Assembly/scatter = coloured, docs/THEORY.md
// §9): the elements are cut into chunks of consecutive ids, and the chunks are coloured so that
// two chunks of one colour share no node. One parallel loop per colour, over its chunks, each
// chunk's elements in ascending order by one thread, then adds into every row with a plain `+=`,
// and each row sums its element contributions in the same order (colour by colour, element by
// element within a chunk) whatever the number of threads or their schedule. A chunk of 1 element
// is the plain element colouring; longer chunks keep the rows of neighbouring elements in cache.
#include "emcontact/fem/scatter.hpp"
#include "emcontact/types.hpp"

namespace emc::fem {

/// The chunks in colour order, for the kernels: the i-th is chunks(i), elements first(i) ..
/// last(i) - 1.
struct ChunkList {
  Kokkos::View<int*, ExecSpace> chunks;
  int chunk = 1;  ///< elements per chunk (the last chunk may be shorter)
  int num_elements = 0;

  KOKKOS_INLINE_FUNCTION int first(int i) const { return chunks(i) * chunk; }
  KOKKOS_INLINE_FUNCTION int last(int i) const {
    const int e = (chunks(i) + 1) * chunk;
    return e < num_elements ? e : num_elements;
  }
};

/// Chunks grouped by colour: colour c is list's chunks offsets(c) .. offsets(c + 1) - 1
/// (ascending chunk ids within a colour).
struct Colouring {
  ChunkList list;
  Kokkos::View<int*, Kokkos::HostSpace> offsets;  ///< colours + 1 entries, read on the host

  int colours() const {
    return offsets.extent(0) > 0 ? static_cast<int>(offsets.extent(0)) - 1 : 0;
  }
  int begin(int c) const { return offsets(c); }
  int end(int c) const { return offsets(c + 1); }
};

/// Greedy colouring of the chunk-node graph: the elements cut into chunks of `chunk`
/// consecutive ids, chunk j (ascending) takes the smallest colour that no chunk sharing a node
/// (`node_lid(k, .)` of its elements k) has taken. `num_nodes` bounds the node ids.
Colouring colour_chunks(const Kokkos::View<const int* [4], Kokkos::HostSpace>& node_lid,
                        int num_nodes, int chunk);

/// The chunk length of the assembly: measured against chunks of 1, 64, 256 and 2048 elements in
/// perf/README.md "OpenMP threads" (BM_Assembly).
constexpr int assembly_chunk = 512;

}  // namespace emc::fem
