#include "emcontact/linalg/elimination.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_RowMatrixTransposer.hpp>
#include <algorithm>
#include <map>

#include "emcontact/linalg/p_matrix.hpp"

namespace emc::linalg {

using Teuchos::RCP;
using Teuchos::rcp;

namespace {

/// v(lids[k]) = values[k] (distinct local rows), on the vector's device: D's entries
/// (docs/THEORY.md §3.2).
void write_entries(Vector& v, const std::vector<LO>& lids, const std::vector<double>& values) {
  if (lids.empty()) return;
  Kokkos::View<LO*, ExecSpace> l(Kokkos::ViewAllocateWithoutInitializing("emc::entry_rows"),
                                 lids.size());
  Kokkos::View<double*, ExecSpace> x(Kokkos::ViewAllocateWithoutInitializing("emc::entry_values"),
                                     values.size());
  Kokkos::deep_copy(l, Kokkos::View<const LO*, Kokkos::HostSpace>(lids.data(), lids.size()));
  Kokkos::deep_copy(x,
                    Kokkos::View<const double*, Kokkos::HostSpace>(values.data(), values.size()));
  auto d = v.getLocalViewDevice(Tpetra::Access::ReadWrite);
  Kokkos::parallel_for(
      "emcontact::linalg::write_entries", Kokkos::RangePolicy<ExecSpace>(0, l.extent(0)),
      KOKKOS_LAMBDA(const int k) { d(l(k), 0) = x(k); });
}

/// docs/THEORY.md §3.6: y = P x = P^T x for P = diag(keep) (0/1): x_i where keep_i != 0, else 0.
void apply_mask(const Vector& keep, const Vector& x, Vector& y) {
  const auto k = keep.getLocalViewDevice(Tpetra::Access::ReadOnly);
  const auto xv = x.getLocalViewDevice(Tpetra::Access::ReadOnly);
  const auto yv = y.getLocalViewDevice(Tpetra::Access::OverwriteAll);
  Kokkos::parallel_for(
      "emcontact::linalg::mask", Kokkos::RangePolicy<ExecSpace>(0, k.extent(0)),
      KOKKOS_LAMBDA(const int i) { yv(i, 0) = k(i, 0) != 0 ? xv(i, 0) : 0.0; });
}

}  // namespace

Elimination::Elimination(RCP<const Map> owned) : owned_(owned) {
  set_constraints({}, {}, {});
}

// P's graph and the keep vector are rebuilt only when the constrained dofs or a special row's
// columns change; while they stay (Newton iterates of one frictionless set), only the special
// rows' values are rewritten.
void Elimination::set_constraints(const std::vector<GO>& fixed, const std::vector<PRow>& rows,
                                  const std::vector<std::pair<GO, double>>& dummy_diag) {
  dummies_.clear();  // set_dummies gives the new set's
  dummy_rows_ = Kokkos::View<LO*, ExecSpace>();
  std::vector<GO> key = fixed;
  key.push_back(-1);
  int mask = 1;  // every special row empty: P is a 0/1 diagonal
  for (const auto& r : rows) {
    key.push_back(r.row);
    key.push_back(static_cast<GO>(r.cols.size()));
    key.insert(key.end(), r.cols.begin(), r.cols.end());
    mask &= r.cols.empty() ? 1 : 0;
  }
  // max: something constrained, a pattern changed; min: every special row empty
  int local[3] = {fixed.empty() && rows.empty() ? 0 : 1, !built_ || key != p_key_ ? 1 : 0, -mask};
  int global[3];
  Teuchos::reduceAll(*owned_->getComm(), Teuchos::REDUCE_MAX, 3, local, global);
  identity_ = global[0] == 0;
  masked_ = global[2] == -1;
  rows_ = rows;
  if (global[1] != 0) {
    fixed_ = fixed;
    // docs/THEORY.md §3.1, with the special rows' values; a 0/1 diagonal P is the keep vector
    P_ = masked_ ? Teuchos::null : make_P(owned_, fixed_, rows);
    std::vector<GO> constrained = fixed_;
    for (const auto& r : rows_) constrained.push_back(r.row);
    keep_ = keep_vector(owned_, constrained);
    if (masked_) masked_reduction_.set_keep(keep_);
    p_key_ = std::move(key);
    built_ = true;
    ++p_builds_;
  } else if (!masked_) {
    write_P_rows(*P_, rows);
  }
  PT_ = Teuchos::null;  // P's pattern or values changed
  pt_rows_.clear();
  X_.clear();
  linearised_ = false;
  set_dummy_values(dummy_diag);
}

void Elimination::set_linearisation(const std::vector<PRow>& pt_rows, const std::vector<Entry>& X,
                                    const std::vector<PRow>& pl_rows) {
  pt_rows_ = pt_rows;
  left_rows_ = rows_;
  if (!pl_rows.empty()) {  // docs/THEORY.md §11.3: the left factor differs from P in these rows
    std::map<GO, const PRow*> by_row;
    for (const auto& r : pl_rows) by_row[r.row] = &r;
    for (auto& r : left_rows_) {
      auto it = by_row.find(r.row);
      if (it != by_row.end()) r = *it->second;
    }
  }
  X_ = X;
  linearised_ = true;
}

// D (docs/THEORY.md §3.2): 1 on fixed dofs, beta on the dummies. Called at every Newton
// iteration under stick (beta follows A); the masked path takes the diagonal as a vector.
void Elimination::set_dummy_values(const std::vector<std::pair<GO, double>>& dummy_diag) {
  std::map<GO, double> diag;
  for (GO g : fixed_) diag[g] = 1.0;
  for (const auto& [g, v] : dummy_diag) diag[g] = v;
  diag_.assign(diag.begin(), diag.end());
  if (!masked_) return;
  // D's vector is kept: only the entries of the last call are cleared and the new ones written
  if (d_.is_null()) d_ = rcp(new Vector(owned_));
  std::vector<LO> lids;
  std::vector<double> values;
  for (const auto& [g, v] : diag) {
    lids.push_back(owned_->getLocalElement(g));
    values.push_back(v);
  }
  if (lids != d_lids_) {  // other dofs (a new set): clear the last ones
    write_entries(*d_, d_lids_, std::vector<double>(d_lids_.size(), 0.0));
    d_lids_ = std::move(lids);
  }
  write_entries(*d_, d_lids_, values);
  masked_reduction_.set_diagonal(d_);
}

// docs/THEORY.md §3.2: the dummies' entries of D, zero until set_dummy_betas writes them.
void Elimination::set_dummies(const std::vector<GO>& dummies) {
  dummies_ = dummies;
  std::vector<std::pair<GO, double>> zero;
  for (GO g : dummies) zero.emplace_back(g, 0.0);
  set_dummy_values(zero);  // D's rows that may be non-zero now include the dummies
  if (!masked_) return;
  dummy_rows_ = Kokkos::View<LO*, ExecSpace>("emc::dummy_rows", dummies.size());
  const auto rows = Kokkos::create_mirror_view(dummy_rows_);
  for (std::size_t k = 0; k < dummies.size(); ++k) rows(k) = owned_->getLocalElement(dummies[k]);
  Kokkos::deep_copy(dummy_rows_, rows);
}

// docs/THEORY.md §3.2: D = beta on the dummies, at every Newton iterate.
void Elimination::set_dummy_betas(Kokkos::View<const double*, ExecSpace> beta) {
  if (!masked_ || linearised_) {  // the host list of D's entries feeds the structured path
    const auto bh = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), beta);
    std::vector<std::pair<GO, double>> diag;
    for (std::size_t k = 0; k < dummies_.size(); ++k) diag.emplace_back(dummies_[k], bh(k / 3));
    set_dummy_values(diag);
    return;
  }
  const auto rows = dummy_rows_;
  const auto d = d_->getLocalViewDevice(Tpetra::Access::ReadWrite);
  Kokkos::parallel_for(
      "emcontact::linalg::dummy_diagonal", Kokkos::RangePolicy<ExecSpace>(0, rows.extent(0)),
      KOKKOS_LAMBDA(const int k) { d(rows(k), 0) = beta(k / 3); });
  masked_reduction_.set_diagonal(d_);
}

// docs/THEORY.md §3.2 (and §5.4: P^T A Pt + X + D with the exact right factor).
RCP<Matrix> Elimination::reduce_matrix(const RCP<Matrix>& A) const {
  if (identity_) return A;
  if (masked_ && !linearised_) return masked_reduction_.apply(*A);
  structured_reduction_.set(keep_, fixed_, linearised_ ? left_rows_ : rows_, pt_rows_, X_, diag_,
                            *owned_->getComm());
  return structured_reduction_.apply(*A);
}

void Elimination::reduce_residual(const Vector& g, Vector& R) const {
  if (identity_) {
    R.assign(g);
    return;
  }
  if (masked_) {
    apply_mask(*keep_, g, R);
  } else if (!form_transpose_) {
    P_->apply(g, R, Teuchos::TRANS);  // one thread: each column sums in row order
  } else {  // threads: bit for bit the same in every run (docs/THEORY.md §9)
    if (PT_.is_null())
      PT_ = Tpetra::RowMatrixTransposer<Scalar, LO, GO, Node>(P_).createTranspose();
    PT_->apply(g, R);
  }
}

void Elimination::expand(const Vector& dq, Vector& du) const {
  if (identity_) {
    du.assign(dq);
    return;
  }
  if (masked_)
    apply_mask(*keep_, dq, du);
  else
    P_->apply(dq, du, Teuchos::NO_TRANS);
}

}  // namespace emc::linalg
