#pragma once
// The size of the regression cases that have a long and a short form (docs/developer-guide.md,
// "Tests"): the ctest entries labelled `long` (run by `ctest -C long -L long`) set
// EMC_LONG_TESTS=1 and run the full-size cases; the default suite runs the short forms (fewer
// steps, a smaller mesh) asserting the same properties.
#include <cstdlib>
#include <cstring>

namespace emc::testing {

inline bool long_tests() {
  const char* v = std::getenv("EMC_LONG_TESTS");
  return v != nullptr && std::strcmp(v, "1") == 0;
}

}  // namespace emc::testing
