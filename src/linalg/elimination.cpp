#include "emcontact/linalg/elimination.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <algorithm>
#include <map>

#include "emcontact/linalg/p_matrix.hpp"

namespace emc::linalg {

using Teuchos::RCP;
using Teuchos::rcp;

Elimination::Elimination(RCP<const Map> owned) : owned_(owned) {
  set_constraints({}, {}, {});
}

// P's graph and the keep vector are rebuilt only when the constrained dofs or a special row's
// columns change; while they stay (Newton iterates of one frictionless set), only the special
// rows' values are rewritten.
void Elimination::set_constraints(const std::vector<GO>& fixed, const std::vector<PRow>& rows,
                                  const std::vector<std::pair<GO, double>>& dummy_diag) {
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
  int local[3] = {fixed.empty() && rows.empty() ? 0 : 1, P_.is_null() || key != p_key_ ? 1 : 0,
                  -mask};
  int global[3];
  Teuchos::reduceAll(*owned_->getComm(), Teuchos::REDUCE_MAX, 3, local, global);
  identity_ = global[0] == 0;
  masked_ = global[2] == -1;
  rows_ = rows;
  if (global[1] != 0) {
    fixed_ = fixed;
    P_ = make_P(owned_, fixed_, rows);  // docs/THEORY.md §3.1, with the special rows' values
    std::vector<GO> constrained = fixed_;
    for (const auto& r : rows_) constrained.push_back(r.row);
    keep_ = keep_vector(owned_, constrained);
    if (masked_) masked_reduction_.set_keep(keep_);
    p_key_ = std::move(key);
    ++p_builds_;
  } else {
    write_P_rows(*P_, rows);
  }
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
  if (masked_) {
    auto d = rcp(new Vector(owned_));
    auto dv = d->getLocalViewHost(Tpetra::Access::ReadWrite);
    for (const auto& [g, v] : diag) dv(owned_->getLocalElement(g), 0) = v;
    masked_reduction_.set_diagonal(d);
  }
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
  P_->apply(g, R, Teuchos::TRANS);
}

void Elimination::expand(const Vector& dq, Vector& du) const {
  if (identity_) {
    du.assign(dq);
    return;
  }
  P_->apply(dq, du, Teuchos::NO_TRANS);
}

}  // namespace emc::linalg
