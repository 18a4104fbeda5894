#include "eomgen/symbolic/simplify.hpp"

#include <gtest/gtest.h>

namespace eomgen {
namespace {

TEST(SimplifyForDisplay, RemovesPythagoreanPairs) {
  const GiNaC::realsymbol x("x"), y("y"), m("m");
  using GiNaC::cos;
  using GiNaC::pow;
  using GiNaC::sin;
  EXPECT_TRUE(simplify_for_display(pow(sin(x), 2) + pow(cos(x), 2)).is_equal(1));
  EXPECT_TRUE(simplify_for_display(m * pow(sin(x), 2) * pow(sin(y), 2) + m * pow(cos(x), 2) * pow(sin(y), 2) +
                                   m * pow(cos(y), 2))
                  .is_equal(m));
  // sin^3 also reduces: sin^3 + sin cos^2 = sin
  EXPECT_TRUE(simplify_for_display(pow(sin(x), 3) + sin(x) * pow(cos(x), 2)).is_equal(sin(x)));
}

}  // namespace
}  // namespace eomgen
