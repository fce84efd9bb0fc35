// The assembly driver: calls the kernel library's element loops (kernels/tet4_elements.hpp) over
// my elements (one loop per colour of element chunks, docs/THEORY.md §9, or one with atomic adds:
// Solver/Assembly/scatter) into the owned+shared rows of the FECrsMatrix and of overlap vectors,
// which Tpetra then exports to their owners.
#include <Teuchos_CommHelpers.hpp>

#include "emcontact/error.hpp"
#include "emcontact/fem/discretization.hpp"
#include "emcontact/views.hpp"

namespace emc::fem {
const kernels::TetColouring<MemSpace>* Discretization::loops() const {
  return model_.scatter == Scatter::coloured ? &colouring_ : nullptr;
}

AssemblyInfo Discretization::assemble(const Vector& u0, const Vector& V0, const Vector& u1,
                                      double dt, FEMatrix* A, Vector& r, Vector* scale) const {
  auto u0o = new_overlap_vector(), V0o = new_overlap_vector(), u1o = new_overlap_vector();
  to_overlap(u0, *u0o);
  to_overlap(V0, *V0o);
  to_overlap(u1, *u1o);
  Vector ro(overlap_), so(overlap_);
  const bool want_scale = scale != nullptr, want_matrix = A != nullptr;
  if (want_matrix) {
    A->beginAssembly();
    A->setAllToScalar(0.0);
  }
  const int ne = tets_.size();
  kernels::MinDetF worst;
  {  // the views are released before the matrix and vectors are exported
    kernels::NewtonStep step;
    for (int i = 0; i < 3; ++i) step.gravity[i] = model_.gravity[i];
    step.dt = dt;
    step.integrator = model_.integrator;
    kernels::NewtonRows<MemSpace> out;
    out.r = write_column(ro);
    if (want_scale) out.s = write_column(so);
    if (want_matrix) {
      const auto lcl = A->getLocalMatrixDevice();
      out.values = lcl.values;
      if (offsets_.extent(0) != static_cast<std::size_t>(ne)) build_offsets(lcl);
      out.offsets = offsets_;
    }
    worst = kernels::newton_tet4_assemble(ExecSpace(), tets_, step, read_column(*u0o),
                                          read_column(*V0o), read_column(*u1o), out, loops());
  }
  AssemblyInfo info;
  info.min_detF = ne > 0 ? worst.val : 1e300;
  // no element's det F compares (all NaN): no worst element
  info.worst_tet = worst.loc >= 0 && worst.loc < ne ? part_.my_tets[worst.loc] : -1;
  // global minimum: reduce (detF, tet) pairs
  double local[2] = {info.min_detF, static_cast<double>(info.worst_tet)};
  std::vector<double> all(2 * comm_->getSize());
  Teuchos::gatherAll(*comm_, 2, local, static_cast<int>(all.size()), all.data());
  for (int p = 0; p < comm_->getSize(); ++p)
    if (all[2 * p] < info.min_detF) {
      info.min_detF = all[2 * p];
      info.worst_tet = static_cast<long long>(all[2 * p + 1]);
    }
  if (want_matrix) {
    if (moved_) add_moved_mass(A->getLocalMatrixDevice(), 2.0 / (dt * dt));  // §6.8
    A->endAssembly();
  }
  r.putScalar(0.0);
  r.doExport(ro, *exporter_, Tpetra::ADD);
  if (want_scale) {
    scale->putScalar(0.0);
    scale->doExport(so, *exporter_, Tpetra::ADD);
  }
  if (moved_) moved_mass_residual(u0, V0, u1, dt, r, scale);  // docs/THEORY.md §6.8
  return info;
}

// Position of every element entry (p, q) in the values of the (owned+shared) local matrix,
// found once per graph: the scatter then adds without searching the row.
void Discretization::build_offsets(const FEMatrix::local_matrix_device_type& lcl) const {
  offsets_ =
      decltype(offsets_)(Kokkos::ViewAllocateWithoutInitializing("emc::tet_offsets"), tets_.size());
  // column indices are sorted within a row of a fill-complete local graph
  if (kernels::tet4_offsets(ExecSpace(), tets_, columns_, lcl.graph.row_map, lcl.graph.entries,
                            offsets_) > 0)
    throw Error("internal: element entry missing from the FE graph");
}

kernels::Monitors Discretization::monitors(const Vector& u, const Vector& V) const {
  auto uo = new_overlap_vector(), Vo = new_overlap_vector();
  to_overlap(u, *uo);
  to_overlap(V, *Vo);
  // element-wise sums: every element counted once, whichever rank owns its nodes
  kernels::Monitors sum = kernels::monitors_tet4_sum(ExecSpace(), tets_, model_.gravity.data(),
                                                     read_column(*uo), read_column(*Vo));
  if (moved_) add_moved_monitors(u, V, sum);
  double local[13] = {sum.kinetic,   sum.elastic,   sum.potential, sum.L[0], sum.L[1],
                      sum.L[2],      sum.J[0],      sum.J[1],      sum.J[2], sum.mass,
                      sum.moment[0], sum.moment[1], sum.moment[2]};
  double global[13];
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, 13, local, global);
  kernels::Monitors out;
  out.kinetic = global[0];
  out.elastic = global[1];
  out.potential = global[2];
  for (int i = 0; i < 3; ++i) {
    out.L[i] = global[3 + i];
    out.J[i] = global[6 + i];
    out.moment[i] = global[10 + i];
  }
  out.mass = global[9];
  return out;
}

Teuchos::RCP<Vector> Discretization::von_mises(const Vector& u) const {
  auto uo = new_overlap_vector();
  to_overlap(u, *uo);
  auto out = Teuchos::rcp(new Vector(elements_));
  {
    const auto vm = out->getLocalViewDevice(Tpetra::Access::OverwriteAll);
    kernels::von_mises_tet4(ExecSpace(), tets_, read_column(*uo),
                            Kokkos::subview(vm, Kokkos::ALL(), 0));
  }
  return out;
}

}  // namespace emc::fem
