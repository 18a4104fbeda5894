// Dimensions in the SI base units: their algebra, how messages print them, and the dimension of
// an expression with the rules of docs/model-language.md, "Units".
#include <gtest/gtest.h>

#include <string>

#include "eomgen/mechanics/dimension.hpp"
#include "support/shared_graphs.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;

const Dimension kg = Dimension::mass(), m = Dimension::length(), s = Dimension::time();
const Dimension newton = kg * m / (s * s);

// The message of the DimensionError that measuring e throws, or "no error".
std::string mismatch_of(DimensionAnalysis& analysis, const ex& e) {
  try {
    analysis.of(e);
  } catch (const DimensionError& error) {
    return error.what();
  }
  return "no error";
}

TEST(Dimension, ProductsQuotientsAndPowersAddAndScaleExponents) {
  EXPECT_EQ(base_units(newton * m), "kg m^2 s^-2");
  EXPECT_EQ(base_units((m * m).power(Exponent(1, 2))), "m");
  EXPECT_EQ(base_units(m.power(Exponent(1, 2))), "m^(1/2)");
  EXPECT_EQ(base_units(m / m), "dimensionless");
  EXPECT_TRUE((newton / newton).is_dimensionless());
  EXPECT_EQ(kg * m, m * kg);
  EXPECT_NE(newton, newton * m);
}

TEST(Dimension, PrintsBaseUnitsWithTheNamedUnitOfMechanicsThatMatches) {
  EXPECT_EQ(to_string(newton), "kg m s^-2 (N)");
  EXPECT_EQ(to_string(newton * m), "kg m^2 s^-2 (N m)");
  EXPECT_EQ(to_string(newton * m, "J"), "kg m^2 s^-2 (J)");
  EXPECT_EQ(to_string(newton * m / s), "kg m^2 s^-3 (W)");
  EXPECT_EQ(to_string(newton / (m * m)), "kg m^-1 s^-2 (Pa)");
  EXPECT_EQ(to_string(newton / m), "kg s^-2 (N/m)");
  EXPECT_EQ(to_string(newton * s / m), "kg s^-1 (N s/m)");
  EXPECT_EQ(to_string(m / (s * s)), "m s^-2");
  EXPECT_EQ(to_string(kg, "J"), "kg");  // a preferred name of another dimension is ignored
}

TEST(Dimension, CoherentSiUnitsOnly) {
  EXPECT_EQ(*coherent_unit("J"), newton * m);
  EXPECT_EQ(*coherent_unit("Hz"), Dimension() / s);
  EXPECT_TRUE(coherent_unit("rad")->is_dimensionless());
  EXPECT_FALSE(coherent_unit("mm"));
  EXPECT_FALSE(coherent_unit("g"));
  EXPECT_FALSE(coherent_unit("deg"));
}

TEST(DimensionAnalysis, NumbersAreDimensionlessAndZeroFitsAnyDimension) {
  DimensionAnalysis analysis({});
  EXPECT_EQ(*analysis.of(ex(3) / 4), Dimension());
  EXPECT_EQ(*analysis.of(GiNaC::Pi), Dimension());
  EXPECT_FALSE(analysis.of(ex(0)));
}

TEST(DimensionAnalysis, ProductsSumsAndRootsOfLengths) {
  GiNaC::realsymbol x("x"), y("y"), f("f");
  DimensionAnalysis analysis({{x, m}, {y, m}, {f, newton}});
  EXPECT_EQ(*analysis.of(f * x), newton * m);
  EXPECT_EQ(*analysis.of(GiNaC::sqrt(x * x + y * y)), m);
  EXPECT_EQ(*analysis.of(GiNaC::pow(x * x + y * y, ex(-3) / 2)), m.power(-3));
  EXPECT_EQ(*analysis.of(GiNaC::abs(x - y)), m);
  EXPECT_EQ(*analysis.of(GiNaC::atan2(y, x)), Dimension());
  EXPECT_EQ(*analysis.of(GiNaC::sin(x / y) * x), m);
}

TEST(DimensionAnalysis, TermsOfASumThatDisagreeAreNamedWithTheirDimensions) {
  GiNaC::realsymbol l("l"), f("f");
  DimensionAnalysis analysis({{l, m}, {f, newton}});
  EXPECT_EQ(mismatch_of(analysis, l + f),
            "the terms 'f' and 'l' have different dimensions, kg m s^-2 (N) and m");
  EXPECT_EQ(mismatch_of(analysis, l + 1), "the terms '1' and 'l' have different dimensions, dimensionless and m");
}

TEST(DimensionAnalysis, FunctionsOfANumberNeedADimensionlessArgument) {
  GiNaC::realsymbol l("l");
  DimensionAnalysis analysis({{l, m}});
  EXPECT_EQ(mismatch_of(analysis, GiNaC::cos(l)), "the argument 'l' of 'cos(l)' has dimension m, expected dimensionless");
  EXPECT_EQ(mismatch_of(analysis, GiNaC::exp(2 * l)),
            "the argument '2*l' of 'exp(2*l)' has dimension m, expected dimensionless");
}

TEST(DimensionAnalysis, Atan2NeedsArgumentsAlike) {
  GiNaC::realsymbol l("l"), f("f");
  DimensionAnalysis analysis({{l, m}, {f, newton}});
  EXPECT_EQ(mismatch_of(analysis, GiNaC::atan2(l, f)),
            "the arguments 'l' and 'f' of atan2 have different dimensions, m and kg m s^-2 (N)");
}

TEST(DimensionAnalysis, ASymbolicExponentNeedsADimensionlessBaseAndExponent) {
  GiNaC::realsymbol l("l"), k("k");
  DimensionAnalysis analysis({{l, m}, {k, Dimension()}});
  EXPECT_EQ(*analysis.of(GiNaC::pow(2, k)), Dimension());
  EXPECT_EQ(mismatch_of(analysis, GiNaC::pow(l, k)),
            "the power with base 'l' (m) and exponent 'k' (dimensionless) needs a dimensionless base where the "
            "exponent is not a rational number, and a dimensionless exponent");
}

TEST(DimensionAnalysis, ASharedSubexpressionIsMeasuredOnce) {
  // 2^40 terms as a tree, a few hundred nodes as a graph: only a memo makes this finish, and
  // only one keyed by value makes the second copy (other nodes, the same value) finish
  GiNaC::realsymbol x("x");
  DimensionAnalysis analysis({{x, m}});
  EXPECT_EQ(*analysis.of(testing::doubling_graph(x, 40)), m);
  EXPECT_EQ(*analysis.of(testing::doubling_graph(x, 40) * x), m * m);
}

}  // namespace
}  // namespace eomgen
