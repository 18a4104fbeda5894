// Differentiation and substitution that follow the graph: on a small tree they give GiNaC's own
// results, on a graph of 2^60 paths they finish and give the right numbers.
#include "eomgen/symbolic/graph_calculus.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "eomgen/symbolic/double_evaluator.hpp"
#include "eomgen/symbolic/expression_ids.hpp"
#include "support/shared_graphs.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;

// e_{i+1} = e_i (1 + sin(e_i / x)) + x in doubles, with its derivative in x carried along
struct ValueAndSlope {
  double value, slope;
};
ValueAndSlope doubling_graph_at(double x, int depth) {
  double e = x, de = 1;
  for (int i = 0; i < depth; ++i) {
    const double r = e * std::pow(x, -1.0), dr = de / x - e / (x * x);
    const double next = e * (1 + std::sin(r)) + x;
    de = de * (1 + std::sin(r)) + e * std::cos(r) * dr + 1;
    e = next;
  }
  return {e, de};
}

TEST(GraphCalculus, SmallTreesGetGinacsOwnResults) {
  const GiNaC::realsymbol q("q"), l("l"), qd("qd");
  const ex e = l * GiNaC::sin(q) * GiNaC::cos(q) + GiNaC::pow(q, 3) / l;
  EXPECT_TRUE(derivative(e, q).is_equal(e.diff(q)));
  EXPECT_TRUE(directional_derivative(e, {{q, qd}}).is_equal(e.diff(q) * qd));
  EXPECT_TRUE(substitute(e, {{q, 0}}).is_equal(e.subs(q == 0)));
}

TEST(GraphCalculus, AGraphOfTwoToTheSixtyPathsIsDifferentiatedNodeByNode) {
  const GiNaC::realsymbol x("x");
  const ex e = testing::doubling_graph(x, 60);
  ASSERT_FALSE(is_small_tree(e, 1e6));
  const ex de = derivative(e, x);
  DoubleEvaluator at;
  at.set(x, 0.001);
  const ValueAndSlope expected = doubling_graph_at(0.001, 60);
  EXPECT_NEAR(at.value(de, "de/dx"), expected.slope, 1e-9 * std::abs(expected.slope));
  // along a rate: de/dx * xd
  const GiNaC::realsymbol xd("xd");
  at.set(xd, -2.5);
  EXPECT_NEAR(at.value(directional_derivative(e, {{x, xd}}), "de/dt"), -2.5 * expected.slope,
              1e-9 * std::abs(expected.slope));
}

TEST(GraphCalculus, SubstitutionInAGraphGivesTheSameGraphOfTheNewSymbol) {
  const GiNaC::realsymbol x("x"), y("y");
  ExpressionIds ids;
  EXPECT_EQ(ids(substitute(testing::doubling_graph(x, 60), {{x, y}})), ids(testing::doubling_graph(y, 60)));
  DoubleEvaluator at;
  EXPECT_NEAR(at.value(substitute(testing::doubling_graph(x, 60), {{x, 0.001}}), "e"),
              doubling_graph_at(0.001, 60).value, 1e-9 * doubling_graph_at(0.001, 60).value);
}

TEST(GraphCalculus, SmallTreesAreToldApartFromLargeOnesWithinTheirLimit) {
  const GiNaC::realsymbol x("x");
  EXPECT_TRUE(is_small_tree(GiNaC::sin(x) + 1, 5));
  EXPECT_FALSE(is_small_tree(GiNaC::sin(x) + 1, 3));
  EXPECT_FALSE(is_small_tree(testing::doubling_graph(x, 60), 1000));  // finds out within its limit
}

}  // namespace
}  // namespace eomgen
