#pragma once
// Physical dimensions in the seven SI base dimensions, and the dimension of an expression of a
// model whose symbols have one. A model that gives units (docs/model-language.md, "Units") is
// checked with them: every term of an equation, energy, load and constraint must agree.
#include <ginac/ginac.h>

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>

#include "eomgen/base/error.hpp"
#include "eomgen/symbolic/expression_map.hpp"

namespace eomgen {

/// An exponent of a base dimension. Rational, not integer: sqrt(x^2 + y^2) of lengths is a
/// length, and its intermediate x^2 + y^2 under a root of its own may give half-integers.
class Exponent {
 public:
  Exponent(std::int64_t numerator = 0, std::int64_t denominator = 1)
      : numerator_(numerator), denominator_(denominator) {
    normalize();
  }
  std::int64_t numerator() const { return numerator_; }
  std::int64_t denominator() const { return denominator_; }
  bool is_zero() const { return numerator_ == 0; }
  friend Exponent operator+(Exponent a, Exponent b) {
    return Exponent(a.numerator_ * b.denominator_ + b.numerator_ * a.denominator_, a.denominator_ * b.denominator_);
  }
  friend Exponent operator-(Exponent a) { return Exponent(-a.numerator_, a.denominator_); }
  friend Exponent operator*(Exponent a, Exponent b) {
    return Exponent(a.numerator_ * b.numerator_, a.denominator_ * b.denominator_);
  }
  friend bool operator==(Exponent a, Exponent b) {
    return a.numerator_ == b.numerator_ && a.denominator_ == b.denominator_;
  }
  friend bool operator!=(Exponent a, Exponent b) { return !(a == b); }

 private:
  void normalize() {
    EOMGEN_DEMAND(denominator_ != 0, "Exponent: a zero denominator");
    if (denominator_ < 0) {
      numerator_ = -numerator_;
      denominator_ = -denominator_;
    }
    std::int64_t a = numerator_ < 0 ? -numerator_ : numerator_, b = denominator_;
    while (b != 0) {
      const std::int64_t r = a % b;
      a = b;
      b = r;
    }
    if (a > 1) {
      numerator_ /= a;
      denominator_ /= a;
    }
  }
  std::int64_t numerator_;
  std::int64_t denominator_;
};

/// A product of powers of the SI base dimensions: kg, m, s, A, K, mol, cd.
class Dimension {
 public:
  enum class Base { kilogram, metre, second, ampere, kelvin, mole, candela };
  static constexpr std::size_t base_count = 7;

  /// Dimensionless.
  Dimension() = default;
  static Dimension of(Base base) {
    Dimension d;
    d.exponents_[static_cast<std::size_t>(base)] = Exponent(1);
    return d;
  }
  static Dimension mass() { return of(Base::kilogram); }
  static Dimension length() { return of(Base::metre); }
  static Dimension time() { return of(Base::second); }

  Exponent exponent(Base base) const { return exponents_[static_cast<std::size_t>(base)]; }
  bool is_dimensionless() const {
    for (const Exponent& e : exponents_)
      if (!e.is_zero()) return false;
    return true;
  }
  Dimension power(Exponent k) const {
    Dimension d;
    for (std::size_t i = 0; i < base_count; ++i) d.exponents_[i] = exponents_[i] * k;
    return d;
  }
  friend Dimension operator*(const Dimension& a, const Dimension& b) {
    Dimension d;
    for (std::size_t i = 0; i < base_count; ++i) d.exponents_[i] = a.exponents_[i] + b.exponents_[i];
    return d;
  }
  friend Dimension operator/(const Dimension& a, const Dimension& b) { return a * b.power(Exponent(-1)); }
  friend bool operator==(const Dimension& a, const Dimension& b) {
    for (std::size_t i = 0; i < base_count; ++i)
      if (a.exponents_[i] != b.exponents_[i]) return false;
    return true;
  }
  friend bool operator!=(const Dimension& a, const Dimension& b) { return !(a == b); }

 private:
  std::array<Exponent, base_count> exponents_{};
};

/// The dimension of a coherent SI unit symbol (the seven base units, rad, sr, N, J, W, Pa, Hz,
/// C, V), or nothing for any other text: eomgen converts no unit, so only these are accepted.
std::optional<Dimension> coherent_unit(const std::string& symbol);
/// The symbols coherent_unit() accepts, for messages: "kg, m, s, ...".
std::string coherent_unit_list();

/// The dimensions of mechanics that unit checks name (functions: constants of other files may
/// not be initialized yet when these are).
namespace dimension {
inline Dimension none() { return Dimension(); }
inline Dimension kg() { return Dimension::mass(); }
inline Dimension m() { return Dimension::length(); }
inline Dimension s() { return Dimension::time(); }
inline Dimension newton() { return kg() * m() / (s() * s()); }
inline Dimension joule() { return newton() * m(); }
}  // namespace dimension

/// The dimension in base units, "kg m^2 s^-2", "m^(1/2)"; "dimensionless" for none.
std::string base_units(const Dimension& d);
/// base_units(d) followed by a named unit of that dimension where one is known and differs:
/// "kg m^2 s^-2 (N m)". `preferred` picks among names of one dimension ("J" for an energy,
/// "N m" for a moment) and is ignored where its dimension is another.
std::string to_string(const Dimension& d, const std::string& preferred = "");

/// Two parts of an expression whose dimensions do not fit together: the terms of a sum, the
/// argument of sin() and what sin() needs, the arguments of atan2, or a symbolic exponent and its
/// base. `first` and `second` are printed as GiNaC prints them.
struct DimensionMismatch {
  enum class Kind { sum, argument, arguments, exponent };
  Kind kind;
  GiNaC::ex first, second;
  Dimension first_dimension, second_dimension;
  /// "the terms 'l' and 'F' have different dimensions, m and kg m s^-2 (N)"
  std::string describe() const;
};

/// Thrown by DimensionAnalysis; the caller adds where and in what.
class DimensionError : public Error {
 public:
  explicit DimensionError(DimensionMismatch mismatch)
      : Error(mismatch.describe()), mismatch_(std::move(mismatch)) {}
  const DimensionMismatch& mismatch() const { return mismatch_; }

 private:
  DimensionMismatch mismatch_;
};

using DimensionMap = std::map<GiNaC::ex, Dimension, GiNaC::ex_is_less>;

/// An expression as a message names it: GiNaC's text, shortened to `limit` characters.
std::string term_text(const GiNaC::ex& e, std::size_t limit = 120);

/// The dimensions of expressions in symbols of known dimension. Numbers are dimensionless and
/// zero fits any dimension (it is returned as nothing); the terms of a sum must agree; products
/// add exponents and a numeric power scales them; a symbolic exponent needs a dimensionless base
/// and exponent; sin, cos, tan, asin, acos, atan, sinh, cosh, tanh, exp and log need a
/// dimensionless argument and give one; abs keeps its argument's; atan2(y, x) needs y and x
/// alike and is dimensionless. Results are remembered per subexpression, so a graph of shared
/// subexpressions (the derived equations of a bicycle) is walked once.
class DimensionAnalysis {
 public:
  explicit DimensionAnalysis(DimensionMap symbols) : symbols_(std::move(symbols)) {}
  /// Gives a symbol its dimension (an intermediate defined by an expression measured before).
  void define(const GiNaC::ex& symbol, const Dimension& d) { symbols_[symbol] = d; }
  bool knows(const GiNaC::ex& symbol) const { return symbols_.count(symbol) != 0; }
  /// The dimension of e, or nothing for zero. \throws DimensionError where two parts disagree.
  std::optional<Dimension> of(const GiNaC::ex& e);

 private:
  std::optional<Dimension> measure(const GiNaC::ex& e);
  std::optional<Dimension> function(const GiNaC::ex& e);
  DimensionMismatch first_disagreement(const GiNaC::ex& sum);
  DimensionMap symbols_;
  // keyed by value, not by node: GiNaC swaps the nodes of equal expressions when it compares
  // them, so a node's address may be freed and reused while its expression lives on
  ExpressionMap<std::optional<Dimension>> memo_;
};

/// Of the terms of `value` (a sum's, or `value` itself), the first in the order of their text
/// whose dimension is not `expected`, with its dimension; nothing when every term has it (zero
/// terms have any). The order of text, not GiNaC's, so a message names the same term in every
/// run. \throws DimensionError where parts of a term disagree.
std::optional<std::pair<GiNaC::ex, Dimension>> first_term_not_of(DimensionAnalysis& analysis, const GiNaC::ex& value,
                                                                 const Dimension& expected);

}  // namespace eomgen
