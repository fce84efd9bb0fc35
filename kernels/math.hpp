#pragma once
// The math functions the kernels use, callable on host and device alike (one place to adapt for
// a device backend instead of Kokkos::Experimental, whose names moved between Kokkos releases).
#include <Kokkos_Core.hpp>
#include <cfloat>
#include <cmath>

/// The join of a reducer functor whose static join_into(a, b) adds b into a: through volatile
/// references before Kokkos 3.7 (what Kokkos 3.4's threaded reductions call), plain ones after
/// (3.7 deprecates the volatile join, 4.0 refuses it). Value is a type, which parentheses would
/// turn into an expression.
// NOLINTBEGIN(bugprone-macro-parentheses)
#if KOKKOS_VERSION < 30700
#define EMC_KERNELS_REDUCER_JOIN(Value)                                                \
  KOKKOS_INLINE_FUNCTION void join(volatile Value& a, const volatile Value& b) const { \
    join_into(a, b);                                                                   \
  }
#else
#define EMC_KERNELS_REDUCER_JOIN(Value)                              \
  KOKKOS_INLINE_FUNCTION void join(Value& a, const Value& b) const { \
    join_into(a, b);                                                 \
  }
#endif
// NOLINTEND(bugprone-macro-parentheses)

namespace emc::kernels {

KOKKOS_INLINE_FUNCTION double sqrt(double x) {
  return ::sqrt(x);
}
KOKKOS_INLINE_FUNCTION double log1p(double x) {
  return ::log1p(x);
}
KOKKOS_INLINE_FUNCTION double fabs(double x) {
  return ::fabs(x);
}
KOKKOS_INLINE_FUNCTION float fabs(float x) {
  return ::fabsf(x);
}
KOKKOS_INLINE_FUNCTION double fmin(double a, double b) {
  return a < b ? a : b;
}
KOKKOS_INLINE_FUNCTION double fmax(double a, double b) {
  return a > b ? a : b;
}
/// +inf and the machine epsilon 2^-52 from the C macros, as Kokkos' own numeric traits (the
/// std::numeric_limits functions are host functions, not callable in a CUDA kernel).
KOKKOS_INLINE_FUNCTION constexpr double infinity() {
  return HUGE_VAL;
}
KOKKOS_INLINE_FUNCTION constexpr double epsilon() {
  return DBL_EPSILON;
}

/// The index of the lowest set bit of m != 0 (a count of trailing zeros).
KOKKOS_INLINE_FUNCTION int lowest_set_bit(unsigned m) {
#if defined(__CUDA_ARCH__) || defined(__HIP_DEVICE_COMPILE__)
  return __ffs(static_cast<int>(m)) - 1;
#else
  return __builtin_ctz(m);
#endif
}

/// c = a x b.
KOKKOS_INLINE_FUNCTION void cross(const double a[3], const double b[3], double c[3]) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

/// m = (a + b) / 2: a point at the mid-point of two configurations.
KOKKOS_INLINE_FUNCTION void midpoint(const double a[3], const double b[3], double m[3]) {
  for (int i = 0; i < 3; ++i) m[i] = 0.5 * (a[i] + b[i]);
}

/// The same for the three nodes of a facet.
KOKKOS_INLINE_FUNCTION void midpoint(const double a[3][3], const double b[3][3], double m[3][3]) {
  for (int k = 0; k < 3; ++k) midpoint(a[k], b[k], m[k]);
}

}  // namespace emc::kernels
