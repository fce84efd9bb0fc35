// The consistent mass matrix of docs/THEORY.md §1.3 applied to a vector, element by element
// (matrix-free: M is constant and needed only for the velocity update of docs/THEORY.md §7).
#include "emcontact/fem/discretization.hpp"
#include "emcontact/fem/element_loop.hpp"
#include "kernels/mass_tet4.hpp"

namespace emc::fem {
namespace {

using ConstDev =
    decltype(std::declval<const Vector&>().getLocalViewDevice(Tpetra::Access::ReadOnly));
using Dev = decltype(std::declval<Vector&>().getLocalViewDevice(Tpetra::Access::ReadWrite));

/// One element's M_e v_e added into the overlap rows.
struct TetMass {
  ElementViews ev;
  ConstDev v;
  Dev Mv;

  template <bool Atomic>
  KOKKOS_INLINE_FUNCTION void element(const int k) const {
    double vk[4][3], pk[4][3];
    ev.gather(v, k, vk);
    kernels::mass_times(ev.rho(k), ev.Ve(k), ev.massless(k), vk, pk);
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) scatter_add<Atomic>(Mv(3 * ev.node_lid(k, a) + i, 0), pk[a][i]);
  }
};

}  // namespace

void Discretization::apply_mass(const Vector& v, Vector& Mv) const {
  auto vo = new_overlap_vector();
  to_overlap(v, *vo);
  Vector mo(overlap_);
  {
    const TetMass f{ev_, vo->getLocalViewDevice(Tpetra::Access::ReadOnly),
                    mo.getLocalViewDevice(Tpetra::Access::ReadWrite)};
    for_each_element("emcontact::fem::mass_tet4", f, colouring_, model_.scatter, ev_.size());
  }
  Mv.putScalar(0.0);
  Mv.doExport(mo, *exporter_, Tpetra::ADD);
}

}  // namespace emc::fem
