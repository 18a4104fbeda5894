// The printer on hand-built programs: precedence, signs, temporaries, numbers.
#include "eomgen/codegen/cpp_printer.hpp"

#include <gtest/gtest.h>

namespace eomgen {
namespace {

using ir::Instruction;
using ir::Op;

Instruction var(const char* name) { return Instruction{Op::variable, {}, 0.0, name}; }
Instruction num(double v) { return Instruction{Op::number, {}, v, {}}; }
Instruction op(Op o, std::vector<std::size_t> args) { return Instruction{o, std::move(args), 0.0, {}}; }

TEST(CppPrinter, SumOfProductNeedsNoParentheses) {
  ir::Program p{{var("a"), var("b"), var("c"), op(Op::multiply, {1, 2}), op(Op::add, {0, 3})}, {{"y", 4}}};
  EXPECT_EQ(print_cpp(p), "    y = a + b * c;\n");
}

TEST(CppPrinter, ProductOfSumIsParenthesized) {
  ir::Program p{{var("a"), var("b"), var("c"), op(Op::add, {0, 1}), op(Op::multiply, {3, 2})}, {{"y", 4}}};
  EXPECT_EQ(print_cpp(p), "    y = (a + b) * c;\n");
}

TEST(CppPrinter, NegatedTermsBecomeSubtractionsAndNegatedFactorsAreParenthesized) {
  ir::Program p{{var("a"), var("b"), op(Op::negate, {0}), op(Op::add, {2, 1}), op(Op::multiply, {1, 2})},
                {{"y", 3}, {"z", 4}}};
  EXPECT_EQ(print_cpp(p), "    const Scalar w0 = -a;\n    y = w0 + b;\n    z = b * w0;\n");
  ir::Program q{{var("a"), var("b"), op(Op::negate, {0}), op(Op::add, {2, 1})}, {{"y", 3}}};
  EXPECT_EQ(print_cpp(q), "    y = b - a;\n");
}

TEST(CppPrinter, NumberOperandsUseTheScalarType) {
  ir::Program p{{var("x"), num(0.5), op(Op::multiply, {1, 0})}, {{"y", 2}}};
  EXPECT_EQ(print_cpp(p), "    y = Scalar(0.5) * x;\n");
  CppPrintOptions options;
  options.scalar = "float";
  EXPECT_EQ(print_cpp(p, options), "    y = float(0.5) * x;\n");
}

TEST(CppPrinter, DivisorThatIsAProductIsParenthesized) {
  ir::Program p{{var("a"), var("b"), var("c"), op(Op::multiply, {1, 2}), op(Op::divide, {0, 3})}, {{"y", 4}}};
  EXPECT_EQ(print_cpp(p), "    y = a / (b * c);\n");
}

TEST(CppPrinter, SharedValuesBecomeTemporariesInOrder) {
  ir::Program p{{var("q(0)"), op(Op::sin, {0}), op(Op::cos, {0}), op(Op::multiply, {1, 2})},
                {{"M(0, 0)", 3}, {"M(1, 1)", 1}}};
  EXPECT_EQ(print_cpp(p), "    const Scalar w0 = sin(q(0));\n    M(0, 0) = w0 * cos(q(0));\n    M(1, 1) = w0;\n");
}

TEST(CppPrinter, WithoutSharingEveryUseIsWrittenOut) {
  ir::Program p{{var("q(0)"), op(Op::sin, {0}), op(Op::cos, {0}), op(Op::multiply, {1, 2})},
                {{"M(0, 0)", 3}, {"M(1, 1)", 1}}};
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
  ir::Program p{{var("y"), var("x"), op(Op::add, {0, 1}), op(Op::atan2, {2, 1})}, {{"r", 3}}};
  EXPECT_EQ(print_cpp(p), "    r = atan2(y + x, x);\n");
}

}  // namespace
}  // namespace eomgen
