#include "eomgen/report/expression_printer.hpp"

#include <algorithm>
#include <cctype>
#include <sstream>

#include "eomgen/mechanics/variables.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;
using GiNaC::is_a;

template <class T>
int three_way(const T& a, const T& b) {
  return a < b ? -1 : (b < a ? 1 : 0);
}

// GiNaC's own printing, only for leaves (no operand order involved)
std::string ginac_text(const ex& e) {
  std::ostringstream os;
  os << e;
  return os.str();
}

std::string ginac_latex(const ex& e) {
  std::ostringstream os;
  os << GiNaC::latex << e;
  return os.str();
}

// names with digit runs compared as numbers: z2 < z10
int natural_compare(const std::string& a, const std::string& b) {
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (std::isdigit(static_cast<unsigned char>(a[i])) && std::isdigit(static_cast<unsigned char>(b[j]))) {
      std::size_t ie = i, je = j;
      while (ie < a.size() && std::isdigit(static_cast<unsigned char>(a[ie]))) ++ie;
      while (je < b.size() && std::isdigit(static_cast<unsigned char>(b[je]))) ++je;
      std::string x = a.substr(i, ie - i), y = b.substr(j, je - j);
      x.erase(0, std::min(x.find_first_not_of('0'), x.size()));
      y.erase(0, std::min(y.find_first_not_of('0'), y.size()));
      if (const int c = x.size() != y.size() ? three_way(x.size(), y.size()) : three_way(x, y)) return c;
      i = ie;
      j = je;
    } else {
      if (a[i] != b[j]) return three_way(a[i], b[j]);
      ++i;
      ++j;
    }
  }
  return three_way(a.size() - i, b.size() - j);
}

// constants first, then symbols, functions and parenthesized sums: "2*Pi*m*l*cos(q)*(a + b)"
int rank(const ex& e) {
  if (is_a<GiNaC::constant>(e)) return 0;
  if (is_a<GiNaC::symbol>(e)) return 1;
  if (is_a<GiNaC::function>(e)) return 2;
  if (is_a<GiNaC::add>(e)) return 3;
  if (is_a<GiNaC::power>(e) || is_a<GiNaC::mul>(e)) return 4;
  if (is_a<GiNaC::numeric>(e)) return 5;
  return 6;
}

std::string join(const std::vector<std::string>& parts, const std::string& separator) {
  std::string out;
  for (std::size_t i = 0; i < parts.size(); ++i) out += (i ? separator : "") + parts[i];
  return out;
}

// stand-in arguments for borrowing GiNaC's LaTeX name of a function ("\sin", "\ln", ...)
const std::vector<GiNaC::symbol>& argument_slots() {
  static const std::vector<GiNaC::symbol> symbols = [] {
    std::vector<GiNaC::symbol> v;
    for (int i = 0; i < 4; ++i) v.emplace_back("@@" + std::to_string(i) + "@@", "@@" + std::to_string(i) + "@@");
    return v;
  }();
  return symbols;
}

}  // namespace

double ExpressionPrinter::latex_width(const std::string& tex) {
  // commands that print nothing themselves, and function names printed as words
  static const char* const silent[] = {"left", "right", "frac", "dot", "ddot", "mathrm", "text", "operatorname"};
  static const char* const words[] = {"sin", "cos", "tan", "sinh", "cosh", "tanh", "arcsin", "arccos",
                                      "arctan", "ln", "log", "exp", "quad"};
  double width = 0;
  int depth = 0, script_depth = -1;  // brace depth of the innermost sub/superscript, if any
  for (std::size_t i = 0; i < tex.size(); ++i) {
    const char c = tex[i];
    const double scale = script_depth >= 0 ? 0.7 : 1.0;  // scripts print smaller
    if (c == '\\' && i + 1 < tex.size() && std::isalpha(static_cast<unsigned char>(tex[i + 1]))) {
      std::size_t end = i + 1;
      while (end < tex.size() && std::isalpha(static_cast<unsigned char>(tex[end]))) ++end;
      const std::string command = tex.substr(i + 1, end - i - 1);
      i = end - 1;
      if (std::find(std::begin(silent), std::end(silent), command) != std::end(silent)) continue;
      const bool word = std::find(std::begin(words), std::end(words), command) != std::end(words);
      width += scale * (word ? command.size() : 1);  // a Greek letter or a symbol is one character
    } else if (c == '{') {
      ++depth;
    } else if (c == '}') {
      if (--depth < script_depth) script_depth = -1;
    } else if (c == '^' || c == '_') {
      if (script_depth < 0 && i + 1 < tex.size() && tex[i + 1] == '{') script_depth = depth + 1;
    } else if (c == '+' || c == '-' || c == '=') {
      width += scale * 2;  // binary operators are set with space around them
    } else if (c != ' ') {
      width += scale;
    }
  }
  return width;
}

ExpressionPrinter::ExpressionPrinter(const std::vector<ex>& symbol_order) {
  for (const ex& s : symbol_order) position_.emplace(s, position_.size());  // the first place of a repeated one
}

std::string ExpressionPrinter::text(const ex& e) const { return print(e, Style::text, in_sum); }

std::string ExpressionPrinter::latex(const ex& e) const { return print(e, Style::latex, in_sum); }

std::vector<std::string> ExpressionPrinter::latex_lines(const ex& e, double width) const {
  // break before a binary + or - outside braces (a row must close its own \frac{..}{..} and
  // scripts, but not its parentheses), packing as many pieces on a row as fit
  const std::string tex = latex(e);
  std::vector<std::string> pieces;
  std::size_t start = 0;
  int depth = 0;
  for (std::size_t i = 0; i + 2 < tex.size(); ++i) {
    if (tex[i] == '{') ++depth;
    if (tex[i] == '}') --depth;
    if (depth == 0 && tex[i] == ' ' && (tex[i + 1] == '+' || tex[i + 1] == '-') && tex[i + 2] == ' ') {
      pieces.push_back(tex.substr(start, i - start));
      start = i + 1;
    }
  }
  pieces.push_back(tex.substr(start));
  std::vector<std::string> lines{""};
  double line_width = 0;
  for (const std::string& piece : pieces) {
    const double piece_width = latex_width(piece);
    if (!lines.back().empty() && line_width + piece_width > width) {
      lines.emplace_back();
      line_width = 0;
    }
    lines.back() += (lines.back().empty() ? "" : " ") + piece;
    line_width += piece_width;
  }
  return lines;
}

std::vector<std::string> ExpressionPrinter::signed_terms(const ex& sum, Style style) const {
  std::vector<std::string> out;
  for (const ex& term : sorted_terms(sum)) {
    Monomial m = monomial(term);
    const bool negative = m.coefficient.is_real() && m.coefficient.is_negative();
    if (negative) m.coefficient = -m.coefficient;
    const std::string body = print_monomial(m, style, in_sum);
    out.push_back(out.empty() ? (negative ? "-" + body : body) : (negative ? "- " : "+ ") + body);
  }
  return out;
}

const ExpressionPrinter::Monomial& ExpressionPrinter::monomial(const ex& term) const {
  if (const Monomial* m = monomials_.find(term)) return *m;
  Monomial m = make_monomial(term);
  return *monomials_.emplace(term, std::move(m)).first;
}

ExpressionPrinter::Monomial ExpressionPrinter::make_monomial(const ex& term) const {
  Monomial m{1, {}};
  std::vector<ex> factors;
  if (is_a<GiNaC::numeric>(term)) {
    m.coefficient = GiNaC::ex_to<GiNaC::numeric>(term);
  } else if (is_a<GiNaC::mul>(term)) {
    for (std::size_t i = 0; i < term.nops(); ++i) {
      if (is_a<GiNaC::numeric>(term.op(i)))
        m.coefficient *= GiNaC::ex_to<GiNaC::numeric>(term.op(i));
      else
        factors.push_back(term.op(i));
    }
  } else {
    factors.push_back(term);
  }
  for (const ex& f : factors) {
    const bool power = is_a<GiNaC::power>(f);
    const ex base = power ? f.op(0) : f, exponent = power ? f.op(1) : ex(1);
    const bool integer = is_a<GiNaC::numeric>(exponent) && GiNaC::ex_to<GiNaC::numeric>(exponent).is_integer();
    if (is_a<GiNaC::add>(base) && integer) {
      const Monomial& first = monomial(sorted_terms(base).front());
      if (first.coefficient.is_real() && first.coefficient.is_negative()) {
        // (-s)^k = (-1)^k s^k; -s of a sum is again a sum, so nothing re-normalizes it
        m.factors.push_back(Factor{-base, exponent});
        if (GiNaC::ex_to<GiNaC::numeric>(exponent).is_odd()) m.coefficient = -m.coefficient;
        continue;
      }
    }
    m.factors.push_back(Factor{base, exponent});
  }
  std::stable_sort(m.factors.begin(), m.factors.end(),
                   [this](const Factor& x, const Factor& y) { return compare_factors(x, y) < 0; });
  return m;
}

std::string ExpressionPrinter::print(const ex& e, Style style, Level level) const {
  const bool tex = style == Style::latex;
  // plain parentheses also in LaTeX: unlike \left( \right) they may open on one row of an
  // alignment and close on a later one, so long products can be broken (latex_lines)
  auto parenthesize = [](const std::string& s) { return "(" + s + ")"; };
  if (is_a<GiNaC::numeric>(e)) {
    const GiNaC::numeric& n = GiNaC::ex_to<GiNaC::numeric>(e);
    std::string s;
    if (n.is_rational() && !n.is_integer()) {
      const GiNaC::numeric p = GiNaC::abs(n.numer()), q = n.denom();
      s = (n.is_negative() ? "-" : "") +
          (tex ? "\\frac{" + ginac_text(p) + "}{" + ginac_text(q) + "}" : ginac_text(p) + "/" + ginac_text(q));
    } else {
      s = ginac_text(n);
    }
    const bool wrap = (level >= in_product && (n.is_negative() || !n.is_real())) ||
                      (level == in_power && !n.is_nonneg_integer());
    return wrap ? parenthesize(s) : s;
  }
  if (is_a<GiNaC::symbol>(e)) {
    const GiNaC::symbol& s = GiNaC::ex_to<GiNaC::symbol>(e);
    if (!tex) return s.get_name();
    // GiNaC's default TeX name is the plain name ("z12"); ours makes subscripts ("z_{12}")
    const std::string given = s.get_TeX_name();
    return given.empty() || given == s.get_name() ? tex_name(s.get_name()) : given;
  }
  if (is_a<GiNaC::constant>(e)) return tex ? ginac_latex(e) : ginac_text(e);
  if (is_a<GiNaC::function>(e)) return print_function(e, style);
  if (is_a<GiNaC::add>(e)) {
    const std::string s = join(signed_terms(e, style), " ");
    return level >= in_product ? parenthesize(s) : s;
  }
  if (is_a<GiNaC::mul>(e) || is_a<GiNaC::power>(e)) return print_monomial(monomial(e), style, level);
  return parenthesize(tex ? ginac_latex(e) : ginac_text(e));  // not expected in equations of motion
}

std::string ExpressionPrinter::print_power(const ex& base, const ex& exponent, Style style) const {
  const bool tex = style == Style::latex;
  if (exponent.is_equal(1)) return print(base, style, in_product);
  if (exponent.is_equal(GiNaC::numeric(1, 2)))
    return tex ? "\\sqrt{" + print(base, style, in_sum) + "}" : "sqrt(" + print(base, style, in_sum) + ")";
  const std::string b = print(base, style, in_power), x = print(exponent, style, in_sum);
  if (tex) return b + "^{" + x + "}";
  const bool simple = is_a<GiNaC::symbol>(exponent) ||
                      (is_a<GiNaC::numeric>(exponent) && GiNaC::ex_to<GiNaC::numeric>(exponent).is_nonneg_integer());
  return b + "^" + (simple ? x : "(" + x + ")");
}

std::string ExpressionPrinter::print_monomial(const Monomial& m, Style style, Level level) const {
  const bool tex = style == Style::latex;
  const bool negative = m.coefficient.is_real() && m.coefficient.is_negative();
  const GiNaC::numeric magnitude = negative ? -m.coefficient : m.coefficient;
  std::vector<std::string> numerator, denominator;
  // a rational coefficient p/q puts p in front and q under the fraction bar
  if (magnitude.is_rational()) {
    if (magnitude.numer() != 1) numerator.push_back(ginac_text(magnitude.numer()));
    if (magnitude.denom() != 1) denominator.push_back(ginac_text(magnitude.denom()));
  } else if (magnitude != 1) {
    numerator.push_back(print(magnitude, style, in_product));
  }
  for (const Factor& f : m.factors) {
    const bool below = is_a<GiNaC::numeric>(f.exponent) && GiNaC::ex_to<GiNaC::numeric>(f.exponent).is_negative();
    if (below)
      denominator.push_back(print_power(f.base, -f.exponent, style));
    else
      numerator.push_back(f.exponent.is_equal(1) ? print(f.base, style, in_product) : print_power(f.base, f.exponent, style));
  }
  auto product = [&](const std::vector<std::string>& parts) {
    if (parts.empty()) return std::string("1");
    if (!tex) return join(parts, "*");
    // juxtaposition, except where a factor starting with a digit would merge with the one before
    std::string s = parts[0];
    for (std::size_t i = 1; i < parts.size(); ++i)
      s += (std::isdigit(static_cast<unsigned char>(parts[i][0])) ? " \\cdot " : " ") + parts[i];
    return s;
  };
  std::string s;
  if (denominator.empty())
    s = product(numerator);
  else if (tex)
    s = "\\frac{" + product(numerator) + "}{" + product(denominator) + "}";
  else
    s = product(numerator) + "/" + (denominator.size() > 1 ? "(" + product(denominator) + ")" : denominator[0]);
  if (negative) s = "-" + s;
  const bool compound = numerator.size() + denominator.size() > 1 || !denominator.empty() ||
                        (m.factors.size() == 1 && !m.factors[0].exponent.is_equal(1));
  if ((level >= in_product && negative) || (level == in_power && compound))
    return "(" + s + ")";
  return s;
}

std::string ExpressionPrinter::print_function(const ex& e, Style style) const {
  const GiNaC::function& f = GiNaC::ex_to<GiNaC::function>(e);
  std::vector<std::string> args;
  for (std::size_t i = 0; i < e.nops(); ++i) args.push_back(print(e.op(i), style, in_sum));
  if (style == Style::text) return f.get_name() + "(" + join(args, ", ") + ")";
  if (args.size() > argument_slots().size()) return "\\operatorname{" + f.get_name() + "}(" + join(args, ", ") + ")";
  // GiNaC knows each function's LaTeX form (\sin, \ln, |x|): print it on stand-in arguments, then fill in
  GiNaC::exvector slots(argument_slots().begin(), argument_slots().begin() + static_cast<std::ptrdiff_t>(args.size()));
  std::string s = ginac_latex(GiNaC::function(f.get_serial(), slots).hold());
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string slot = "@@" + std::to_string(i) + "@@";
    for (std::size_t at = s.find(slot); at != std::string::npos; at = s.find(slot, at + args[i].size()))
      s.replace(at, slot.size(), args[i]);
  }
  return s;
}

int ExpressionPrinter::compare_symbols(const ex& a, const ex& b) const {
  const std::size_t *pa = position_.find(a), *pb = position_.find(b);
  if (pa && pb) return three_way(*pa, *pb);
  if (pa) return -1;
  if (pb) return 1;
  return natural_compare(GiNaC::ex_to<GiNaC::symbol>(a).get_name(), GiNaC::ex_to<GiNaC::symbol>(b).get_name());
}

int ExpressionPrinter::compare(const ex& a, const ex& b) const {
  if (a.is_equal(b)) return 0;  // shared subtrees: the same object, or equal hashes and structure
  if (const int c = three_way(rank(a), rank(b))) return c;
  switch (rank(a)) {
    case 0: return three_way(ginac_text(a), ginac_text(b));
    case 1: return compare_symbols(a, b);
    case 2: {
      const std::string na = GiNaC::ex_to<GiNaC::function>(a).get_name(), nb = GiNaC::ex_to<GiNaC::function>(b).get_name();
      if (const int c = three_way(na, nb)) return c;
      for (std::size_t i = 0; i < std::min(a.nops(), b.nops()); ++i)
        if (const int c = compare(a.op(i), b.op(i))) return c;
      return three_way(a.nops(), b.nops());
    }
    case 3: {
      const std::vector<ex>& ta = sorted_terms(a);
      const std::vector<ex>& tb = sorted_terms(b);
      for (std::size_t i = 0; i < std::min(ta.size(), tb.size()); ++i)
        if (const int c = compare_monomials(monomial(ta[i]), monomial(tb[i]))) return c;
      return three_way(ta.size(), tb.size());
    }
    case 4: return compare_monomials(monomial(a), monomial(b));  // products and powers
    case 5: return GiNaC::ex_to<GiNaC::numeric>(a).compare(GiNaC::ex_to<GiNaC::numeric>(b));
    default: return three_way(ginac_text(a), ginac_text(b));
  }
}

int ExpressionPrinter::compare_factors(const Factor& a, const Factor& b) const {
  // a power sorts with its base; higher powers first: l^2*m before l*m
  if (const int c = compare(a.base, b.base)) return c;
  return compare(b.exponent, a.exponent);
}

int ExpressionPrinter::compare_monomials(const Monomial& a, const Monomial& b) const {
  if (a.factors.empty() != b.factors.empty()) return a.factors.empty() ? 1 : -1;  // a constant term last
  for (std::size_t i = 0; i < std::min(a.factors.size(), b.factors.size()); ++i)
    if (const int c = compare_factors(a.factors[i], b.factors[i])) return c;
  if (const int c = three_way(a.factors.size(), b.factors.size())) return c;
  return a.coefficient.compare(b.coefficient);
}

const std::vector<ex>& ExpressionPrinter::sorted_terms(const ex& sum) const {
  if (const std::vector<ex>* terms = sorted_terms_.find(sum)) return *terms;
  std::vector<ex> terms(sum.begin(), sum.end());
  std::stable_sort(terms.begin(), terms.end(),
                   [this](const ex& x, const ex& y) { return compare_monomials(monomial(x), monomial(y)) < 0; });
  return *sorted_terms_.emplace(sum, std::move(terms)).first;
}

}  // namespace eomgen
