#include "eomgen/symbolic/subexpressions.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace eomgen {
namespace {

using GiNaC::ex;

TEST(Subexpressions, AtomicValuesAreNotBound) {
  Subexpressions z;
  const GiNaC::realsymbol q("q");
  EXPECT_TRUE(z.bind(q).is_equal(q));
  EXPECT_TRUE(z.bind(ex(3)).is_equal(3));
  EXPECT_TRUE(z.bind(-2 * q).is_equal(-2 * q));
  EXPECT_TRUE(z.bind(GiNaC::sin(q)).is_equal(GiNaC::sin(q)));
  EXPECT_EQ(z.size(), 0u);
}

TEST(Subexpressions, EqualValuesShareOneSymbol) {
  Subexpressions z;
  const GiNaC::realsymbol a("a"), b("b");
  const ex first = z.bind(a * b + 1);
  const ex second = z.bind(1 + b * a);
  EXPECT_TRUE(first.is_equal(second));
  EXPECT_EQ(z.size(), 1u);
  EXPECT_EQ(GiNaC::ex_to<GiNaC::symbol>(first).get_name(), "z1");
}

TEST(Subexpressions, ExpandWritesOutNestedDefinitions) {
  Subexpressions z;
  const GiNaC::realsymbol a("a"), b("b");
  const ex z1 = z.bind(a + b);
  const ex z2 = z.bind(z1 * z1 + a);
  EXPECT_TRUE((z.expand(z2 * 2) - 2 * (GiNaC::pow(a + b, 2) + a)).expand().is_zero());
}

TEST(Subexpressions, EvaluateComputesDefinitionsInOrder) {
  Subexpressions z;
  const GiNaC::realsymbol a("a");
  const ex z1 = z.bind(a * a + 1);
  const ex z2 = z.bind(GiNaC::sqrt(z1) * a);
  const ex value = z.evaluate(z2 + z1, {{a, 2.0}});
  ASSERT_TRUE(GiNaC::is_a<GiNaC::numeric>(value));
  EXPECT_NEAR(GiNaC::ex_to<GiNaC::numeric>(value).to_double(), std::sqrt(5.0) * 2 + 5, 1e-14);
}

// GiNaC writes one value as x*(a - b) in one run and as -x*(b - a) in another: share() must
// see one node there, or the intermediates (and the printed equations) would change from run
// to run
TEST(Subexpressions, ShareTakesAValueAndItsNegationAsOneNode) {
  const GiNaC::realsymbol a("a"), b("b"), x("x"), y("y");
  const ex difference = GiNaC::sin(a) - GiNaC::cos(b);
  const ex negated = GiNaC::cos(b) - GiNaC::sin(a);
  Subexpressions z;
  const ex shared = z.share(GiNaC::lst{GiNaC::exp(x * difference), GiNaC::exp(y * negated)});
  ASSERT_EQ(z.size(), 1u) << shared;  // sin(a) - cos(b) once, with one sign
  const GiNaC::exmap at{{a, 0.3}, {b, 1.1}, {x, 0.7}, {y, -0.4}};
  for (std::size_t i = 0; i < 2; ++i) {
    const ex original = i == 0 ? GiNaC::exp(x * difference) : GiNaC::exp(y * negated);
    const double want = GiNaC::ex_to<GiNaC::numeric>(original.subs(at).evalf()).to_double();
    const double got = GiNaC::ex_to<GiNaC::numeric>(z.evaluate(shared.op(i), at).evalf()).to_double();
    EXPECT_NEAR(got, want, 1e-14) << i;
  }
}

// A negation -X (a product of -1 and one factor) has the magnitude of X: share() must still
// count what X is made of, which it reaches through it (it once took X for the negation's
// second parent and left X's inside uncounted: "unordered_map::at" from eomgen generate)
TEST(Subexpressions, ShareCountsTheInsideOfANegatedNode) {
  const GiNaC::realsymbol a("a"), b("b"), x("x");
  const ex inside = GiNaC::sin(a) + GiNaC::cos(b) * x;
  const ex value = GiNaC::lst{-GiNaC::pow(inside, 2), GiNaC::exp(-GiNaC::pow(inside, 3)) * x};
  Subexpressions z;
  const ex shared = z.share(value);
  const GiNaC::exmap at{{a, 0.3}, {b, 1.1}, {x, 0.7}};
  for (std::size_t i = 0; i < value.nops(); ++i) {
    const double want = GiNaC::ex_to<GiNaC::numeric>(value.op(i).subs(at).evalf()).to_double();
    const double got = GiNaC::ex_to<GiNaC::numeric>(z.evaluate(shared.op(i), at).evalf()).to_double();
    EXPECT_NEAR(got, want, 1e-14) << i;
  }
}

}  // namespace
}  // namespace eomgen
