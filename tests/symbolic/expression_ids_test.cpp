// Numbers for the values of expressions: equal values share one whatever nodes hold them,
// different values never do, and numbering follows the graph of shared nodes, never the tree.
#include "eomgen/symbolic/expression_ids.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "eomgen/symbolic/expression_map.hpp"
#include "support/shared_graphs.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;

TEST(ExpressionIds, EqualValuesBuiltApartShareANumber) {
  const GiNaC::realsymbol a("a"), b("b");
  ExpressionIds ids;
  EXPECT_EQ(ids(a * b + 1), ids(1 + b * a));
  EXPECT_EQ(ids(GiNaC::sin(a - b) * 3), ids(3 * GiNaC::sin(-b + a)));
  EXPECT_EQ(ids(GiNaC::pow(a, 2)), ids(a * a));
  EXPECT_EQ(ids(GiNaC::lst{a, b}), ids(GiNaC::lst{a, b}));
  // a symbol copied into new nodes is still the symbol
  EXPECT_EQ(ids(ex(a)), ids(ex(GiNaC::realsymbol(a))));
}

TEST(ExpressionIds, DifferentValuesGetDifferentNumbers) {
  const GiNaC::realsymbol a("a"), b("b"), same_name("a");
  ExpressionIds ids;
  const std::vector<ex> values = {a,
                                  b,
                                  same_name,  // another symbol of the same name
                                  2 * a,
                                  3 * a,
                                  a + 1,
                                  a + 2,
                                  a * b,
                                  a / b,
                                  GiNaC::pow(a, 2),
                                  GiNaC::pow(a, 3),
                                  GiNaC::sin(a),
                                  GiNaC::cos(a),
                                  GiNaC::atan2(a, b),
                                  GiNaC::atan2(b, a),
                                  GiNaC::lst{a, b},
                                  GiNaC::lst{b, a},
                                  GiNaC::matrix{{a, b, 1}, {2, 3, 4}},
                                  GiNaC::matrix{{a, b}, {1, 2}, {3, 4}},
                                  ex(GiNaC::numeric(1, 3)),
                                  ex(0.1),
                                  GiNaC::Pi};
  std::set<ExpressionIds::Id> numbers;
  for (const ex& v : values) numbers.insert(ids(v));
  EXPECT_EQ(numbers.size(), values.size());
}

TEST(ExpressionIds, AGraphIsNumberedNodeByNodeAndTwoCopiesAreOneValue) {
  // 2^60 paths each: a walk of the tree, or a structural comparison of the two copies (GiNaC's
  // ex_is_equal on equal hash values), would not end
  const GiNaC::realsymbol x("x");
  const ex first = testing::doubling_graph(x, 60), second = testing::doubling_graph(x, 60);
  ExpressionIds ids;
  EXPECT_EQ(ids(first), ids(second));
  EXPECT_LT(ids.size(), 6u * 60 + 10);
}

TEST(ExpressionMap, FindsAValueStoredUnderAnotherNodeAndKeepsReferencesValid) {
  const GiNaC::realsymbol x("x");
  ExpressionMap<std::string> map;
  std::string* stored = map.emplace(testing::doubling_graph(x, 50), "graph").first;
  EXPECT_FALSE(map.emplace(testing::doubling_graph(x, 50), "again").second);
  for (int i = 0; i < 1000; ++i) map.emplace(x + i, std::to_string(i));
  ASSERT_NE(map.find(testing::doubling_graph(x, 50)), nullptr);
  EXPECT_EQ(stored, map.find(testing::doubling_graph(x, 50)));
  EXPECT_EQ(*stored, "graph");
  EXPECT_EQ(map.find(x + 1001), nullptr);
  EXPECT_EQ(map[x + 7], "7");
  EXPECT_EQ(map.size(), 1001u);
}

// The table remembers nodes by address: the nodes of a value dropped by every other owner
// must not be freed and reused for another value while the table lives.
TEST(ExpressionMap, ANodeDroppedByItsOwnerIsNotMistakenForANewOne) {
  const GiNaC::realsymbol x("x"), y("y");
  ExpressionMap<int> map;
  for (int i = 0; i < 2000; ++i) {
    map.emplace(GiNaC::sin(x + i) * y, i);  // every temporary dies here
    const int* found = map.find(GiNaC::cos(x - i) * y);
    ASSERT_EQ(found, nullptr) << i;
  }
  for (int i = 0; i < 2000; ++i) ASSERT_EQ(*map.find(y * GiNaC::sin(i + x)), i);
}

}  // namespace
}  // namespace eomgen
