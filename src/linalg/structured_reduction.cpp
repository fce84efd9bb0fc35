#include "emcontact/linalg/structured_reduction.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <algorithm>
#include <cstdint>
#include <iterator>
#include <map>

#include "emcontact/error.hpp"
#include "emcontact/parallel.hpp"
#include "emcontact/views.hpp"

namespace emc::linalg {

using Teuchos::RCP;
using Teuchos::rcp;

namespace {

/// Rows sorted by id, flattened: ids, spans into cols/weights (index 0: the weight 1 of a plain
/// row), and the key (row, count, columns...).
void flatten(std::vector<const PRow*> rows, std::vector<GO>& ids, std::vector<GO>& cols,
             std::vector<double>& w, std::vector<GO>& key, std::vector<RowSpan>& spans) {
  std::sort(rows.begin(), rows.end(), [](const PRow* a, const PRow* b) { return a->row < b->row; });
  ids.clear();
  cols.assign(1, -1);
  w.assign(1, 1.0);
  key.clear();
  spans.clear();
  for (const PRow* r : rows) {
    ids.push_back(r->row);
    key.push_back(r->row);
    key.push_back(static_cast<GO>(r->cols.size()));
    spans.push_back(
        {static_cast<int>(cols.size()), static_cast<int>(cols.size() + r->cols.size())});
    for (std::size_t k = 0; k < r->cols.size(); ++k) {
      cols.push_back(r->cols[k]);
      w.push_back(r->weights[k]);
      key.push_back(r->cols[k]);
    }
  }
}

}  // namespace

void StructuredReduction::set(Teuchos::RCP<const Vector> keep, const std::vector<GO>& fixed,
                              const std::vector<PRow>& p_rows, const std::vector<PRow>& pt_rows,
                              const std::vector<Entry>& X,
                              const std::vector<std::pair<GO, double>>& diag, const Comm& comm) {
  comm_ = &comm;
  keep_ = std::move(keep);
  key_.fixed = fixed;
  std::vector<double> pw, ptw;
  {  // P: my rows
    std::vector<const PRow*> mine;
    for (const auto& r : p_rows) mine.push_back(&r);
    flatten(mine, p_row_ids_, p_cols_, pw, key_.p, p_spans_);
  }
  {  // Pt: P with the given rows replaced, every rank's (A's columns may be anywhere)
    std::map<GO, const PRow*> merged;
    for (const auto& r : p_rows) merged[r.row] = &r;
    for (const auto& r : pt_rows) merged[r.row] = &r;
    std::vector<double> send;
    for (const auto& [g, r] : merged) {
      send.push_back(static_cast<double>(g));
      send.push_back(static_cast<double>(r->cols.size()));
      for (std::size_t k = 0; k < r->cols.size(); ++k) {
        send.push_back(static_cast<double>(r->cols[k]));
        send.push_back(r->weights[k]);
      }
    }
    const auto all = allgather(comm, send);
    std::vector<PRow> rows;
    for (std::size_t k = 0; k < all.size();) {
      PRow r{static_cast<GO>(all[k]), {}, {}};
      const auto n = static_cast<std::size_t>(all[k + 1]);
      for (std::size_t j = 0; j < n; ++j) {
        r.cols.push_back(static_cast<GO>(all[k + 2 + 2 * j]));
        r.weights.push_back(all[k + 3 + 2 * j]);
      }
      k += 2 + 2 * n;
      rows.push_back(std::move(r));
    }
    std::vector<const PRow*> ptrs;
    for (const auto& r : rows) ptrs.push_back(&r);
    flatten(ptrs, pt_row_ids_, pt_cols_, ptw, key_.pt, pt_spans_);
  }
  p_w_ = to_view("emc::structured::p_w", pw);
  pt_w_ = to_view("emc::structured::pt_w", ptw);
  x_rows_.clear();
  x_cols_.clear();
  key_.x.clear();
  std::vector<double> xv;
  for (const auto& e : X) {
    x_rows_.push_back(e.row);
    x_cols_.push_back(e.col);
    xv.push_back(e.value);
    key_.x.push_back(e.row);
    key_.x.push_back(e.col);
  }
  x_v_ = to_view("emc::structured::x", xv);
  d_rows_.clear();
  std::vector<double> dv;
  for (const auto& [g, v] : diag) {
    d_rows_.push_back(g);
    dv.push_back(v);
  }
  key_.d = d_rows_;
  d_v_ = to_view("emc::structured::d", dv);
}

// Which of A's local columns are plain (P's and Pt's row is e_j: not fixed, not special).
std::vector<char> StructuredReduction::plain_columns(const Matrix& A,
                                                     std::vector<char>& plain_row) const {
  const Vector keep_col = keep_on_columns(*keep_, A);
  auto kh = keep_->getLocalViewHost(Tpetra::Access::ReadOnly);
  auto kc = keep_col.getLocalViewHost(Tpetra::Access::ReadOnly);
  plain_row.assign(kh.extent(0), 0);
  for (std::size_t i = 0; i < kh.extent(0); ++i) plain_row[i] = kh(i, 0) != 0;
  std::vector<char> plain(kc.extent(0));
  for (std::size_t j = 0; j < kc.extent(0); ++j) plain[j] = kc(j, 0) != 0;
  return plain;
}

// docs/THEORY.md §3.6, §5.4: the contributions P_ki A_ij Pt_jl and the graph of the result. An
// entry of A in a plain row and a plain column is copied to (i, j) (most of them: found row by
// row below, without a list); the others, X and D are listed with their weights.
void StructuredReduction::build(const Matrix& A) {
  ++builds_;
  const auto& rows_map = *A.getRowMap();
  const auto& col_map = *A.getColMap();
  const LO n_own = static_cast<LO>(rows_map.getNodeNumElements());
  std::vector<char> plain_row;
  const std::vector<char> plain_col = plain_columns(A, plain_row);
  auto find = [](const std::vector<GO>& ids, GO g) {
    const auto it = std::lower_bound(ids.begin(), ids.end(), g);
    return it != ids.end() && *it == g ? static_cast<int>(it - ids.begin()) : -1;
  };

  const auto lA = A.getLocalMatrixHost();
  std::vector<Contribution> c;
  std::vector<std::pair<GO, int>> prow, ptrow;  // (column, weight index)
  for (LO i = 0; i < n_own; ++i) {
    const GO gi = rows_map.getGlobalElement(i);
    prow.clear();
    if (plain_row[i]) {
      prow.emplace_back(gi, 0);
    } else if (const int s = find(p_row_ids_, gi); s >= 0) {
      for (int w = p_spans_[s].begin; w < p_spans_[s].end; ++w) prow.emplace_back(p_cols_[w], w);
    }
    if (prow.empty()) continue;
    for (auto e = lA.graph.row_map(i); e < lA.graph.row_map(i + 1); ++e) {
      const LO lj = lA.graph.entries(e);
      if (plain_row[i] && plain_col[lj]) continue;  // a plain entry
      const GO gj = col_map.getGlobalElement(lj);
      ptrow.clear();
      if (plain_col[lj]) {
        ptrow.emplace_back(gj, 0);
      } else if (const int s = find(pt_row_ids_, gj); s >= 0) {
        for (int w = pt_spans_[s].begin; w < pt_spans_[s].end; ++w)
          ptrow.emplace_back(pt_cols_[w], w);
      }
      for (const auto& [k, ip] : prow)
        for (const auto& [l, it] : ptrow) c.push_back({static_cast<int>(e), ip, it, k, l});
    }
  }

  // docs/THEORY.md §3.6: with keep_graph, the graph holds A's whole pattern and the listed
  // entries of earlier sets too, and is kept while it has every entry this pattern needs
  const bool same_a = !B_.is_null() && graph_for_ == std::make_pair(key_.col_map, key_.nnz);
  int attempt = keep_graph_ && same_a ? 1 : 0, all_attempt = 0, found = 0;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MIN, 1, &attempt, &all_attempt);
  std::vector<int> cpos, xdpos;
  if (all_attempt) {
    int mine = find_positions(A, plain_row, plain_col, c, cpos, xdpos) ? 1 : 0;
    Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MIN, 1, &mine, &found);
  }
  if (!found) {
    new_graph(A, plain_row, plain_col, c, all_attempt != 0);
    if (!find_positions(A, plain_row, plain_col, c, cpos, xdpos))
      throw Error("internal: reduced-matrix entry missing from its graph");
  }
  std::vector<int> ca(c.size()), cp(c.size()), ct(c.size());
  for (std::size_t k = 0; k < c.size(); ++k) {
    ca[k] = c[k].a;
    cp[k] = c[k].ip;
    ct[k] = c[k].it;
  }
  c_a_ = to_view("emc::structured::a", ca);
  c_ip_ = to_view("emc::structured::ip", cp);
  c_it_ = to_view("emc::structured::it", ct);
  c_pos_ = to_view("emc::structured::pos", cpos);
  segments(cpos, c_order_, c_seg_);
  xd_pos_ = to_view("emc::structured::xd_pos", xdpos);  // X's entries, then D's
  segments(xdpos, xd_order_, xd_seg_);
}

// The graph for the listed entries of this pattern (the contributions', X's and D's) and, with
// keep_graph on the same A, those of the current graph while the union is at most twice them
// (it bounds the explicit zeros a direct solver factors).
void StructuredReduction::new_graph(const Matrix& A, const std::vector<char>& plain_row,
                                    const std::vector<char>& plain_col,
                                    const std::vector<Contribution>& c, bool merge) {
  const auto& rows_map = *A.getRowMap();
  std::vector<std::pair<GO, GO>> needed;
  needed.reserve(c.size() + x_rows_.size() + d_rows_.size());
  for (const auto& x : c) needed.emplace_back(x.k, x.l);
  for (std::size_t k = 0; k < x_rows_.size(); ++k) needed.emplace_back(x_rows_[k], x_cols_[k]);
  for (GO g : d_rows_) needed.emplace_back(g, g);
  sort_unique_entries(needed);
  std::vector<std::pair<GO, GO>> merged;
  if (merge)
    std::set_union(graph_extra_.begin(), graph_extra_.end(), needed.begin(), needed.end(),
                   std::back_inserter(merged));
  if (merge && merged.size() <= 2 * needed.size())
    graph_extra_ = std::move(merged);
  else
    graph_extra_ = std::move(needed);
  graph_for_ = {key_.col_map, key_.nnz};
  // rows: mine, then the rows owned elsewhere that I add to (FECrsGraph wants mine first)
  graph_remote_.clear();
  for (const auto& [k, l] : graph_extra_)
    if (!rows_map.isNodeGlobalElement(k)) graph_remote_.push_back(k);
  graph_remote_.erase(std::unique(graph_remote_.begin(), graph_remote_.end()), graph_remote_.end());
  std::vector<std::pair<LO, GO>> extra;  // by graph row: plain entries (or A's row), then these
  extra.reserve(graph_extra_.size());
  for (const auto& [k, l] : graph_extra_) extra.emplace_back(row_of(rows_map, k), l);
  std::sort(extra.begin(), extra.end());
  B_ = rcp(new FEMatrix(make_graph(A, plain_row, plain_col, graph_remote_, extra)));
  ++graph_builds_;
}

// A row of the graph: mine by local index, then the rows owned elsewhere (graph_remote_).
LO StructuredReduction::row_of(const Map& rows_map, GO g) const {
  const LO l = rows_map.getLocalElement(g);
  if (l != Teuchos::OrdinalTraits<LO>::invalid()) return l;
  const auto it = std::lower_bound(graph_remote_.begin(), graph_remote_.end(), g);
  if (it == graph_remote_.end() || *it != g) return -1;
  return static_cast<LO>(rows_map.getNodeNumElements() + (it - graph_remote_.begin()));
}

// The FE graph: my rows (plain entries of A's row, or with keep_graph its whole row, then the
// listed ones) and the rows owned elsewhere that I add to. `extra`: sorted unique (overlap
// row, column).
RCP<FEGraph> StructuredReduction::make_graph(const Matrix& A, const std::vector<char>& plain_row,
                                             const std::vector<char>& plain_col,
                                             const std::vector<GO>& remote,
                                             const std::vector<std::pair<LO, GO>>& extra) const {
  const auto& rows_map = *A.getRowMap();
  const auto& col_map = *A.getColMap();
  const LO n_own = static_cast<LO>(rows_map.getNodeNumElements());
  const auto lA = A.getLocalMatrixHost();
  std::vector<GO> ids(rows_map.getNodeElementList().begin(), rows_map.getNodeElementList().end());
  ids.insert(ids.end(), remote.begin(), remote.end());
  const auto invalid = Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid();
  auto overlap = rcp(new Map(invalid, Teuchos::ArrayView<const GO>(ids), 0, rows_map.getComm()));
  std::vector<std::size_t> first(ids.size() + 1, 0);  // each row's range in `extra`
  for (const auto& [r, g] : extra) ++first[r + 1];
  for (std::size_t r = 0; r < ids.size(); ++r) first[r + 1] += first[r];
  // each row once: plain entries (or A's row) and listed ones, no duplicates
  std::vector<GO> cols;
  std::vector<std::size_t> start(ids.size() + 1, 0);
  cols.reserve(lA.nnz() + extra.size());
  Kokkos::DualView<std::size_t*, Node::device_type> count("emc::structured::count", ids.size());
  for (std::size_t r = 0; r < ids.size(); ++r) {
    start[r] = cols.size();
    if (static_cast<LO>(r) < n_own && (plain_row[r] || keep_graph_))
      for (auto e = lA.graph.row_map(r); e < lA.graph.row_map(r + 1); ++e)
        if (plain_col[lA.graph.entries(e)] || keep_graph_)
          cols.push_back(col_map.getGlobalElement(lA.graph.entries(e)));
    const std::size_t n_plain = cols.size() - start[r];
    for (std::size_t k = first[r]; k < first[r + 1]; ++k) cols.push_back(extra[k].second);
    if (first[r + 1] > first[r] && n_plain > 0) {
      const auto b = cols.begin() + static_cast<std::ptrdiff_t>(start[r]);
      std::sort(b, cols.end());
      cols.erase(std::unique(b, cols.end()), cols.end());
    }
    count.h_view(r) = cols.size() - start[r];
  }
  start[ids.size()] = cols.size();
  count.modify_host();
  count.sync_device();
  auto graph = rcp(new FEGraph(A.getRowMap(), overlap, count));
  graph->beginAssembly();
  for (std::size_t r = 0; r < ids.size(); ++r)
    graph->insertGlobalIndices(ids[r], Teuchos::ArrayView<const GO>(
                                           cols.data() + start[r],
                                           static_cast<Teuchos::Ordinal>(start[r + 1] - start[r])));
  graph->endAssembly();
  return graph;
}

// Positions in the values of B's owned+shared local matrix: of every plain entry of A (a
// column marker per row), of the contributions, and of X's then D's entries. False if one is
// not in B's graph. Collective (B's assembly).
bool StructuredReduction::find_positions(const Matrix& A, const std::vector<char>& plain_row,
                                         const std::vector<char>& plain_col,
                                         const std::vector<Contribution>& c, std::vector<int>& cpos,
                                         std::vector<int>& xdpos) {
  B_->beginAssembly();
  const auto lA = A.getLocalMatrixHost();
  const auto lB = B_->getLocalMatrixHost();
  const auto& bcol = *B_->getColMap();
  const auto& acol = *A.getColMap();
  const auto& rows_map = *A.getRowMap();
  std::vector<LO> a2b(acol.getNodeNumElements());  // A's local columns in B's column map
  for (std::size_t j = 0; j < a2b.size(); ++j)
    a2b[j] = bcol.getLocalElement(acol.getGlobalElement(j));
  bool ok = true;
  std::vector<int> plain_pos(lA.nnz(), -1), marker(bcol.getNodeNumElements(), -1);
  for (std::size_t i = 0; i < plain_row.size(); ++i) {
    if (!plain_row[i]) continue;
    for (auto p = lB.graph.row_map(i); p < lB.graph.row_map(i + 1); ++p)
      marker[lB.graph.entries(p)] = static_cast<int>(p);
    for (auto e = lA.graph.row_map(i); e < lA.graph.row_map(i + 1); ++e)
      if (plain_col[lA.graph.entries(e)]) {
        const LO j = a2b[lA.graph.entries(e)];
        const int q = j >= 0 ? marker[j] : -1;  // a stale mark is of an earlier row
        ok &= q >= static_cast<int>(lB.graph.row_map(i)) && lB.graph.entries(q) == j;
        plain_pos[e] = q;
      }
  }
  plain_pos_ = to_view("emc::structured::plain_pos", plain_pos);
  auto pos = [&](GO k, GO l) {
    const LO r = row_of(rows_map, k), cl = bcol.getLocalElement(l);
    if (r < 0 || cl == Teuchos::OrdinalTraits<LO>::invalid()) return -1;
    const auto* b = lB.graph.entries.data() + lB.graph.row_map(r);
    const auto* e = lB.graph.entries.data() + lB.graph.row_map(r + 1);
    const auto* it = std::lower_bound(b, e, cl);
    return it == e || *it != cl ? -1 : static_cast<int>(it - lB.graph.entries.data());
  };
  cpos.resize(c.size());
  for (std::size_t k = 0; ok && k < c.size(); ++k) ok = (cpos[k] = pos(c[k].k, c[k].l)) >= 0;
  xdpos.clear();
  for (std::size_t k = 0; ok && k < x_rows_.size(); ++k)
    ok = xdpos.emplace_back(pos(x_rows_[k], x_cols_[k])) >= 0;
  for (std::size_t k = 0; ok && k < d_rows_.size(); ++k)
    ok = xdpos.emplace_back(pos(d_rows_[k], d_rows_[k])) >= 0;
  B_->endAssembly();
  return ok;
}

// docs/THEORY.md §3.6: the graph kept across patterns (direct solvers), dropped at a checkpoint.
void StructuredReduction::keep_graph(bool on) {
  keep_graph_ = on;
  forget();
}

void StructuredReduction::forget() {
  B_ = Teuchos::null;
  built_for_ = Key{};
  graph_extra_.clear();
  graph_remote_.clear();
}

// Groups the contributions by the value they add to: order lists them by position (stably: in
// their own order within a position), seg the start of each position's run. A kernel over the
// runs then adds each position's contributions in a fixed order, with no two threads on one
// value: the same bits on any number of threads (docs/THEORY.md §9).
void StructuredReduction::segments(const std::vector<int>& pos,
                                   Kokkos::View<int*, ExecSpace>& order,
                                   Kokkos::View<int*, ExecSpace>& seg) {
  const int n_values = pos.empty() ? 0 : *std::max_element(pos.begin(), pos.end()) + 1;
  std::vector<int> first(n_values + 1, 0), o(pos.size()), starts;
  for (int p : pos) ++first[p + 1];  // a counting sort: stable, linear in the values
  for (int v = 0; v < n_values; ++v) {
    if (first[v + 1] > 0) starts.push_back(first[v]);
    first[v + 1] += first[v];
  }
  starts.push_back(static_cast<int>(pos.size()));
  for (std::size_t k = 0; k < pos.size(); ++k) o[first[pos[k]]++] = static_cast<int>(k);
  order = to_view("emc::structured::order", o);
  seg = to_view("emc::structured::seg", starts);
}

// Packed into one 64-bit key where both ids fit in 32 bits (every mesh MUMPS takes).
void sort_unique_entries(std::vector<std::pair<GO, GO>>& v) {
  constexpr GO limit = GO(1) << 32;
  const bool packable = std::all_of(v.begin(), v.end(), [&](const std::pair<GO, GO>& e) {
    return e.first >= 0 && e.first < limit && e.second >= 0 && e.second < limit;
  });
  if (!packable) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
    return;
  }
  std::vector<std::uint64_t> keys(v.size());
  for (std::size_t k = 0; k < v.size(); ++k)
    keys[k] =
        static_cast<std::uint64_t>(v[k].first) << 32 | static_cast<std::uint64_t>(v[k].second);
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  v.resize(keys.size());
  for (std::size_t k = 0; k < keys.size(); ++k)
    v[k] = {static_cast<GO>(keys[k] >> 32), static_cast<GO>(keys[k] & 0xffffffffu)};
}

RCP<Matrix> StructuredReduction::apply(const Matrix& A) {
  key_.col_map = A.getColMap().get();
  key_.nnz = A.getNodeNumEntries();
  int changed = B_.is_null() || !(key_ == built_for_) ? 1 : 0, any = 0;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, 1, &changed, &any);
  if (any) {
    build(A);
    built_for_ = key_;
  }
  const auto vA = A.getLocalMatrixDevice().values;
  B_->beginAssembly();
  B_->setAllToScalar(0.0);
  {
    const auto vB = B_->getLocalMatrixDevice().values;
    const auto plain = plain_pos_;
    const auto a = c_a_, ip = c_ip_, it = c_it_, pos = c_pos_, xdpos = xd_pos_;
    const auto pw = p_w_, ptw = pt_w_, xv = x_v_, dv = d_v_;
    const auto corder = c_order_, cseg = c_seg_, xdorder = xd_order_, xdseg = xd_seg_;
    const int nx = static_cast<int>(x_v_.extent(0));
    Kokkos::parallel_for(  // distinct positions: no atomics
        "emcontact::linalg::structured_plain", Kokkos::RangePolicy<ExecSpace>(0, plain.extent(0)),
        KOKKOS_LAMBDA(const int e) {
          if (plain(e) >= 0) vB(plain(e)) += vA(e);
        });
    Kokkos::parallel_for(  // one run of contributions per value, in a fixed order
        "emcontact::linalg::structured_ptap",
        Kokkos::RangePolicy<ExecSpace>(0, cseg.extent(0) > 0 ? cseg.extent(0) - 1 : 0),
        KOKKOS_LAMBDA(const int r) {
          const int p = pos(corder(cseg(r)));
          double v = vB(p);
          for (int j = cseg(r); j < cseg(r + 1); ++j) {
            const int k = corder(j);
            v += pw(ip(k)) * vA(a(k)) * ptw(it(k));
          }
          vB(p) = v;
        });
    Kokkos::parallel_for(
        "emcontact::linalg::structured_x_d",
        Kokkos::RangePolicy<ExecSpace>(0, xdseg.extent(0) > 0 ? xdseg.extent(0) - 1 : 0),
        KOKKOS_LAMBDA(const int r) {
          const int p = xdpos(xdorder(xdseg(r)));
          double v = vB(p);
          for (int j = xdseg(r); j < xdseg(r + 1); ++j) {
            const int e = xdorder(j);
            v += e < nx ? xv(e) : dv(e - nx);
          }
          vB(p) = v;
        });
  }
  B_->endAssembly();
  return B_;
}

}  // namespace emc::linalg
