#pragma once
// The typed tests' list of execution spaces (support/spaces.hpp) and their names.
#include <gtest/gtest.h>

#include <string>

#include "support/spaces.hpp"

namespace emc::kernels::test {

template <class L>
struct ToGtest;
template <class... T>
struct ToGtest<List<T...>> {
  using type = ::testing::Types<T...>;
};

/// Every enabled execution space, as gtest's typed-test list.
using Backends = typename ToGtest<Spaces>::type;

/// The typed tests' names: the execution space's.
struct BackendName {
  template <class T>
  static std::string GetName(int) {
    return T::name();
  }
};

}  // namespace emc::kernels::test
