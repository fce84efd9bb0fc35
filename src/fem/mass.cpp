// The consistent mass matrix of ALGORITHM.md §1 applied to a vector, element by element
// (matrix-free: M is constant and needed only for the velocity update of docs/THEORY.md §7).
#include "emcontact/fem/discretization.hpp"
#include "kernels/mass_tet4.hpp"

namespace emc::fem {

void Discretization::apply_mass(const Vector& v, Vector& Mv) const {
  auto vo = new_overlap_vector();
  to_overlap(v, *vo);
  Vector mo(overlap_);
  {
    auto vv = vo->getLocalViewDevice(Tpetra::Access::ReadOnly);
    auto vm = mo.getLocalViewDevice(Tpetra::Access::ReadWrite);
    const ElementViews ev = ev_;  // by value: never capture `this` in a device lambda
    Kokkos::parallel_for(
        "emcontact::fem::mass_tet4", Kokkos::RangePolicy<ExecSpace>(0, ev.size()),
        KOKKOS_LAMBDA(const int k) {
          double vk[4][3], pk[4][3];
          ev.gather(vv, k, vk);
          kernels::mass_times(ev.rho(k), ev.Ve(k), vk, pk);
          for (int a = 0; a < 4; ++a)
            for (int i = 0; i < 3; ++i)
              Kokkos::atomic_add(&vm(3 * ev.node_lid(k, a) + i, 0), pk[a][i]);
        });
  }
  Mv.putScalar(0.0);
  Mv.doExport(mo, *exporter_, Tpetra::ADD);
}

}  // namespace emc::fem
