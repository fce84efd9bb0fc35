#pragma once
// How the element loops add into shared rows (input `Solver/Assembly/scatter`).
#include <string>

namespace emc::fem {

/// coloured: one loop per element colour with plain adds, reproducible bit for bit with any
/// number of threads; atomic: one loop with atomic adds, whose order varies between threaded
/// runs (include/emcontact/fem/colouring.hpp).
enum class Scatter { coloured, atomic };

/// `coloured` or `atomic`; anything else throws an InputError naming the parameter.
Scatter parse_scatter(const std::string& value);

}  // namespace emc::fem
