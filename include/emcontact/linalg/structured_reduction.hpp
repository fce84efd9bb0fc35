#pragma once
// P^T A Pt + X + D when P and Pt are the identity outside a few rows (docs/THEORY.md §3.6, §5.4:
// the active slaves' rows, fixed dofs' empty rows). Every entry A_ij contributes
// P_ki A_ij Pt_jl to (k, l) for the entries of P's row i and Pt's row j; a plain row is the
// single entry (i, 1). Which (A entry, weight, weight) lands on which position of the reduced
// matrix is worked out once per pattern (A's graph, the constrained rows' columns, X's
// entries); while the pattern holds (Newton iterations of one active set), each reduction is
// one pass over those contributions into an FECrsMatrix on a graph built once, whose rows
// owned elsewhere (a master dof of another rank) are exported like assembled ones.
#include <Teuchos_RCP.hpp>
#include <utility>
#include <vector>

#include "emcontact/linalg/masked_reduction.hpp"
#include "emcontact/types.hpp"

namespace emc::linalg {

/// One row block of P: owned dof `row` gets du_row = sum_k weight_k dq_{col_k}.
struct PRow {
  GO row;
  std::vector<GO> cols;
  std::vector<double> weights;
};

/// One entry of the variation X of P^T (docs/THEORY.md §5.4); its row may be owned elsewhere.
struct Entry {
  GO row, col;
  double value;
};

/// A row of P or Pt as a range of flat arrays (whose index 0 holds the weight 1 of a plain row).
struct RowSpan {
  int begin = 0, end = 0;
};

/// Sorts (row, column) pairs and drops repeats (the entries a new graph needs).
void sort_unique_entries(std::vector<std::pair<GO, GO>>& v);

class StructuredReduction {
 public:
  /// The constraints of one iterate. `keep`: 1 on the owned dofs whose rows of P and Pt are
  /// e_i (keep_vector); `fixed`: owned dofs whose row of P (and Pt) is empty;
  /// `p_rows`, `pt_rows`: owned special rows of P and Pt (the same set of rows); `X`: entries
  /// anywhere; `diag`: D on owned dofs. Collective (Pt's rows are gathered on every rank).
  void set(Teuchos::RCP<const Vector> keep, const std::vector<GO>& fixed,
           const std::vector<PRow>& p_rows, const std::vector<PRow>& pt_rows,
           const std::vector<Entry>& X, const std::vector<std::pair<GO, double>>& diag,
           const Comm& comm);
  /// P^T A Pt + X + D (collective). The same matrix object is refilled while the pattern
  /// holds, so it is valid until the next call.
  Teuchos::RCP<Matrix> apply(const Matrix& A);
  /// Times the pattern was (re)built, for tests.
  int builds() const { return builds_; }
  /// Times the result's graph was built (fewer than builds() with keep_graph).
  int graph_builds() const { return graph_builds_; }
  /// Keep the result's graph across patterns (docs/THEORY.md §3.6): it then holds A's whole
  /// pattern and the listed entries of earlier patterns, and a new pattern whose entries it
  /// has keeps the same matrix object (a direct solver keeps its analysis). Off: the graph
  /// holds exactly the entries of the current pattern.
  void keep_graph(bool on);
  /// Drops the graph: the next apply builds it from the current pattern alone (a checkpoint:
  /// a restart has no earlier patterns).
  void forget();

 private:
  struct Key {  // what the pattern depends on
    const void* col_map = nullptr;
    std::size_t nnz = 0;
    std::vector<GO> fixed, p, pt, x, d;  // rows and their columns, flattened
    bool operator==(const Key& o) const {
      return col_map == o.col_map && nnz == o.nnz && fixed == o.fixed && p == o.p && pt == o.pt &&
             x == o.x && d == o.d;
    }
  };
  Key key_, built_for_;
  const Comm* comm_ = nullptr;
  Teuchos::RCP<const Vector> keep_;
  std::vector<GO> p_row_ids_, pt_row_ids_;
  std::vector<GO> p_cols_, pt_cols_;             ///< flat columns (index 0 unused)
  std::vector<RowSpan> p_spans_, pt_spans_;      ///< per special row, in id order
  Kokkos::View<double*, ExecSpace> p_w_, pt_w_;  ///< flat weights, [0] = 1
  Kokkos::View<double*, ExecSpace> x_v_, d_v_;   ///< X's and D's values, in the given order
  std::vector<GO> x_rows_, x_cols_, d_rows_;
  // the contributions, found once per pattern: value += p_w(ip) * A(ea) * pt_w(it)
  Kokkos::View<int*, ExecSpace> c_a_, c_ip_, c_it_, c_pos_;
  Kokkos::View<int*, ExecSpace> xd_pos_;  ///< X's positions, then D's
  /// per value of the result, the run of its contributions (segments)
  Kokkos::View<int*, ExecSpace> c_order_, c_seg_, xd_order_, xd_seg_;
  Kokkos::View<int*, ExecSpace> plain_pos_;  ///< per entry of A: its position, or -1
  Teuchos::RCP<FEMatrix> B_;
  int builds_ = 0, graph_builds_ = 0;
  bool keep_graph_ = false;
  std::vector<std::pair<GO, GO>> graph_extra_;  ///< B's listed entries (row, column), sorted
  std::vector<GO> graph_remote_;                ///< B's rows owned elsewhere, sorted
  std::pair<const void*, std::size_t> graph_for_{nullptr, 0};  ///< A's structure B was built on
  struct Contribution {  // value(k, l) += p_w(ip) * A(a) * pt_w(it)
    int a, ip, it;
    GO k, l;
  };
  void build(const Matrix& A);
  void new_graph(const Matrix& A, const std::vector<char>& plain_row,
                 const std::vector<char>& plain_col, const std::vector<Contribution>& c,
                 bool merge);
  LO row_of(const Map& rows_map, GO g) const;
  static void segments(const std::vector<int>& pos, Kokkos::View<int*, ExecSpace>& order,
                       Kokkos::View<int*, ExecSpace>& seg);
  std::vector<char> plain_columns(const Matrix& A, std::vector<char>& plain_row) const;
  Teuchos::RCP<FEGraph> make_graph(const Matrix& A, const std::vector<char>& plain_row,
                                   const std::vector<char>& plain_col,
                                   const std::vector<GO>& remote,
                                   const std::vector<std::pair<LO, GO>>& extra) const;
  bool find_positions(const Matrix& A, const std::vector<char>& plain_row,
                      const std::vector<char>& plain_col, const std::vector<Contribution>& c,
                      std::vector<int>& cpos, std::vector<int>& xdpos);
};

}  // namespace emc::linalg
