#pragma once
// Small collective helpers shared by the modules.
#include <vector>

#include "emcontact/types.hpp"

namespace emc {

/// Every rank's doubles, concatenated in rank order, on every rank (MPI_Allgatherv).
std::vector<double> allgather(const Comm& comm, const std::vector<double>& mine);

}  // namespace emc
