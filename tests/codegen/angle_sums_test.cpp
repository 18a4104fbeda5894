// Sines and cosines of angle sums from their parts' (addition theorems) on hand-built programs:
// which calls go, which stay, and that every output keeps its value.
#include "eomgen/codegen/angle_sums.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "support/ir_builders.hpp"
#include "support/ir_interpreter.hpp"

namespace eomgen {
namespace {

using ir::Op;
using ir::VariableKind;
using namespace testing::ir_builders;

// the arguments of the program's sin and cos calls, each as the set of variables it sums
// (with a sign: -1 - index for a subtracted one)
std::set<std::set<long>> call_arguments(const ir::Program& p) {
  std::set<std::set<long>> arguments;
  const auto index = [&](std::size_t i, bool negative) {
    const long k = static_cast<long>(p.instructions.at(i).variable.index);
    return negative ? -1 - k : k;
  };
  for (const ir::Instruction& in : p.instructions) {
    if (in.op != Op::sin && in.op != Op::cos) continue;
    const ir::Instruction& a = p.instructions.at(in.args[0]);
    std::set<long> terms;
    if (a.op == Op::add) {
      for (std::size_t t : a.args) {
        const bool negative = p.instructions.at(t).op == Op::negate;
        terms.insert(index(negative ? p.instructions.at(t).args[0] : t, negative));
      }
    } else {
      terms.insert(index(in.args[0], false));
    }
    arguments.insert(terms);
  }
  return arguments;
}

// every output equal before and after, at states spread over several turns
void expect_same_values(const ir::Program& before, const ir::Program& after) {
  for (int k = 0; k < 25; ++k) {
    std::map<ir::Variable, double> state;
    for (std::size_t i = 0; i < 4; ++i)
      state[{VariableKind::coordinate, i}] = std::sin(1.7 * k + 2.3 * static_cast<double>(i)) * (3.0 + k % 4);
    const auto expected = testing::evaluate(before, state);
    const auto actual = testing::evaluate(after, state);
    ASSERT_EQ(expected.size(), actual.size());
    for (const auto& [target, value] : expected) EXPECT_NEAR(actual.at(target), value, 1e-14) << "state " << k;
  }
}

TEST(AngleSums, SineOfTwoJointAnglesComesFromTheirSinesAndCosines) {
  // y0 = sin(q0 + q1), y1 = sin(q0), y2 = cos(q1): a planar chain's M and F
  const ir::Program p{{q(0), q(1), op(Op::add, {0, 1}), op(Op::sin, {2}), op(Op::sin, {0}), op(Op::cos, {1})},
                      {{y(0), 3}, {y(1), 4}, {y(2), 5}}};
  const ir::Program r = expand_angle_sums(p);
  EXPECT_EQ(call_arguments(r), (std::set<std::set<long>>{{0}, {1}}));  // sincos(q0), sincos(q1)
  const ir::OperationCounts c = ir::count_operations(r);
  EXPECT_EQ(c.multiplications, 2u);
  EXPECT_EQ(c.additions, 1u);
  expect_same_values(p, r);
}

TEST(AngleSums, ASumWhosePartHasNoSineOrCosineIsLeftAsItIs) {
  // sin(q0 + q1) beside sin(q0) only: cos(q1) and sin(q1) would be new calls
  const ir::Program p{{q(0), q(1), op(Op::add, {0, 1}), op(Op::sin, {2}), op(Op::sin, {0})}, {{y(0), 3}, {y(1), 4}}};
  const ir::Program r = expand_angle_sums(p);
  ASSERT_EQ(r.instructions.size(), p.instructions.size());
  for (std::size_t i = 0; i < p.instructions.size(); ++i) {
    EXPECT_EQ(r.instructions[i].op, p.instructions[i].op);
    EXPECT_EQ(r.instructions[i].args, p.instructions[i].args);
  }
}

TEST(AngleSums, ALongerSumIsBuiltOnAShorterSumTheProgramComputes) {
  // y0 = sin(q0 + q1 + q2), y1 = cos(q0 + q1), y2 = sin(q2); q0 and q1 have no call of their own
  const ir::Program p{{q(0), q(1), q(2), op(Op::add, {0, 1, 2}), op(Op::sin, {3}), op(Op::add, {0, 1}),
                       op(Op::cos, {5}), op(Op::sin, {2})},
                      {{y(0), 4}, {y(1), 6}, {y(2), 7}}};
  const ir::Program r = expand_angle_sums(p);
  EXPECT_EQ(call_arguments(r), (std::set<std::set<long>>{{0, 1}, {2}}));
  expect_same_values(p, r);
}

TEST(AngleSums, SubtractedPartsAndSumsKeepTheirSigns) {
  // y0 = sin(q2 - q0 - q1), y1 = cos(q3 - q2), y2 = cos(q0 + q1), y3 = sin(q2), y4 = cos(q3)
  const ir::Program p{{q(0), q(1), q(2), q(3), op(Op::negate, {0}), op(Op::negate, {1}), op(Op::add, {2, 4, 5}),
                       op(Op::sin, {6}), op(Op::negate, {2}), op(Op::add, {3, 8}), op(Op::cos, {9}),
                       op(Op::add, {0, 1}), op(Op::cos, {11}), op(Op::sin, {2}), op(Op::cos, {3})},
                      {{y(0), 7}, {y(1), 10}, {y(2), 12}, {y(3), 13}, {y(4), 14}}};
  const ir::Program r = expand_angle_sums(p);
  EXPECT_EQ(call_arguments(r), (std::set<std::set<long>>{{0, 1}, {2}, {3}}));
  expect_same_values(p, r);
}

TEST(AngleSums, BothFunctionsOfARewrittenSumAndOfItsPartsAreSharedNotRepeated) {
  // y0 = sin(q0 + q1), y1 = cos(q0 + q1), y2 = sin(q0) * cos(q1): the product is the program's
  const ir::Program p{{q(0), q(1), op(Op::add, {0, 1}), op(Op::sin, {2}), op(Op::cos, {2}), op(Op::sin, {0}),
                       op(Op::cos, {1}), op(Op::multiply, {5, 6})},
                      {{y(0), 3}, {y(1), 4}, {y(2), 7}}};
  const ir::Program r = expand_angle_sums(p);
  EXPECT_EQ(call_arguments(r), (std::set<std::set<long>>{{0}, {1}}));
  // sin q0 cos q1 (kept), cos q0 sin q1, cos q0 cos q1, sin q0 sin q1; a sum and a difference
  const ir::OperationCounts c = ir::count_operations(r);
  EXPECT_EQ(c.multiplications, 4u);
  EXPECT_EQ(c.additions, 3u);  // two sums and the negation of the difference's second term
  expect_same_values(p, r);
}

}  // namespace
}  // namespace eomgen
