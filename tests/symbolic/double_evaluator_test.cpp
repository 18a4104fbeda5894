// The double evaluator's sums and products give the same bits whatever order GiNaC keeps their
// operands in (an order that follows addresses and so changes between processes): sums are
// the exact sum rounded once, products multiply magnitudes in increasing order.
#include "eomgen/symbolic/double_evaluator.hpp"

#include <ginac/ginac.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "support/shared_graphs.hpp"

namespace {

using GiNaC::ex;
using GiNaC::realsymbol;

struct Values {
  std::vector<realsymbol> symbols;
  eomgen::DoubleEvaluator eval;

  explicit Values(const std::vector<double>& xs) {
    for (std::size_t i = 0; i < xs.size(); ++i) {
      symbols.emplace_back("x" + std::to_string(i));
      eval.set(symbols.back(), xs[i]);
    }
  }
  ex sum() const {
    ex s = 0;
    for (const auto& x : symbols) s += x;
    return s;
  }
  ex product() const {
    ex p = 1;
    for (const auto& x : symbols) p *= x;
    return p;
  }
};

TEST(DoubleEvaluator, SumIsTheExactSumRoundedOnce) {
  // in any order of plain addition, 1e16 absorbs the 1s
  Values v({1e16, 1.0, -1e16, 1.0});
  EXPECT_EQ(v.eval.value(v.sum(), "sum"), 2.0);
  // 0.1 + 0.2 - 0.3 in doubles is the exact sum of the three doubles
  Values w({0.1, 0.2, -0.3});
  EXPECT_EQ(w.eval.value(w.sum(), "sum"), 2.7755575615628914e-17);
}

TEST(DoubleEvaluator, SumRoundsHalfwayCasesByTheTermsBelow) {
  // 1 + 2^-53 is halfway between 1 and the next double: ties to even gives 1, but a tiny
  // positive term below decides it upwards
  Values v({1.0, std::ldexp(1.0, -53), std::ldexp(1.0, -80)});
  EXPECT_EQ(v.eval.value(v.sum(), "sum"), 1.0 + std::ldexp(1.0, -52));
  Values w({1.0, std::ldexp(1.0, -53)});
  EXPECT_EQ(w.eval.value(w.sum(), "sum"), 1.0);
}

TEST(DoubleEvaluator, SumAndProductAreTheSameForEveryOrderOfTheSameValues) {
  std::vector<double> xs{0.7234, -1.3e-3, 12.5, 3.3e-9, -0.333, 1.0 / 3.0};
  std::sort(xs.begin(), xs.end());
  double first_sum = 0, first_product = 0;
  bool first = true;
  do {
    Values v(xs);  // new symbols: GiNaC orders them differently each time
    const double s = v.eval.value(v.sum(), "sum"), p = v.eval.value(v.product(), "product");
    if (first) {
      first_sum = s;
      first_product = p;
      first = false;
    }
    EXPECT_EQ(s, first_sum);
    EXPECT_EQ(p, first_product);
  } while (std::next_permutation(xs.begin(), xs.end()));
}

TEST(DoubleEvaluator, NegatedOperandsGiveTheNegatedValue) {
  // GiNaC writes one value as l*(a - b) in one process and -l*(b - a) in another
  const realsymbol a("a"), b("b"), c("c"), l("l");
  eomgen::DoubleEvaluator eval;
  eval.set(a, 0.1);
  eval.set(b, 0.7);
  eval.set(c, -0.30000000000000004);
  eval.set(l, 1.9);
  EXPECT_EQ(eval.value(l * (a - b + c), "x"), eval.value(-l * (b - a - c), "x"));
  EXPECT_EQ(eval.value(a - b + c, "x"), -eval.value(b - a - c, "x"));
}

TEST(DoubleEvaluator, ZeroResultIsPositiveZero) {
  Values v({0.5, -0.5});
  EXPECT_FALSE(std::signbit(v.eval.value(v.sum(), "sum")));
  Values w({-0.0, 3.0});
  EXPECT_FALSE(std::signbit(w.eval.value(w.product(), "product")));
}

TEST(DoubleEvaluator, NonFiniteOperandsFollowIeee) {
  Values v({INFINITY, 1.0});
  EXPECT_EQ(v.eval.value(v.sum(), "sum"), INFINITY);
  Values w({INFINITY, -INFINITY});
  EXPECT_TRUE(std::isnan(w.eval.value(w.sum(), "sum")));
  Values z({0.0, INFINITY});
  EXPECT_TRUE(std::isnan(z.eval.value(z.product(), "product")));
  Values big({1e308, 1e308, -1e308});
  EXPECT_EQ(big.eval.value(big.sum(), "sum"), 1e308);  // an intermediate overflow of plain addition
}

TEST(DoubleEvaluator, EvaluatesEachSharedNodeOnce) {
  // 2^60 paths through a few hundred nodes: a walk of the tree would not end
  const realsymbol x("x");
  eomgen::DoubleEvaluator eval;
  eval.set(x, 0.001);
  double expected = 0.001;
  for (int i = 0; i < 60; ++i) expected = expected * (1 + std::sin(expected * std::pow(0.001, -1.0))) + 0.001;
  EXPECT_DOUBLE_EQ(eval.value(eomgen::testing::doubling_graph(x, 60), "graph"), expected);
}

}  // namespace
