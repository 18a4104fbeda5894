// The split of hand-built programs into their once-per-parameter-set part and their per-call
// parts: what is taken out, how it is numbered, and that the values stay what they were.
#include "eomgen/codegen/parameter_constants.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "eomgen/base/error.hpp"
#include "eomgen/codegen/cpp_printer.hpp"
#include "support/ir_builders.hpp"
#include "support/ir_interpreter.hpp"

namespace eomgen {
namespace {

using ir::Instruction;
using ir::Op;
using ir::VariableKind;

using namespace testing::ir_builders;
using testing::evaluate;

CppPrintOptions options() {
  CppPrintOptions o;
  o.parameter_names = {"a", "m"};
  return o;
}

const std::map<ir::Variable, double> state{{{VariableKind::coordinate, 0}, 0.7},
                                           {{VariableKind::coordinate, 1}, -1.3},
                                           {{VariableKind::parameter, 0}, 2.5},
                                           {{VariableKind::parameter, 1}, 0.4}};

// constants then the per-call program, as the generated Constants and function evaluate them
std::map<ir::Target, double> evaluate_split(const ConstantSplit& split, std::size_t k) {
  std::map<ir::Variable, double> inputs = state;
  for (const auto& [target, value] : evaluate(split.constants, state))
    inputs[{VariableKind::constant, target.row}] = value;
  return evaluate(split.per_call[k], inputs);
}

TEST(ParameterConstants, AParameterOnlyProductIsComputedOncePerParameterSet) {
  // y0 = a * m * q0
  const ir::Program program{{p(0), p(1), q(0), op(Op::multiply, {0, 1, 2})}, {{y(0), 3}}};
  const ConstantSplit split = split_constants({program});
  EXPECT_EQ(print_cpp(split.constants, options()), "    k0 = p.a * p.m;\n");
  EXPECT_EQ(print_cpp(split.per_call[0], options()), "    y(0) = c.k0 * q(0);\n");
  EXPECT_EQ(ir::count_operations(split.per_call[0]).total(), 1u);
  EXPECT_DOUBLE_EQ(evaluate_split(split, 0).at(y(0)), 2.5 * 0.4 * 0.7);
}

TEST(ParameterConstants, AProductWithACoordinateAndAParameterAloneStayInTheCall) {
  // y0 = a * q0, y1 = m, y2 = -a, y3 = 2 * q1
  const ir::Program program{{p(0), q(0), op(Op::multiply, {0, 1}), p(1), op(Op::negate, {0}), num(2), q(1),
                             op(Op::multiply, {5, 6})},
                            {{y(0), 2}, {y(1), 3}, {y(2), 4}, {y(3), 7}}};
  const ConstantSplit split = split_constants({program});
  EXPECT_TRUE(split.constants.instructions.empty());
  EXPECT_TRUE(split.constants.outputs.empty());
  EXPECT_EQ(print_cpp(split.per_call[0], options()),
            "    y(0) = p.a * q(0);\n    y(1) = p.m;\n    y(2) = -p.a;\n    y(3) = Scalar(2) * q(1);\n");
}

TEST(ParameterConstants, TheConstantOperandsOfASumBecomeOneConstantWhereTheFirstWas) {
  // y0 = q0 + a + (-m) + q1
  const ir::Program program{{q(0), p(0), p(1), op(Op::negate, {2}), q(1), op(Op::add, {0, 1, 3, 4})}, {{y(0), 5}}};
  const ConstantSplit split = split_constants({program});
  EXPECT_EQ(print_cpp(split.constants, options()), "    k0 = p.a - p.m;\n");
  EXPECT_EQ(print_cpp(split.per_call[0], options()), "    y(0) = q(0) + c.k0 + q(1);\n");
  EXPECT_DOUBLE_EQ(evaluate_split(split, 0).at(y(0)), 0.7 + 2.5 - 0.4 - 1.3);
}

TEST(ParameterConstants, ADivisionByAConstantBecomesAMultiplicationByItsReciprocal) {
  // y0 = q0 / (a * m), y1 = q1 / 4 (a number stays a divisor)
  const ir::Program program{
      {q(0), p(0), p(1), op(Op::multiply, {1, 2}), op(Op::divide, {0, 3}), q(1), num(4), op(Op::divide, {5, 6})},
      {{y(0), 4}, {y(1), 7}}};
  const ConstantSplit split = split_constants({program});
  EXPECT_EQ(print_cpp(split.constants, options()), "    k0 = Scalar(1) / (p.a * p.m);\n");
  EXPECT_EQ(print_cpp(split.per_call[0], options()), "    y(0) = q(0) * c.k0;\n    y(1) = q(1) / Scalar(4);\n");
  const auto values = evaluate_split(split, 0);
  EXPECT_NEAR(values.at(y(0)), 0.7 / (2.5 * 0.4), 1e-15);
  EXPECT_DOUBLE_EQ(values.at(y(1)), -1.3 / 4);
}

TEST(ParameterConstants, ConstantsAreSharedBetweenProgramsAndNumberedInOrderOfFirstUse) {
  // first: y0 = sin(m) * q0, y1 = a * m (an output that is constant as a whole)
  const ir::Program first{{p(1), op(Op::sin, {0}), q(0), op(Op::multiply, {1, 2}), p(0), op(Op::multiply, {4, 0})},
                          {{y(0), 3}, {y(1), 5}}};
  // second: y0 = a * m * q1 + sin(m)
  const ir::Program second{
      {p(0), p(1), q(1), op(Op::multiply, {0, 1, 2}), op(Op::sin, {1}), op(Op::add, {3, 4})}, {{y(0), 5}}};
  const ConstantSplit split = split_constants({first, second});
  EXPECT_EQ(print_cpp(split.constants, options()), "    k0 = sin(p.m);\n    k1 = p.a * p.m;\n");
  EXPECT_EQ(print_cpp(split.per_call[0], options()), "    y(0) = c.k0 * q(0);\n    y(1) = c.k1;\n");
  EXPECT_EQ(print_cpp(split.per_call[1], options()), "    y(0) = c.k1 * q(1) + c.k0;\n");
  for (std::size_t k = 0; k < 2; ++k)
    for (const auto& [target, value] : evaluate(k == 0 ? first : second, state))
      EXPECT_NEAR(evaluate_split(split, k).at(target), value, 1e-15) << k;
}

TEST(ParameterConstants, AStateDependentSubexpressionSharedWithAConstantOneIsKeptOnce) {
  // y0 = (a * m) * cos(q0) and y1 = cos(q0) + a * m * m: a * m feeds a bigger constant too
  const ir::Program program{{p(0), p(1), op(Op::multiply, {0, 1}), q(0), op(Op::cos, {3}), op(Op::multiply, {2, 4}),
                             op(Op::multiply, {2, 1}), op(Op::add, {4, 6})},
                            {{y(0), 5}, {y(1), 7}}};
  const ConstantSplit split = split_constants({program});
  EXPECT_EQ(print_cpp(split.constants, options()), "    const Scalar w0 = p.a * p.m;\n    k0 = w0;\n    k1 = w0 * p.m;\n");
  EXPECT_EQ(print_cpp(split.per_call[0], options()),
            "    const Scalar w0 = cos(q(0));\n    y(0) = c.k0 * w0;\n    y(1) = w0 + c.k1;\n");
  for (const auto& [target, value] : evaluate(program, state))
    EXPECT_NEAR(evaluate_split(split, 0).at(target), value, 1e-15);
}

TEST(ParameterConstants, AProgramThatAlreadyReadsConstantsIsAGeneratorBug) {
  const ir::Program program{{var(VariableKind::constant, 0)}, {{y(0), 0}}};
  EXPECT_THROW(split_constants({program}), InternalError);
}

}  // namespace
}  // namespace eomgen
