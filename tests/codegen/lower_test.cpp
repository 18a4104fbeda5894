// Lowering: sharing, integer powers, canonical order, and errors.
#include "eomgen/codegen/lower.hpp"

#include <gtest/gtest.h>

#include "eomgen/codegen/cpp_printer.hpp"
#include "eomgen/base/error.hpp"
#include "support/expect_throw.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;

struct Symbols {
  GiNaC::realsymbol x{"x"}, y{"y"};
  VariableNames names() const { return {{x, "x"}, {y, "y"}}; }
};

TEST(Lower, SineOfTheSameAngleIsComputedOnce) {
  Symbols s;
  Subexpressions none;
  const ir::Program p = lower({{"a", GiNaC::sin(s.x) * s.y}, {"b", GiNaC::sin(s.x) + s.y}}, none, s.names());
  const ir::OperationCounts c = ir::count_operations(p);
  EXPECT_EQ(c.calls, 1u);
  EXPECT_EQ(ir::count_operations_without_sharing(p).calls, 2u);
}

TEST(Lower, IntegerPowersBecomeRepeatedSquaring) {
  Symbols s;
  Subexpressions none;
  const ir::Program p = lower({{"a", GiNaC::pow(s.x, 4)}}, none, s.names());
  const ir::OperationCounts c = ir::count_operations(p);
  EXPECT_EQ(c.multiplications, 2u);  // x*x, then (x*x)*(x*x)
  EXPECT_EQ(c.calls, 0u);
  EXPECT_EQ(print_cpp(p), "    const Scalar w0 = x * x;\n    a = w0 * w0;\n");
}

TEST(Lower, NegativeAndHalfPowersBecomeDivisionsAndRoots) {
  Symbols s;
  Subexpressions none;
  EXPECT_EQ(print_cpp(lower({{"a", s.y / (s.x * s.x)}}, none, s.names())), "    a = y / (x * x);\n");
  EXPECT_EQ(print_cpp(lower({{"a", GiNaC::sqrt(s.x)}}, none, s.names())), "    a = sqrt(x);\n");
  EXPECT_EQ(print_cpp(lower({{"a", GiNaC::pow(s.x, GiNaC::numeric(-1, 2))}}, none, s.names())),
            "    a = Scalar(1) / sqrt(x);\n");
}

TEST(Lower, IntermediatesAreFollowedAndShared) {
  Symbols s;
  Subexpressions z;
  const ex z1 = z.bind(s.x * s.y + 1);
  const ir::Program p = lower({{"a", z1 * z1}, {"b", z1 + s.x}}, z, s.names());
  EXPECT_EQ(ir::count_operations(p).multiplications, 2u);  // x*y once, z1*z1 once
}

TEST(Lower, ZeroTargetsAreDropped) {
  Symbols s;
  Subexpressions none;
  const ir::Program p = lower({{"a", 0}, {"b", s.x}}, none, s.names());
  ASSERT_EQ(p.outputs.size(), 1u);
  EXPECT_EQ(p.outputs[0].target, "b");
}

TEST(Lower, ResultDoesNotDependOnSymbolCreationOrder) {
  // GiNaC orders terms by symbol serial numbers, so build the same expression from symbols
  // created in opposite orders and compare the printed programs
  auto program = [](bool reversed) {
    GiNaC::realsymbol first(reversed ? "b" : "a"), second(reversed ? "a" : "b");
    const ex a = reversed ? second : first, b = reversed ? first : second;
    Subexpressions none;
    const VariableNames names{{a, "a"}, {b, "b"}};
    return print_cpp(lower({{"y", GiNaC::sin(a) * b + GiNaC::cos(b) * a - a * b * b}}, none, names));
  };
  EXPECT_EQ(program(false), program(true));
}

TEST(Lower, UnknownSymbolIsAnEmitError) {
  Symbols s;
  Subexpressions none;
  GiNaC::realsymbol stranger("stranger");
  EXPECT_THROW_MESSAGE(lower({{"a", stranger * s.x}}, none, s.names()), EmitError,
                       "code emission: the symbol 'stranger' is not an input of this function");
}

TEST(Lower, UnprintableFunctionIsAnEmitError) {
  Symbols s;
  Subexpressions none;
  EXPECT_THROW_MESSAGE(lower({{"a", GiNaC::zeta(s.x)}}, none, s.names()), EmitError,
                       "code emission: the function 'zeta' has no C++ form");
}

}  // namespace
}  // namespace eomgen
