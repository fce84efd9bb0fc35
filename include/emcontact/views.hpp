#pragma once
// A host vector copied into a Kokkos View on the execution space (the inputs of a kernel).
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

}  // namespace emc
