// Reading a sum's terms from its pairs: the value op() gives, without the evaluation that
// distributes a number over a sum or walks the sums among a product's factors at every read.
#include "eomgen/symbolic/operand.hpp"

#include <gtest/gtest.h>

namespace eomgen {
namespace {

using GiNaC::ex;

TEST(Operand, ATermWithANumberIsTheProductOfItsStoredPartsWithoutDistributing) {
  const GiNaC::symbol a("a"), b("b"), c("c");
  const ex inner = a + b;
  // a held 2*(a + b) beside c: the sum keeps the pair (a + b, 2), and op() distributes it anew
  const ex sum = GiNaC::add(GiNaC::mul(inner, 2).hold(), c).hold();
  std::size_t checked = 0;
  for (std::size_t i = 0; i < sum.nops(); ++i) {
    const ex read = operand(sum, i);
    const GiNaC::exmap at{{a, 0.3}, {b, 0.7}, {c, 1.9}};
    EXPECT_TRUE(GiNaC::evalf(read.subs(at) - sum.op(i).subs(at)).is_zero()) << read << " against " << sum.op(i);
    if (GiNaC::is_a<GiNaC::symbol>(read)) continue;
    // the stored sum itself, not a rebuilt one
    ASSERT_TRUE(GiNaC::is_exactly_a<GiNaC::mul>(read)) << read;
    EXPECT_TRUE(GiNaC::are_ex_trivially_equal(read.op(0), inner)) << read;
    EXPECT_TRUE(read.op(1).is_equal(2)) << read;
    EXPECT_TRUE(GiNaC::is_exactly_a<GiNaC::add>(sum.op(i))) << "op() no longer distributes: " << sum.op(i);
    ++checked;
  }
  EXPECT_EQ(checked, 1u);
}

TEST(Operand, TermsWithoutANumberAndTheSumsNumberAreOpsOwn) {
  const GiNaC::symbol x("x"), y("y");
  const ex sum = x * y + GiNaC::sin(x) + 3;
  ASSERT_EQ(sum.nops(), 3u);
  for (std::size_t i = 0; i < sum.nops(); ++i) EXPECT_TRUE(operand(sum, i).is_equal(sum.op(i))) << i;
  const ex product = 5 * x * GiNaC::pow(y, 2);
  for (std::size_t i = 0; i < product.nops(); ++i) EXPECT_TRUE(operand(product, i).is_equal(product.op(i))) << i;
}

TEST(Operand, SumPairsAreTheTermsOfASumOnly) {
  const GiNaC::symbol x("x"), y("y");
  const ex sum = 2 * x + y;
  const GiNaC::epvector* pairs = sum_pairs(sum);
  ASSERT_NE(pairs, nullptr);
  ASSERT_EQ(pairs->size(), 2u);
  double coefficients = 0;
  for (const GiNaC::expair& pair : *pairs) coefficients += GiNaC::ex_to<GiNaC::numeric>(pair.coeff).to_double();
  EXPECT_EQ(coefficients, 3.0);
  EXPECT_EQ(sum_pairs(x * y), nullptr);
  EXPECT_EQ(sum_pairs(x), nullptr);
}

}  // namespace
}  // namespace eomgen
