#pragma once
// How the element loops add into shared rows (input `Solver/Assembly/scatter`).
namespace emc::fem {

/// coloured: one loop per element colour with plain adds, reproducible bit for bit with any
/// number of threads; atomic: one loop with atomic adds, whose order varies between threaded
/// runs (include/emcontact/fem/colouring.hpp).
enum class Scatter { coloured, atomic };

/// The values of `Solver/Assembly/scatter` (its validator's, Teuchos::getIntegralValue).
enum class ScatterChoice { automatic, coloured, atomic };

/// The scatter of a choice: `automatic` is coloured if Kokkos runs more than one thread, else
/// atomic.
Scatter resolve_scatter(ScatterChoice choice);

}  // namespace emc::fem
