#pragma once
// A host vector copied into a Kokkos View on the execution space (the inputs of a kernel), and a
// Tpetra vector's local column as the kernel library's dof vector.
#include <Kokkos_Core.hpp>
#include <vector>

#include "emcontact/types.hpp"

namespace emc {

template <class T>
Kokkos::View<T*, ExecSpace> to_view(const char* label, const std::vector<T>& v) {
  Kokkos::View<T*, ExecSpace> out(Kokkos::ViewAllocateWithoutInitializing(label), v.size());
  auto h = Kokkos::create_mirror_view(out);
  for (std::size_t k = 0; k < v.size(); ++k) h(k) = v[k];
  Kokkos::deep_copy(out, h);
  return out;
}

/// v's local column on the device, read only (ReadOnly access) or writable (ReadWrite).
inline Kokkos::View<const double*, Kokkos::LayoutLeft, MemSpace> read_column(const Vector& v) {
  return Kokkos::subview(v.getLocalViewDevice(Tpetra::Access::ReadOnly), Kokkos::ALL(), 0);
}
inline Kokkos::View<double*, Kokkos::LayoutLeft, MemSpace> write_column(Vector& v) {
  return Kokkos::subview(v.getLocalViewDevice(Tpetra::Access::ReadWrite), Kokkos::ALL(), 0);
}

}  // namespace emc
