#include "eomgen/report/expression_printer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

namespace eomgen {
namespace {

using GiNaC::ex;
using GiNaC::numeric;
using GiNaC::pow;
using GiNaC::realsymbol;

TEST(ExpressionPrinter, FactorsFollowTheGivenSymbolOrderThenFunctions) {
  const realsymbol m("m"), l("l"), g("g"), theta("theta", "\\theta"), theta_dot("theta_dot", "\\dot{\\theta}");
  const ExpressionPrinter p({m, l, g, theta, theta_dot});
  EXPECT_EQ(p.text(m * pow(l, 2)), "m*l^2");
  EXPECT_EQ(p.text(-g * m * l * GiNaC::sin(theta)), "-m*l*g*sin(theta)");
  EXPECT_EQ(p.text(m * pow(l, 2) * pow(theta_dot, 2) / 2), "m*l^2*theta_dot^2/2");
  EXPECT_EQ(p.latex(m * pow(l, 2) * pow(theta_dot, 2) / 2), "\\frac{m l^{2} \\dot{\\theta}^{2}}{2}");
  EXPECT_EQ(p.latex(-g * m * l * GiNaC::sin(theta)), "-m l g \\sin(\\theta)");
}

TEST(ExpressionPrinter, OutputDoesNotDependOnTheOrderSymbolsWereCreatedIn) {
  // GiNaC's own order of terms follows serial numbers and hash values; ours follows names
  const realsymbol a1("a"), b1("b"), c1("c");
  const realsymbol c2("c"), b2("b"), a2("a");
  const ExpressionPrinter p;
  const ex e1 = pow(a1, 2) * b1 - c1 * GiNaC::cos(b1) + 3 * a1 * c1 + GiNaC::sin(a1 + c1) / b1;
  const ex e2 = pow(a2, 2) * b2 - c2 * GiNaC::cos(b2) + 3 * a2 * c2 + GiNaC::sin(a2 + c2) / b2;
  EXPECT_EQ(p.text(e1), p.text(e2));
  EXPECT_EQ(p.latex(e1), p.latex(e2));
  EXPECT_EQ(p.text(e1), "a^2*b + 3*a*c + sin(a + c)/b - c*cos(b)");
}

TEST(ExpressionPrinter, UnlistedSymbolsSortByNameWithNumbersComparedAsNumbers) {
  const realsymbol z2("z2"), z10("z10"), z1("z1");
  const ExpressionPrinter p;
  EXPECT_EQ(p.text(z10 + z2 + z1), "z1 + z2 + z10");
  EXPECT_EQ(p.latex(z10 * z2), "z_{2} z_{10}");  // TeX name made from the name
}

TEST(ExpressionPrinter, FractionsRootsPowersAndParentheses) {
  const realsymbol a("a"), b("b"), c("c"), x("x"), y("y");
  const ExpressionPrinter p({a, b, c, x, y});
  EXPECT_EQ(p.text(a / b), "a/b");
  EXPECT_EQ(p.text(-a / b), "-a/b");
  EXPECT_EQ(p.text(a / (b * pow(c, 2))), "a/(b*c^2)");
  EXPECT_EQ(p.text(1 / a), "1/a");
  EXPECT_EQ(p.text(-a / (2 * b)), "-a/(2*b)");
  EXPECT_EQ(p.text(numeric(3, 4)), "3/4");
  EXPECT_EQ(p.text(GiNaC::sqrt(pow(x, 2) + pow(y, 2))), "sqrt(x^2 + y^2)");
  EXPECT_EQ(p.text(pow(x + y, numeric(-1, 2))), "1/sqrt(x + y)");
  EXPECT_EQ(p.text(pow(a, numeric(3, 2))), "a^(3/2)");
  EXPECT_EQ(p.text(a * (b + c)), "a*(b + c)");
  EXPECT_EQ(p.text(pow(a + b, 2)), "(a + b)^2");
  EXPECT_EQ(p.text(pow(a, b + 1)), "a^(b + 1)");
  EXPECT_EQ(p.text(x + 1), "x + 1");  // the constant term last
  EXPECT_EQ(p.text(1 - x), "-x + 1");
  EXPECT_EQ(p.text(GiNaC::atan2(y, x)), "atan2(y, x)");
  EXPECT_EQ(p.latex(a / (b * pow(c, 2))), "\\frac{a}{b c^{2}}");
  EXPECT_EQ(p.latex(pow(x + y, numeric(-1, 2))), "\\frac{1}{\\sqrt{x + y}}");
  EXPECT_EQ(p.latex(a * (b - c)), "a (b - c)");
  EXPECT_EQ(p.text(-a * (c - b)), "a*(b - c)");  // the sign of a sum factor is ours, not GiNaC's
  EXPECT_EQ(p.text(a * pow(c - b, 3)), "-a*(b - c)^3");
  EXPECT_EQ(p.text(pow(c - b, 2)), "(b - c)^2");
  EXPECT_EQ(p.latex(GiNaC::log(a)), "\\ln(a)");
  EXPECT_EQ(p.latex(2 * pow(numeric(3), a)), "2 \\cdot 3^{a}");
}

TEST(ExpressionPrinter, LatexLinesBreakBetweenTermsAndKeepSigns) {
  std::vector<realsymbol> q;
  ex sum = 0;
  for (int i = 1; i <= 12; ++i) {
    q.emplace_back("q" + std::to_string(i));
    sum += (i % 3 == 0 ? -1 : 1) * q.back() * GiNaC::cos(q.back());
  }
  const ExpressionPrinter p;
  const std::vector<std::string> lines = p.latex_lines(sum, 30);
  ASSERT_GT(lines.size(), 2u);
  std::string joined;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    EXPECT_LE(ExpressionPrinter::latex_width(lines[i]), 30) << lines[i];
    if (i > 0) {
      EXPECT_TRUE(lines[i].rfind("+ ", 0) == 0 || lines[i].rfind("- ", 0) == 0) << lines[i];
    }
    joined += (i ? " " : "") + lines[i];
  }
  EXPECT_EQ(joined, p.latex(sum));
  EXPECT_LT(p.latex_lines(sum, 60).size(), lines.size());
  EXPECT_EQ(p.latex_lines(q[0], 30), std::vector<std::string>{"q_{1}"});
  // a long product breaks inside its parentheses, never inside braces
  const std::vector<std::string> inner = p.latex_lines(q[0] * sum + q[1] / (q[2] + q[3]), 30);
  ASSERT_GT(inner.size(), 2u);
  EXPECT_EQ(inner[0].rfind("q_{1} (", 0), 0u) << inner[0];
  for (const std::string& line : inner)
    EXPECT_EQ(std::count(line.begin(), line.end(), '{'), std::count(line.begin(), line.end(), '}')) << line;
}

TEST(ExpressionPrinter, LatexWidthCountsWhatIsPrinted) {
  EXPECT_DOUBLE_EQ(ExpressionPrinter::latex_width("m l"), 2);
  EXPECT_DOUBLE_EQ(ExpressionPrinter::latex_width("\\cos(\\theta)"), 6);          // cos ( theta )
  EXPECT_DOUBLE_EQ(ExpressionPrinter::latex_width("z_{12}"), 1 + 2 * 0.7);        // a smaller subscript
  EXPECT_DOUBLE_EQ(ExpressionPrinter::latex_width("a + \\left(b\\right)"), 6);  // + with its spaces
  EXPECT_DOUBLE_EQ(ExpressionPrinter::latex_width("\\frac{a}{b}"), 2);
}

}  // namespace
}  // namespace eomgen
