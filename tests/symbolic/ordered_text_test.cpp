// ordered_text: the text of an expression the same in every process, whatever order GiNaC keeps
// its terms and factors in.
#include <gtest/gtest.h>

#include "eomgen/symbolic/ordered_text.hpp"

namespace eomgen {
namespace {

TEST(OrderedText, SumsAndProductsAreWrittenInTheOrderOfTheirPartsText) {
  // created in the opposite order to their names, so GiNaC's order is not the text's
  const GiNaC::symbol z("z"), l("l"), F("F");
  EXPECT_EQ(ordered_text(z + l), "l+z");
  EXPECT_EQ(ordered_text(l * F * z), "F*l*z");
  EXPECT_EQ(ordered_text(-F * l), "-F*l");
  EXPECT_EQ(ordered_text(GiNaC::numeric(9, 20) * l), "9/20*l");
  EXPECT_EQ(ordered_text(z - l), "-l+z");
  EXPECT_EQ(ordered_text(GiNaC::pow(z + l, 2) * F), "(l+z)^2*F");  // "(" sorts before letters
  EXPECT_EQ(ordered_text(GiNaC::sin(z * l)), "sin(l*z)");
  EXPECT_EQ(ordered_text(GiNaC::pow(l, GiNaC::numeric(-1, 2))), "l^(-1/2)");
}

}  // namespace
}  // namespace eomgen
