#pragma once
// Text and LaTeX for GiNaC expressions with a fixed order of terms and factors.
//
// GiNaC prints sums and products in its internal order, which compares hash values seeded by
// the addresses of type_info names (ginac/utils.h, make_hash_seed). Under address-space layout
// randomization the same expression therefore prints differently from one run to the next
// ("m2*l1^2+l1^2*m1" once, "l1^2*m1+m2*l1^2" the next time). This printer sorts operands by a
// given symbol order and by names instead, so its output depends only on the expression.
#include <ginac/ginac.h>

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "eomgen/symbolic/expression_map.hpp"

namespace eomgen {

class ExpressionPrinter {
 public:
  /// `symbol_order` lists symbols in the order they should appear as factors (e.g. the
  /// parameters, then time, coordinates and rates); any other symbol comes after them, sorted
  /// by name with digit runs compared as numbers (z2 before z10).
  explicit ExpressionPrinter(const std::vector<GiNaC::ex>& symbol_order = {});

  /// Plain text: "m*l^2", "-g*m*l*sin(theta)", "m*l^2*theta_dot^2/2", "sqrt(x^2 + y^2)".
  std::string text(const GiNaC::ex& e) const;
  /// LaTeX for math mode with each symbol's TeX name: "m l^{2}", "\frac{m l^{2} \dot{\theta}^{2}}{2}".
  std::string latex(const GiNaC::ex& e) const;
  /// latex(e) broken before binary + and - (also inside parentheses, never inside braces) into
  /// lines of at most about `width` printed characters (see latex_width) where possible;
  /// lines after the first start with "+ " or "- ".
  std::vector<std::string> latex_lines(const GiNaC::ex& e, double width) const;

  /// Estimated printed width of LaTeX math in characters: commands such as \left and \frac
  /// and braces count nothing, \theta one, \cos three, sub- and superscripts 0.7 each.
  static double latex_width(const std::string& tex);

 private:
  enum class Style { text, latex };
  // precedence of the place an expression is printed in: decides the parentheses
  enum Level { in_sum = 0, in_product = 1, in_power = 2 };

  // A product as coefficient times factors in print order. GiNaC keeps a sum inside a product
  // with either sign (a*(b - c) or -a*(c - b), by its hash order); here every such sum with an
  // integer exponent is signed so that its first term is positive.
  // Factors are kept as (base, exponent) pairs and never rebuilt into GiNaC powers: GiNaC
  // would evaluate pow(b - c, 3) back into -(c - b)^3 by its own order, undoing the sign.
  struct Factor {
    GiNaC::ex base;
    GiNaC::ex exponent;
  };
  struct Monomial {
    GiNaC::numeric coefficient;
    std::vector<Factor> factors;
  };
  const Monomial& monomial(const GiNaC::ex& term) const;
  Monomial make_monomial(const GiNaC::ex& term) const;

  std::string print(const GiNaC::ex& e, Style style, Level level) const;
  std::string print_monomial(const Monomial& m, Style style, Level level) const;
  std::string print_power(const GiNaC::ex& base, const GiNaC::ex& exponent, Style style) const;
  std::string print_function(const GiNaC::ex& e, Style style) const;
  // first term as printed, the others as "+ term" / "- term"
  std::vector<std::string> signed_terms(const GiNaC::ex& sum, Style style) const;

  // total order used for sorting (0 only for expressions that print the same)
  int compare(const GiNaC::ex& a, const GiNaC::ex& b) const;
  int compare_symbols(const GiNaC::ex& a, const GiNaC::ex& b) const;
  int compare_factors(const Factor& a, const Factor& b) const;
  int compare_monomials(const Monomial& a, const Monomial& b) const;
  const std::vector<GiNaC::ex>& sorted_terms(const GiNaC::ex& sum) const;

  // the symbols' places in symbol_order: a chain's equations have tens of thousands of
  // intermediates, and sorting looks them up at every comparison of two symbols
  mutable ExpressionMap<std::size_t> position_;
  // Sorting compares subexpressions by their sorted terms and factors, recursively: without
  // these memos every comparison re-sorts both sides down to the leaves, and printing a
  // constraint row of the bicycle took seconds. Not thread-safe, like the rest of a printer's
  // use (one printer per printing call).
  mutable ExpressionMap<Monomial> monomials_;
  mutable ExpressionMap<std::vector<GiNaC::ex>> sorted_terms_;
};

}  // namespace eomgen
