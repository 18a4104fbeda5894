#pragma once
// The scalar types every runtime test suite runs over (double and long double), with readable
// names in the test names.
#include <gtest/gtest.h>

#include <string>
#include <type_traits>

namespace eomrt::testing {

struct ScalarName {
  template <typename T>
  static std::string GetName(int) {
    return std::is_same<T, double>::value ? "double" : "long_double";
  }
};
using Scalars = ::testing::Types<double, long double>;

}  // namespace eomrt::testing
