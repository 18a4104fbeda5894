// The printer on hand-built programs: precedence, signs, temporaries, numbers.
#include "eomgen/codegen/cpp_printer.hpp"

#include <gtest/gtest.h>

#include "support/ir_builders.hpp"

namespace eomgen {
namespace {

using ir::Instruction;
using ir::Op;
using ir::VariableKind;

using namespace testing::ir_builders;
ir::Target M(std::size_t row, std::size_t column) { return {ir::Array::mass_matrix, row, column}; }

CppPrintOptions with_parameters() {
  CppPrintOptions options;
  options.parameter_names = {"x", "m"};
  return options;
}

TEST(CppPrinter, SumOfProductNeedsNoParentheses) {
  ir::Program p{{q(0), q(1), q(2), op(Op::multiply, {1, 2}), op(Op::add, {0, 3})}, {{y(0), 4}}};
  EXPECT_EQ(print_cpp(p), "    y(0) = q(0) + q(1) * q(2);\n");
}

TEST(CppPrinter, ProductOfSumIsParenthesized) {
  ir::Program p{{q(0), q(1), q(2), op(Op::add, {0, 1}), op(Op::multiply, {3, 2})}, {{y(0), 4}}};
  EXPECT_EQ(print_cpp(p), "    y(0) = (q(0) + q(1)) * q(2);\n");
}

TEST(CppPrinter, NegatedTermsBecomeSubtractionsAndNegatedFactorsAreParenthesized) {
  ir::Program p{{q(0), q(1), op(Op::negate, {0}), op(Op::add, {2, 1}), op(Op::multiply, {1, 2})},
                {{y(0), 3}, {y(1), 4}}};
  EXPECT_EQ(print_cpp(p), "    const Scalar w0 = -q(0);\n    y(0) = w0 + q(1);\n    y(1) = q(1) * w0;\n");
  ir::Program r{{q(0), q(1), op(Op::negate, {0}), op(Op::add, {2, 1})}, {{y(0), 3}}};
  EXPECT_EQ(print_cpp(r), "    y(0) = q(1) - q(0);\n");
}

TEST(CppPrinter, NumberOperandsUseTheScalarType) {
  ir::Program r{{p(0), num(0.5), op(Op::multiply, {1, 0})}, {{y(0), 2}}};
  CppPrintOptions options = with_parameters();
  EXPECT_EQ(print_cpp(r, options), "    y(0) = Scalar(0.5) * p.x;\n");
  options.scalar = "float";
  EXPECT_EQ(print_cpp(r, options), "    y(0) = float(0.5) * p.x;\n");
}

TEST(CppPrinter, DivisorThatIsAProductIsParenthesized) {
  ir::Program p{{q(0), q(1), q(2), op(Op::multiply, {1, 2}), op(Op::divide, {0, 3})}, {{y(0), 4}}};
  EXPECT_EQ(print_cpp(p), "    y(0) = q(0) / (q(1) * q(2));\n");
}

TEST(CppPrinter, SharedValuesBecomeTemporariesInOrder) {
  ir::Program p{{q(0), op(Op::sin, {0}), op(Op::sqrt, {0}), op(Op::multiply, {1, 2})}, {{M(0, 0), 3}, {M(1, 1), 1}}};
  EXPECT_EQ(print_cpp(p), "    const Scalar w0 = sin(q(0));\n    M(0, 0) = w0 * sqrt(q(0));\n    M(1, 1) = w0;\n");
}

TEST(CppPrinter, SineAndCosineOfOneAngleAreBothComputedBeforeTheFirstOutput) {
  // an output may alias q, so cos(q(0)) written inside M(1, 1)'s statement would be read after
  // M(0, 0) is stored, and the compiler could not merge it with sin(q(0)) into one sincos
  ir::Program p{{q(0), op(Op::sin, {0}), op(Op::cos, {0}), q(1), op(Op::multiply, {1, 3})},
                {{M(0, 0), 4}, {M(1, 1), 2}}};
  EXPECT_EQ(print_cpp(p), "    const Scalar w0 = sin(q(0));\n    const Scalar w1 = cos(q(0));\n    M(0, 0) = w0 * q(1);\n"
                          "    M(1, 1) = w1;\n");
}

TEST(CppPrinter, WithoutSharingEveryUseIsWrittenOut) {
  ir::Program p{{q(0), op(Op::sin, {0}), op(Op::cos, {0}), op(Op::multiply, {1, 2})}, {{M(0, 0), 3}, {M(1, 1), 1}}};
  CppPrintOptions options;
  options.share_subexpressions = false;
  EXPECT_EQ(print_cpp(p, options), "    M(0, 0) = sin(q(0)) * cos(q(0));\n    M(1, 1) = sin(q(0));\n");
}

TEST(CppPrinter, NumbersAreWrappedInTheScalarTypeAndRoundTrip) {
  EXPECT_EQ(cpp_number(2.0, "Scalar"), "Scalar(2)");
  EXPECT_EQ(cpp_number(0.1, "Scalar"), "Scalar(0.1)");
  EXPECT_EQ(cpp_number(1.0 / 3.0, "double"), "double(0.3333333333333333)");
  EXPECT_EQ(std::stod(cpp_number(1.0 / 3.0, "").substr(1)), 1.0 / 3.0);
}

TEST(CppPrinter, CallsPrintTheirArgumentsWithoutExtraParentheses) {
  ir::Program r{{p(1), p(0), op(Op::add, {0, 1}), op(Op::atan2, {2, 1})}, {{y(0), 3}}};
  EXPECT_EQ(print_cpp(r, with_parameters()), "    y(0) = atan2(p.m + p.x, p.x);\n");
}

TEST(CppPrinter, EveryCallPrintsAsItsCmathFunction) {
  for (const ir::CallOp& call : ir::call_ops) {
    ir::Program p{{q(0), q(1)}, {}};
    p.instructions.push_back(op(call.op, call.arity == 1 ? std::vector<std::size_t>{0} : std::vector<std::size_t>{0, 1}));
    p.outputs.push_back({y(0), 2});
    const std::string arguments = call.arity == 1 ? "q(0)" : "q(0), q(1)";
    EXPECT_EQ(print_cpp(p), "    y(0) = " + std::string(call.cpp_name) + "(" + arguments + ");\n");
  }
}

// the spelling the generated headers have always had (and their model hashes depend on)
TEST(CppPrinter, VariablesAreTheArgumentsOfTheGeneratedFunctions) {
  const CppPrintOptions options = with_parameters();
  EXPECT_EQ(cpp_variable({VariableKind::time, 0}, options), "t");
  EXPECT_EQ(cpp_variable({VariableKind::coordinate, 2}, options), "q(2)");
  EXPECT_EQ(cpp_variable({VariableKind::rate, 0}, options), "qd(0)");
  EXPECT_EQ(cpp_variable({VariableKind::input, 1}, options), "u(1)");
  EXPECT_EQ(cpp_variable({VariableKind::acceleration, 3}, options), "qdd(3)");
  EXPECT_EQ(cpp_variable({VariableKind::multiplier, 0}, options), "lambda(0)");
  EXPECT_EQ(cpp_variable({VariableKind::parameter, 1}, options), "p.m");
}

TEST(CppPrinter, ParametersAreReadThroughTheirIdentifiers) {
  CppPrintOptions options;
  options.parameter_names = {"int", "_hidden"};
  EXPECT_EQ(cpp_variable({VariableKind::parameter, 0}, options), "p.int_");
  EXPECT_EQ(cpp_variable({VariableKind::parameter, 1}, options), "p.v_0_hidden_");
}

TEST(CppPrinter, TargetsAreEntriesOfTheOutputArguments) {
  using ir::Array;
  EXPECT_EQ(cpp_target({Array::mass_matrix, 0, 1}), "M(0, 1)");
  EXPECT_EQ(cpp_target({Array::forcing, 2, 0}), "F(2)");
  EXPECT_EQ(cpp_target({Array::constraint_jacobian, 1, 0}), "Xi(1, 0)");
  EXPECT_EQ(cpp_target({Array::constraint_rate_term, 0, 0}), "Xi_t(0)");
  EXPECT_EQ(cpp_target({Array::constraint_acceleration_term, 1, 0}), "b(1)");
  EXPECT_EQ(cpp_target({Array::holonomic_residuals, 0, 0}), "phi(0)");
  EXPECT_EQ(cpp_target({Array::outputs, 4, 0}), "y(4)");
  EXPECT_EQ(cpp_target({Array::kinetic_energy, 0, 0}), "T");
  EXPECT_EQ(cpp_target({Array::potential_energy, 0, 0}), "V");
  EXPECT_EQ(cpp_target({Array::stiffness, 1, 2}), "K(1, 2)");
  EXPECT_EQ(cpp_target({Array::damping, 0, 0}), "D(0, 0)");
  EXPECT_EQ(cpp_target({Array::input_matrix, 1, 0}), "B_u(1, 0)");
  EXPECT_EQ(cpp_target({Array::acceleration_constraint_by_q, 0, 3}), "S_q(0, 3)");
  EXPECT_EQ(cpp_target({Array::acceleration_constraint_by_qd, 1, 1}), "S_qd(1, 1)");
  EXPECT_EQ(cpp_target({Array::constants, 3, 0}), "k3");
}

TEST(CppPrinter, InsideTheConstantsOverloadsConstantsAndParametersAreReadFromTheConstants) {
  CppPrintOptions options = with_parameters();
  options.parameters = "c.p";
  ir::Program r{{var(VariableKind::constant, 2), q(0), op(Op::multiply, {0, 1}), p(1), op(Op::add, {2, 3})},
                {{y(0), 4}}};
  EXPECT_EQ(print_cpp(r, options), "    y(0) = c.k2 * q(0) + c.p.m;\n");
  EXPECT_EQ(cpp_variable({VariableKind::constant, 7}, options), "c.k7");
}

}  // namespace
}  // namespace eomgen
