#include "emcontact/linalg/elimination.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <algorithm>
#include <map>

namespace emc::linalg {

using Teuchos::RCP;
using Teuchos::rcp;

Elimination::Elimination(RCP<const Map> owned) : owned_(owned) {
  set_constraints({}, {}, {});
}

// docs/THEORY.md §3.1: P is the identity except in constrained rows (fixed: empty rows). Its
// graph is built here; the special rows' values are written by fill_P.
RCP<Matrix> Elimination::build_P(const std::vector<PRow>& rows) const {
  std::map<GO, const PRow*> special;
  for (const auto& r : rows) special[r.row] = &r;
  std::vector<char> is_fixed(owned_->getNodeNumElements(), 0);
  for (GO g : fixed_) is_fixed[owned_->getLocalElement(g)] = 1;
  std::size_t width = 1;
  for (const auto& r : rows) width = std::max(width, r.cols.size());
  auto graph = rcp(new Graph(owned_, width));
  for (LO l = 0; l < static_cast<LO>(owned_->getNodeNumElements()); ++l) {
    const GO g = owned_->getGlobalElement(l);
    auto it = special.find(g);
    if (it != special.end()) {
      if (!it->second->cols.empty())
        graph->insertGlobalIndices(g, Teuchos::ArrayView<const GO>(it->second->cols));
    } else if (!is_fixed[l]) {
      graph->insertGlobalIndices(g, Teuchos::ArrayView<const GO>(&g, 1));
    }
  }
  graph->fillComplete(owned_, owned_);
  auto P = rcp(new Matrix(graph));
  P->setAllToScalar(1.0);  // the plain rows' e_i; fill_P writes the special rows
  return P;
}

// The special rows' values (a column may come twice, through two chains: the weights add).
void Elimination::fill_P(const std::vector<PRow>& rows) {
  P_->resumeFill();
  std::vector<double> zeros;
  for (const auto& r : rows) {
    if (r.cols.empty()) continue;
    zeros.assign(r.cols.size(), 0.0);
    const Teuchos::ArrayView<const GO> cols(r.cols);
    P_->replaceGlobalValues(r.row, cols, Teuchos::ArrayView<const double>(zeros));
    P_->sumIntoGlobalValues(r.row, cols, Teuchos::ArrayView<const double>(r.weights));
  }
  P_->fillComplete(owned_, owned_);
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
    P_ = build_P(rows);
    std::vector<GO> constrained = fixed_;
    for (const auto& r : rows_) constrained.push_back(r.row);
    keep_ = keep_vector(owned_, constrained);
    if (masked_) masked_reduction_.set_keep(keep_);
    p_key_ = std::move(key);
    ++p_builds_;
  }
  fill_P(rows);
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
