#include "eomgen/mechanics/vector.hpp"

#include <gtest/gtest.h>

#include "eomgen/base/error.hpp"
#include "support/expect_throw.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;

TEST(Vector, TermsInTheSameFrameMergeAndCancel) {
  const GiNaC::realsymbol x("x");
  const Vector u(FrameId{2}, x, 1, 0);
  const Vector w(FrameId{1}, 0, 0, 3);
  const Vector sum = u + w + u;
  ASSERT_EQ(sum.terms().size(), 2u);
  EXPECT_EQ(sum.terms()[0].first.index, 1u);  // sorted by frame
  EXPECT_TRUE(sum.terms()[1].second(0, 0).is_equal(2 * x));
  EXPECT_TRUE((u - u).is_zero());
  EXPECT_TRUE((sum - w - 2 * u).is_zero());
}

TEST(Vector, ScalarProductAndNegation) {
  const GiNaC::realsymbol k("k");
  const Vector u(FrameId{0}, 1, 2, 3);
  const Vector v = k * u;
  EXPECT_TRUE(v.terms()[0].second(2, 0).is_equal(3 * k));
  EXPECT_TRUE((-u).terms()[0].second(1, 0).is_equal(-2));
  EXPECT_TRUE((ex(0) * u).is_zero());
}

TEST(Vector, ComponentsMustBeAColumnOfThree) {
  EXPECT_THROW_MESSAGE(Vector(FrameId{0}, GiNaC::matrix(2, 1)), ModelError,
                       "physical vector: expected 3x1 components, got 2x1");
}

TEST(Vector, MapComponentsAppliesToEveryComponent) {
  const GiNaC::realsymbol x("x");
  const Vector u(FrameId{0}, x * x, x, 1);
  const Vector d = u.map_components([&](const ex& e) { return e.diff(x); });
  EXPECT_TRUE(d.terms()[0].second(0, 0).is_equal(2 * x));
  EXPECT_TRUE(d.terms()[0].second(2, 0).is_zero());
}

}  // namespace
}  // namespace eomgen
