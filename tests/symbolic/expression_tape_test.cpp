// The expression tape computes what the double evaluator computes, bit for bit (the linearizer
// moved from one to the other and its numbers must not move), shares what the expressions
// share, and refuses at compile time what it cannot evaluate.
#include "eomgen/symbolic/expression_tape.hpp"

#include <ginac/ginac.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "eomgen/base/error.hpp"
#include "eomgen/symbolic/double_evaluator.hpp"

namespace {

using GiNaC::ex;
using GiNaC::realsymbol;

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(ExpressionTape, GivesTheDoubleEvaluatorsBitsThroughDefinitionsAndEveryOperation) {
  const realsymbol x("x"), y("y"), z("z"), s1("s1"), s2("s2");
  // s1, s2 play the derivation's intermediates; the outputs use every kind of node
  const ex d1 = GiNaC::sin(x) * GiNaC::cos(y) - GiNaC::pow(z, 3) / 7 + GiNaC::Pi;
  const ex d2 = GiNaC::sqrt(1 + s1 * s1) + GiNaC::atan2(y, x) + GiNaC::exp(-z) * GiNaC::log(2 + x * x);
  const std::vector<ex> outputs{s1 + s2, s1 * s2 * x - y, GiNaC::pow(s2, GiNaC::numeric(3, 2)), GiNaC::tan(s1) - s2 / 3,
                                GiNaC::abs(y - x) + GiNaC::tanh(z) + GiNaC::asin(x / 4)};
  eomgen::ExpressionTape tape({x, y, z});
  tape.define(s1, d1, "s1");
  tape.define(s2, d2, "s2");
  std::vector<std::uint32_t> registers;
  for (const ex& e : outputs) registers.push_back(tape.compile(e, "output"));

  std::mt19937 rng(7);
  std::uniform_real_distribution<double> value(-2, 2);
  std::vector<double> out;
  for (int trial = 0; trial < 50; ++trial) {
    const std::vector<double> in{value(rng), value(rng), value(rng)};
    tape.evaluate(in, out);
    eomgen::DoubleEvaluator eval;
    eval.set(x, in[0]);
    eval.set(y, in[1]);
    eval.set(z, in[2]);
    eval.set(s1, eval.value(d1, "s1"));
    eval.set(s2, eval.value(d2, "s2"));
    for (std::size_t k = 0; k < outputs.size(); ++k) {
      const double want = eval.value(outputs[k], "output");
      EXPECT_TRUE(same_bits(out[registers[k]], want) || (std::isnan(want) && std::isnan(out[registers[k]])))
          << "output " << k << ": " << out[registers[k]] << " against " << want;
    }
  }
}

TEST(ExpressionTape, SharedSubexpressionsAreComputedOnce) {
  const realsymbol x("x"), y("y");
  eomgen::ExpressionTape tape({x, y});
  const ex shared = GiNaC::sin(x + y);
  const std::uint32_t a = tape.compile(shared * 2, "a");
  const std::uint32_t b = tape.compile(shared, "b");
  EXPECT_LT(b, a);  // the sine was compiled with the first expression and is found again
  EXPECT_EQ(tape.compile(shared, "again"), b);
  EXPECT_EQ(tape.compile(x, "an input"), 0u);
}

TEST(ExpressionTape, SymbolsWithoutValuesAndUnknownFunctionsAreRefusedWhenCompiled) {
  const realsymbol x("x"), w("w");
  eomgen::ExpressionTape tape({x});
  try {
    tape.compile(x + w, "F[2]");
    FAIL() << "compiled a symbol without a value";
  } catch (const eomgen::Error& e) {
    EXPECT_STREQ(e.what(), "evaluating F[2]: it depends on 'w', which has no value here");
  }
  EXPECT_THROW(tape.compile(GiNaC::zeta(x), "zeta"), eomgen::Error);
  EXPECT_THROW(tape.compile(x + GiNaC::I, "complex"), eomgen::Error);
}

TEST(ExpressionTape, PolesGiveInfinityOrNaNNotExceptions) {
  const realsymbol x("x");
  eomgen::ExpressionTape tape({x});
  const std::uint32_t inverse = tape.compile(1 / x, "1/x"), root = tape.compile(GiNaC::sqrt(x), "sqrt");
  std::vector<double> out;
  tape.evaluate({0.0}, out);
  EXPECT_TRUE(std::isinf(out[inverse]));
  tape.evaluate({-1.0}, out);
  EXPECT_TRUE(std::isnan(out[root]));
}

}  // namespace
