#pragma once
// A host reference sum for the loop tests: its value, the count of its terms and the sum of
// their magnitudes, which bound how far another order of the same terms may land.
#include <cmath>
#include <limits>

namespace emc::kernels::test {

struct Sum {
  double value = 0, magnitude = 0;
  int terms = 0;
  void add(double v) {
    value += v;
    magnitude += std::fabs(v);
    ++terms;
  }
  /// |s' - s| <= 2 (c - 1) eps sum |t| for c terms t reordered (bitwise: a host backend);
  /// a device, whose compiler may also fuse products, within 1e-12 of the magnitudes.
  double tolerance(bool bitwise) const {
    constexpr double eps = std::numeric_limits<double>::epsilon();
    return bitwise ? 2 * (terms > 1 ? terms - 1 : 0) * eps * magnitude : 1e-12 * magnitude;
  }
};

}  // namespace emc::kernels::test
