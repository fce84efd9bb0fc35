#pragma once
// The math functions the kernels use, callable on host and device alike (one place to adapt for
// a device backend instead of Kokkos::Experimental, whose names moved between Kokkos releases).
#include <Kokkos_Core.hpp>
#include <cmath>
#include <limits>

namespace emc::kernels {

KOKKOS_INLINE_FUNCTION double sqrt(double x) {
  return ::sqrt(x);
}
KOKKOS_INLINE_FUNCTION double fabs(double x) {
  return ::fabs(x);
}
KOKKOS_INLINE_FUNCTION double fmin(double a, double b) {
  return a < b ? a : b;
}
KOKKOS_INLINE_FUNCTION double fmax(double a, double b) {
  return a > b ? a : b;
}
KOKKOS_INLINE_FUNCTION constexpr double infinity() {
  return std::numeric_limits<double>::infinity();
}
KOKKOS_INLINE_FUNCTION constexpr double epsilon() {
  return std::numeric_limits<double>::epsilon();
}

}  // namespace emc::kernels
