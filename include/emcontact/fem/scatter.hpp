#pragma once
// How the element loops add into shared rows (input `Solver/Assembly/scatter`).
namespace emc::fem {

/// coloured: one loop per element colour with plain adds, reproducible bit for bit with any
/// number of threads; atomic: one loop with atomic adds, whose order varies between threaded
/// runs (kernels::TetColouring, kernels/tet4_loops.hpp).
enum class Scatter { coloured, atomic };

/// The values of `Solver/Assembly/scatter` (its validator's, Teuchos::getIntegralValue).
enum class ScatterChoice { automatic, coloured, atomic };

/// The scatter of a choice: `automatic` is coloured if Kokkos runs more than one thread, else
/// atomic.
Scatter resolve_scatter(ScatterChoice choice);

/// The chunk length of the coloured loops: measured against chunks of 1, 64, 256 and 2048
/// elements in perf/README.md "OpenMP threads" (BM_Assembly).
constexpr int assembly_chunk = 512;

}  // namespace emc::fem
