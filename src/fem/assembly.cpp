// The assembly driver: launches the element kernels of kernels/ over my elements (Kokkos
// parallel loops, one per colour of element chunks, docs/THEORY.md §9, or one with atomic adds:
// Solver/Assembly/scatter) and scatters into the owned+shared rows of the FECrsMatrix and of
// overlap vectors, which Tpetra then exports to their owners.
#include <Teuchos_CommHelpers.hpp>
#include <algorithm>

#include "emcontact/error.hpp"
#include "emcontact/fem/discretization.hpp"
#include "emcontact/fem/element_loop.hpp"
#include "kernels/newton_tet4.hpp"

namespace emc::fem {
namespace {

using ConstDev =
    decltype(std::declval<const Vector&>().getLocalViewDevice(Tpetra::Access::ReadOnly));
using Dev = decltype(std::declval<Vector&>().getLocalViewDevice(Tpetra::Access::ReadWrite));

/// One element's residual (eq. 20), Newton matrix and round-off scale added into the overlap
/// rows and the CRS values (through the precomputed positions `off`).
struct TetNewton {
  ElementViews ev;
  ConstDev u0, V0, u1;
  Dev r, s;
  Kokkos::View<double*, ExecSpace> vals;
  Kokkos::View<int* [12][12], ExecSpace> off;
  double g[3], dt;
  kernels::Integrator integ;
  bool want_matrix, want_scale;

  template <bool Atomic>
  KOKKOS_INLINE_FUNCTION void element(const int k, MinLoc::value_type& mn) const {
    kernels::ElementState st;
    ev.gather(u0, k, st.u0);
    ev.gather(V0, k, st.V0);
    ev.gather(u1, k, st.u1);
    double Gk[4][3];
    ev.gradients(k, Gk);
    const double gk[3] = {g[0], g[1], g[2]};
    const double detF = kernels::tet4_detF(Gk, st.u1);
    if (detF < mn.val) {
      mn.val = detF;
      mn.loc = k;
    }
    double re[12], Ae[12][12], se[12];
    if (want_matrix)
      for (int p = 0; p < 12; ++p)
        for (int q = 0; q < 12; ++q) Ae[p][q] = 0;
    kernels::newton_tet4(Gk, ev.Ve(k), ev.lame(k), ev.rho(k), gk, integ, dt, st, re,
                         want_matrix ? Ae : nullptr, want_scale ? se : nullptr,
                         ev.massless(k) != 0);
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) {
        const int row = 3 * ev.node_lid(k, a) + i;
        scatter_add<Atomic>(r(row, 0), re[3 * a + i]);
        if (want_scale) scatter_add<Atomic>(s(row, 0), se[3 * a + i]);
        if (want_matrix)  // precomputed positions in the CRS values: no column search
          for (int q = 0; q < 12; ++q)
            scatter_add<Atomic>(vals(off(k, 3 * a + i, q)), Ae[3 * a + i][q]);
      }
  }
};

}  // namespace

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
  const int ne = ev_.size();
  MinLoc::value_type worst;
  {  // the views of f are released before the matrix and vectors are exported
    TetNewton f{ev_,
                u0o->getLocalViewDevice(Tpetra::Access::ReadOnly),
                V0o->getLocalViewDevice(Tpetra::Access::ReadOnly),
                u1o->getLocalViewDevice(Tpetra::Access::ReadOnly),
                ro.getLocalViewDevice(Tpetra::Access::ReadWrite),
                so.getLocalViewDevice(Tpetra::Access::ReadWrite),
                {},
                {},
                {model_.gravity[0], model_.gravity[1], model_.gravity[2]},
                dt,
                model_.integrator,
                want_matrix,
                want_scale};
    if (want_matrix) {
      const auto lcl = A->getLocalMatrixDevice();
      f.vals = lcl.values;
      if (offsets_.extent(0) != static_cast<std::size_t>(ev_.size())) build_offsets(lcl);
      f.off = offsets_;
    }
    worst = reduce_elements("emcontact::fem::em_tet4", f, colouring_, model_.scatter, ne);
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
  const int ne = ev_.size();
  offsets_ = decltype(offsets_)("emc::offsets", ne);
  auto h = Kokkos::create_mirror_view(offsets_);
  auto rows = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), lcl.graph.row_map);
  auto ents = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), lcl.graph.entries);
  auto lid = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), ev_.node_lid);
  auto col = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), ev_.col_lid);
  for (int k = 0; k < ne; ++k)
    for (int p = 0; p < 12; ++p) {
      const int row = 3 * lid(k, p / 3) + p % 3;
      for (int q = 0; q < 12; ++q) {
        // column indices are sorted within a row of a fill-complete local graph
        const auto* b = ents.data() + rows(row);
        const auto* e = ents.data() + rows(row + 1);
        const auto* it = std::lower_bound(b, e, col(k, q));
        if (it == e || *it != col(k, q))
          throw Error("internal: element entry missing from the FE graph");
        h(k, p, q) = static_cast<int>(it - ents.data());
      }
    }
  Kokkos::deep_copy(offsets_, h);
}

kernels::Monitors Discretization::monitors(const Vector& u, const Vector& V) const {
  auto uo = new_overlap_vector(), Vo = new_overlap_vector();
  to_overlap(u, *uo);
  to_overlap(V, *Vo);
  // element-wise sums: every element counted once, whichever rank owns its nodes
  auto vu = uo->getLocalViewDevice(Tpetra::Access::ReadOnly);
  auto vV = Vo->getLocalViewDevice(Tpetra::Access::ReadOnly);
  const ElementViews ev = ev_;
  const double g0 = model_.gravity[0], g1 = model_.gravity[1], g2 = model_.gravity[2];
  const int ne = ev.size();
  kernels::Monitors sum;
  Kokkos::parallel_reduce(
      "emcontact::fem::monitors_tet4", Kokkos::RangePolicy<ExecSpace>(0, ne),
      KOKKOS_LAMBDA(const int k, kernels::Monitors& m) {
        double xk[4][3], Gk[4][3], uk[4][3], Vk[4][3];
        for (int a = 0; a < 4; ++a)
          for (int i = 0; i < 3; ++i) xk[a][i] = ev.X(k, a, i);
        ev.gradients(k, Gk);
        ev.gather(vu, k, uk);
        ev.gather(vV, k, Vk);
        const double gk[3] = {g0, g1, g2};
        kernels::monitors_tet4(xk, Gk, ev.Ve(k), ev.lame(k), ev.rho(k), gk, uk, Vk, m,
                               ev.massless(k) != 0);
      },
      sum);
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
  auto vu = uo->getLocalViewDevice(Tpetra::Access::ReadOnly);
  auto vm = out->getLocalViewDevice(Tpetra::Access::OverwriteAll);
  const ElementViews ev = ev_;
  const int ne = ev.size();
  Kokkos::parallel_for(
      "emcontact::fem::von_mises_tet4", Kokkos::RangePolicy<ExecSpace>(0, ne),
      KOKKOS_LAMBDA(const int k) {
        double Gk[4][3], uk[4][3], H[3][3], F[3][3], E[3][3], S[3][3];
        ev.gradients(k, Gk);
        ev.gather(vu, k, uk);
        kernels::displacement_gradient(Gk, uk, H);
        kernels::identity_plus(H, F);
        kernels::green_strain(H, E);
        kernels::svk_stress(ev.lame(k), E, S);
        vm(k, 0) = kernels::von_mises(F, S, kernels::det3(F));
      });
  return out;
}

}  // namespace emc::fem
