#pragma once
// Small 3-vectors of host code (mesh geometry): difference, dot and cross products, norm. The
// kernels have their own, on raw arrays and device-callable (kernels/math.hpp).
#include <array>
#include <cmath>

namespace emc {

using Vec3 = std::array<double, 3>;

inline Vec3 sub(const Vec3& a, const Vec3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline double dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline double norm(const Vec3& a) {
  return std::sqrt(dot(a, a));
}
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline Vec3 scaled(double s, const Vec3& a) {
  return {s * a[0], s * a[1], s * a[2]};
}

}  // namespace emc
