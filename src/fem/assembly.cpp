// The assembly driver: calls the kernel library's element loops (kernels/tet4_elements.hpp) over
// my elements (one loop per colour of element chunks, docs/THEORY.md §9, or one with atomic adds:
// Solver/Assembly/scatter) into the owned+shared rows of the FECrsMatrix and of overlap vectors,
// which Tpetra then exports to their owners.
#include <Teuchos_CommHelpers.hpp>

#include "emcontact/error.hpp"
#include "emcontact/fem/discretization.hpp"
#include "emcontact/views.hpp"

namespace emc::fem {

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
  AssemblyInfo info;
  info.min_detF = 1e300;  // without elements, or where no det F compares (all NaN): no worst
  {                       // the views are released before the matrix and vectors are exported
    kernels::NewtonStep step;
    for (int i = 0; i < 3; ++i) step.gravity[i] = model_.gravity[i];
    step.dt = dt;
    step.integrator = model_.integrator;
    kernels::NewtonRows<MemSpace> out;
    out.r = write_column(ro);
    if (want_scale) out.s = write_column(so);
    const auto u0v = read_column(*u0o), V0v = read_column(*V0o), u1v = read_column(*u1o);
    bool first = true;
    for_each_group([&](const auto& g) {
      if (want_matrix) {
        const auto lcl = A->getLocalMatrixDevice();
        out.values = lcl.values;
        if (g.offsets.extent(0) != static_cast<std::size_t>(g.size())) build_offsets(g, lcl);
        out.offsets = g.offsets;
      }
      const kernels::MinDetF w =
          kernels::newton_tet4_assemble(ExecSpace(), g.tets, step, u0v, V0v, u1v, out, loops(g));
      if (first || w.val < info.min_detF) {
        info.min_detF = w.val;
        info.worst_tet = w.loc >= 0 && w.loc < g.size() ? part_.my_tets[g.local[w.loc]] : -1;
      }
      first = false;
    });
  }
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
template <class Material>
void Discretization::build_offsets(const ElementGroup<Material>& g,
                                   const FEMatrix::local_matrix_device_type& lcl) const {
  g.offsets = kernels::TetOffsets<MemSpace>(
      Kokkos::ViewAllocateWithoutInitializing("emc::tet_offsets"), g.size());
  // column indices are sorted within a row of a fill-complete local graph
  if (kernels::tet4_offsets(ExecSpace(), g.tets, g.columns, lcl.graph.row_map, lcl.graph.entries,
                            g.offsets) > 0)
    throw Error("internal: element entry missing from the FE graph");
}

kernels::Monitors Discretization::monitors(const Vector& u, const Vector& V) const {
  auto uo = new_overlap_vector(), Vo = new_overlap_vector();
  to_overlap(u, *uo);
  to_overlap(V, *Vo);
  // element-wise sums: every element counted once, whichever rank owns its nodes
  kernels::Monitors sum;
  bool first = true;
  for_each_group([&](const auto& g) {
    const kernels::Monitors m = kernels::monitors_tet4_sum(
        ExecSpace(), g.tets, model_.gravity.data(), read_column(*uo), read_column(*Vo));
    if (first)
      sum = m;
    else
      sum += m;
    first = false;
  });
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
    const auto vm =
        Kokkos::subview(out->getLocalViewDevice(Tpetra::Access::OverwriteAll), Kokkos::ALL(), 0);
    for_each_group([&](const auto& g) {
      Kokkos::View<double*, MemSpace> mine("emc::von_mises", g.size());
      kernels::von_mises_tet4(ExecSpace(), g.tets, read_column(*uo), mine);
      kernels::set_at(ExecSpace(), "emcontact::fem::von_mises_scatter", vm, g.local_view, mine);
    });
  }
  return out;
}

}  // namespace emc::fem
