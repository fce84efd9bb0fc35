#pragma once
// P^T A P + D when P is diagonal with entries 0 or 1 (docs/THEORY.md §3.6: fixed dofs, and full
// stick against rigid masters, whose slave rows of P are empty): the entries of A in a
// constrained row or column are zeroed and D is added on the diagonal, on a copy of A's graph
// made once. No sparse products; the result is exactly the triple product's (products with
// 1 and 0 are exact), with explicit zeros where the product would leave no entry.
#include <Teuchos_RCP.hpp>
#include <vector>

#include "emcontact/types.hpp"

namespace emc::linalg {

/// 1 on the owned dofs whose row of P is e_i (kept), 0 on the `constrained` ones (fixed dofs and
/// the rows of active slaves).
Teuchos::RCP<Vector> keep_vector(const Teuchos::RCP<const Map>& owned,
                                 const std::vector<GO>& constrained);
/// `keep` on A's column map (through A's importer).
Vector keep_on_columns(const Vector& keep, const Matrix& A);

class MaskedReduction {
 public:
  /// `keep`: 1 on the owned dofs P keeps, 0 on the constrained ones (when P changes).
  void set_keep(Teuchos::RCP<const Vector> keep);
  /// `d`: D's diagonal (when beta changes).
  void set_diagonal(Teuchos::RCP<const Vector> d) { d_ = std::move(d); }
  /// P^T A P + D, a new matrix on the saved copy of A's graph (collective).
  Teuchos::RCP<Matrix> apply(const Matrix& A);

 private:
  Teuchos::RCP<const Vector> keep_, d_;
  Teuchos::RCP<const Graph> graph_;            ///< copy of A's graph, made once
  Teuchos::RCP<const Map> col_map_;            ///< A's column map it was made for
  Kokkos::View<double*, ExecSpace> keep_col_;  ///< keep on A's local columns
  Kokkos::View<long*, ExecSpace> diag_pos_;    ///< per row, its diagonal entry (or -1)
  bool keep_col_stale_ = true;
  void copy_graph(const Matrix& A);
  void import_keep(const Matrix& A);
};

}  // namespace emc::linalg
