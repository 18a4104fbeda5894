// The grammar of units: factors, '/', '^' and parentheses over coherent SI unit symbols.
#include "model_unit.hpp"

#include <fmt/format.h>

#include "eomgen/base/error.hpp"

namespace eomgen::syntax {
namespace {

class UnitParser {
 public:
  UnitParser(const std::vector<Token>& tokens, const SourceLocation& open) : tokens_(tokens), open_(open) {}

  Dimension whole() {
    if (tokens_.empty()) throw SourceError(open_, "expected a unit inside '[]', or '[-]' for a dimensionless quantity");
    if (tokens_.size() == 1 && is_symbol("-")) return Dimension();
    const Dimension d = product();
    if (pos_ < tokens_.size()) unexpected();
    return d;
  }

 private:
  bool at_end() const { return pos_ >= tokens_.size(); }
  bool is_symbol(const char* s) const {
    return !at_end() && tokens_[pos_].kind == Token::Kind::symbol && tokens_[pos_].text == s;
  }
  [[noreturn]] void unexpected() const {
    throw SourceError(tokens_[pos_].location, fmt::format("unexpected {} in a unit: expected unit symbols separated "
                                                          "by spaces, '*' or '/', with integer powers (kg m^2/s^2)",
                                                          describe(tokens_[pos_])));
  }
  SourceLocation end_location() const {
    return tokens_.empty() ? open_ : tokens_.back().location;
  }

  // factor (('*')? factor | '/' factor)*, until ')' or the end
  Dimension product() {
    Dimension d = factor();
    while (!at_end() && !is_symbol(")")) {
      if (is_symbol("/")) {
        ++pos_;
        d = d / factor();
        continue;
      }
      if (is_symbol("*")) ++pos_;
      d = d * factor();
    }
    return d;
  }

  Dimension factor() {
    if (at_end())
      throw SourceError(end_location(), "the unit ends after an operator: expected a unit symbol");
    const Token& t = tokens_[pos_];
    Dimension base;
    if (is_symbol("(")) {
      ++pos_;
      base = product();
      if (!is_symbol(")")) throw SourceError(t.location, "'(' in a unit is never closed: expected ')'");
      ++pos_;
    } else if (t.kind == Token::Kind::number && t.text == "1") {
      ++pos_;
    } else if (t.kind == Token::Kind::identifier) {
      const std::optional<Dimension> known = coherent_unit(t.text);
      if (!known)
        throw SourceError(t.location, fmt::format("'{}' is not a coherent SI unit: expected SI units ({}) or '-'; "
                                                  "values are taken in SI, eomgen converts no unit",
                                                  t.text, coherent_unit_list()));
      base = *known;
      ++pos_;
    } else {
      unexpected();
    }
    if (!is_symbol("^")) return base;
    const Token& caret = tokens_[pos_++];
    long sign = 1;
    if (is_symbol("-") || is_symbol("+")) sign = tokens_[pos_++].text == "-" ? -1 : 1;
    if (at_end() || tokens_[pos_].kind != Token::Kind::number ||
        tokens_[pos_].text.find_first_not_of("0123456789") != std::string::npos || tokens_[pos_].text.size() > 3)
      throw SourceError(at_end() ? caret.location : tokens_[pos_].location,
                        "expected an integer power after '^' in a unit (m^2, s^-1)");
    return base.power(Exponent(sign * std::stol(tokens_[pos_++].text)));
  }

  const std::vector<Token>& tokens_;
  SourceLocation open_;
  std::size_t pos_ = 0;
};

}  // namespace

Dimension unit_dimension(const std::vector<Token>& tokens, const SourceLocation& open) {
  return UnitParser(tokens, open).whole();
}

}  // namespace eomgen::syntax
