#pragma once
// P of the elimination (docs/THEORY.md §3.1) as a local CRS matrix built by Kokkos loops over
// the owned rows: e_i on a plain row, nothing on a fixed row, the weights of a special row. Only
// the special rows (the active slaves' dofs) pass through the host.
#include <Teuchos_RCP.hpp>
#include <vector>

#include "emcontact/linalg/structured_reduction.hpp"
#include "emcontact/types.hpp"

namespace emc::linalg {

/// P over `owned` (rows, domain and range). Its column map is `owned` followed, where some
/// rank's special rows have columns owned elsewhere, by those columns (sorted). A column met
/// twice in a special row (through two chains) adds its weights. Collective.
Teuchos::RCP<Matrix> make_P(const Teuchos::RCP<const Map>& owned, const std::vector<GO>& fixed,
                            const std::vector<PRow>& rows);

/// Rewrites the values of P's special rows in place (their columns must be in P's graph, as
/// when P was made from rows with the same columns). Local: no communication.
void write_P_rows(Matrix& P, const std::vector<PRow>& rows);

}  // namespace emc::linalg
