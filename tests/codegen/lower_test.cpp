// Lowering: sharing, integer powers, canonical order, and errors.
#include "eomgen/codegen/lower.hpp"

#include <gtest/gtest.h>

#include "eomgen/codegen/cpp_printer.hpp"
#include "eomgen/base/error.hpp"
#include "support/expect_throw.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;

// x and y are coordinates 0 and 1 (printed q(0) and q(1)), named "x" and "y" for the order
struct Symbols {
  GiNaC::realsymbol x{"x"}, y{"y"};
  VariableNames names() const {
    return {{x, {{ir::VariableKind::coordinate, 0}, "x"}}, {y, {{ir::VariableKind::coordinate, 1}, "y"}}};
  }
};

// outputs a and b are y(0) and y(1)
const ir::Target a{ir::Array::outputs, 0, 0}, b{ir::Array::outputs, 1, 0};

TEST(Lower, SineOfTheSameAngleIsComputedOnce) {
  Symbols s;
  Subexpressions none;
  const ir::Program p = lower({{a, GiNaC::sin(s.x) * s.y}, {b, GiNaC::sin(s.x) + s.y}}, none, s.names());
  const ir::OperationCounts c = ir::count_operations(p);
  EXPECT_EQ(c.calls, 1u);
  EXPECT_EQ(ir::count_operations_without_sharing(p).calls, 2u);
}

TEST(Lower, IntegerPowersBecomeRepeatedSquaring) {
  Symbols s;
  Subexpressions none;
  const ir::Program p = lower({{a, GiNaC::pow(s.x, 4)}}, none, s.names());
  const ir::OperationCounts c = ir::count_operations(p);
  EXPECT_EQ(c.multiplications, 2u);  // x*x, then (x*x)*(x*x)
  EXPECT_EQ(c.calls, 0u);
  EXPECT_EQ(print_cpp(p), "    const Scalar w0 = q(0) * q(0);\n    y(0) = w0 * w0;\n");
}

TEST(Lower, NegativeAndHalfPowersBecomeDivisionsAndRoots) {
  Symbols s;
  Subexpressions none;
  EXPECT_EQ(print_cpp(lower({{a, s.y / (s.x * s.x)}}, none, s.names())), "    y(0) = q(1) / (q(0) * q(0));\n");
  EXPECT_EQ(print_cpp(lower({{a, GiNaC::sqrt(s.x)}}, none, s.names())), "    y(0) = sqrt(q(0));\n");
  EXPECT_EQ(print_cpp(lower({{a, GiNaC::pow(s.x, GiNaC::numeric(-1, 2))}}, none, s.names())),
            "    y(0) = Scalar(1) / sqrt(q(0));\n");
}

TEST(Lower, IntermediatesAreFollowedAndShared) {
  Symbols s;
  Subexpressions z;
  const ex z1 = z.bind(s.x * s.y + 1);
  const ir::Program p = lower({{a, z1 * z1}, {b, z1 + s.x}}, z, s.names());
  EXPECT_EQ(ir::count_operations(p).multiplications, 2u);  // x*y once, z1*z1 once
}

// GiNaC holds (0.1845 x + y) y as 1/2000 (369 x + 2000 y) y; the content goes back into the sum
TEST(Lower, TheRationalContentGiNaCTakesOutOfASumInAProductGoesBackIntoIt) {
  Symbols s;
  Subexpressions z;
  const ex sum = GiNaC::numeric(369, 2000) * s.x + s.y;
  const ex held = sum * s.y;
  ASSERT_EQ(GiNaC::ex_to<GiNaC::numeric>(held.op(held.nops() - 1)), GiNaC::numeric(1, 2000)) << held;
  EXPECT_EQ(print_cpp(lower({{a, held}}, z, s.names())), "    y(0) = q(1) * (q(0) * Scalar(0.1845) + q(1));\n");
  // the same through an intermediate; it goes in where it saves multiplications, and stays out
  // where it would scale terms that have none
  const ex bound = z.bind(GiNaC::numeric(369) * s.x + GiNaC::numeric(2000) * s.y);
  EXPECT_EQ(ir::count_operations(lower({{a, bound * s.y / 2000}}, z, s.names())).multiplications, 2u);
  EXPECT_EQ(ir::count_operations(lower({{a, (3 * s.x + 5 * s.y) * s.y / 7}}, z, s.names())).multiplications, 3u);
  EXPECT_EQ(ir::count_operations(lower({{a, (s.x + s.y) * s.y / 7}}, z, s.names())).multiplications, 2u);
}

TEST(Lower, ZeroTargetsAreDropped) {
  Symbols s;
  Subexpressions none;
  const ir::Program p = lower({{a, 0}, {b, s.x}}, none, s.names());
  ASSERT_EQ(p.outputs.size(), 1u);
  EXPECT_EQ(p.outputs[0].target, b);
}

TEST(Lower, ResultDoesNotDependOnSymbolCreationOrder) {
  // GiNaC orders terms by symbol serial numbers, so build the same expression from symbols
  // created in opposite orders and compare the printed programs
  auto program = [](bool reversed) {
    GiNaC::realsymbol first(reversed ? "b" : "a"), second(reversed ? "a" : "b");
    const ex u = reversed ? second : first, v = reversed ? first : second;
    Subexpressions none;
    const VariableNames names{{u, {{ir::VariableKind::coordinate, 0}, "a"}}, {v, {{ir::VariableKind::coordinate, 1}, "b"}}};
    return print_cpp(lower({{a, GiNaC::sin(u) * v + GiNaC::cos(v) * u - u * v * v}}, none, names));
  };
  EXPECT_EQ(program(false), program(true));
}

TEST(Lower, OperandOrderComesFromTheVariablesNames) {
  Symbols s;
  Subexpressions none;
  const std::string named = print_cpp(lower({{a, s.x + s.y}}, none, s.names()));
  VariableNames swapped = s.names();
  std::swap(swapped.at(s.x).name, swapped.at(s.y).name);
  const std::string renamed = print_cpp(lower({{a, s.x + s.y}}, none, swapped));
  EXPECT_NE(named, renamed);
  EXPECT_TRUE(named == "    y(0) = q(0) + q(1);\n" || named == "    y(0) = q(1) + q(0);\n") << named;
  EXPECT_TRUE(renamed == "    y(0) = q(0) + q(1);\n" || renamed == "    y(0) = q(1) + q(0);\n") << renamed;
}

TEST(Lower, UnknownSymbolIsAnEmitError) {
  Symbols s;
  Subexpressions none;
  GiNaC::realsymbol stranger("stranger");
  EXPECT_THROW_MESSAGE(lower({{a, stranger * s.x}}, none, s.names()), EmitError,
                       "code emission: the symbol 'stranger' is not an input of this function");
}

TEST(Lower, UnprintableFunctionIsAnEmitError) {
  Symbols s;
  Subexpressions none;
  EXPECT_THROW_MESSAGE(lower({{a, GiNaC::zeta(s.x)}}, none, s.names()), EmitError,
                       "code emission: the function 'zeta' has no C++ form");
}

TEST(Lower, EveryGiNaCFunctionOfACallsNameLowersToThatCall) {
  Symbols s;
  Subexpressions none;
  std::size_t found = 0;
  for (const ir::CallOp& call : ir::call_ops) {
    unsigned serial = 0;
    try {
      serial = GiNaC::function::find_function(call.cpp_name, static_cast<unsigned>(call.arity));
    } catch (const std::runtime_error&) {
      continue;  // sqrt and pow come from powers: GiNaC has no functions of those names
    }
    ++found;
    GiNaC::exvector args{s.x + 2};
    if (call.arity == 2) args.push_back(s.y + 3);
    const ir::Program p = lower({{a, GiNaC::function(serial, args)}}, none, s.names());
    ASSERT_EQ(p.outputs.size(), 1u) << call.cpp_name;
    EXPECT_EQ(p.instructions[p.outputs[0].value].op, call.op) << call.cpp_name;
  }
  EXPECT_EQ(found, std::size(ir::call_ops) - 2);
}

TEST(Lower, OddCallsTakeTheSignOutsideAndEvenCallsDropIt) {
  Symbols s;
  Subexpressions none;
  EXPECT_EQ(print_cpp(lower({{a, GiNaC::sin(-s.x)}}, none, s.names())), "    y(0) = -sin(q(0));\n");
  EXPECT_EQ(print_cpp(lower({{a, GiNaC::cosh(-s.x)}}, none, s.names())), "    y(0) = cosh(q(0));\n");
  EXPECT_EQ(print_cpp(lower({{a, GiNaC::exp(-s.x)}}, none, s.names())), "    y(0) = exp(-q(0));\n");
}

}  // namespace
}  // namespace eomgen
