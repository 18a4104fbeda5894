// Dimensions of the SI base units, their names, and the dimension of an expression.
#include "eomgen/mechanics/dimension.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <sstream>
#include <vector>

#include "eomgen/symbolic/ordered_text.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;
using Base = Dimension::Base;

const Dimension kg = Dimension::mass(), m = Dimension::length(), s = Dimension::time();
const Dimension newton = kg * m / (s * s);

struct NamedUnit {
  const char* symbol;
  Dimension dimension;
};

// The units a model may write: coherent SI only, since values are taken as written.
const std::vector<NamedUnit>& coherent_units() {
  static const std::vector<NamedUnit> units = {
      {"kg", kg}, {"m", m}, {"s", s}, {"A", Dimension::of(Base::ampere)}, {"K", Dimension::of(Base::kelvin)},
      {"mol", Dimension::of(Base::mole)}, {"cd", Dimension::of(Base::candela)}, {"rad", Dimension()},
      {"sr", Dimension()}, {"N", newton}, {"J", newton * m}, {"W", newton * m / s}, {"Pa", newton / (m * m)},
      {"Hz", Dimension() / s}, {"C", Dimension::of(Base::ampere) * s},
      {"V", newton * m / (s * Dimension::of(Base::ampere))}};
  return units;
}

// The names a message adds to base units, first match first: the loads and coefficients of
// mechanics. "J" has the dimension of "N m" and is named only where preferred (an energy).
const std::vector<NamedUnit>& named_units() {
  static const std::vector<NamedUnit> units = {
      {"N", newton},        {"N m", newton * m}, {"J", newton * m},       {"W", newton * m / s},
      {"Pa", newton / (m * m)}, {"N/m", newton / m}, {"N s/m", newton * s / m}, {"N m s", newton * m * s}};
  return units;
}

const char* const base_symbols[Dimension::base_count] = {"kg", "m", "s", "A", "K", "mol", "cd"};

std::optional<Dimension> require_dimensionless(const ex& argument, const std::optional<Dimension>& d, const ex& call) {
  if (d && !d->is_dimensionless())
    throw DimensionError({DimensionMismatch::Kind::argument, argument, call, *d, Dimension()});
  return Dimension();
}

}  // namespace

std::optional<Dimension> coherent_unit(const std::string& symbol) {
  for (const NamedUnit& u : coherent_units())
    if (symbol == u.symbol) return u.dimension;
  return std::nullopt;
}

std::string coherent_unit_list() {
  std::string out;
  for (const NamedUnit& u : coherent_units()) out += (out.empty() ? "" : ", ") + std::string(u.symbol);
  return out;
}

std::string base_units(const Dimension& d) {
  if (d.is_dimensionless()) return "dimensionless";
  std::string out;
  for (std::size_t i = 0; i < Dimension::base_count; ++i) {
    const Exponent e = d.exponent(static_cast<Base>(i));
    if (e.is_zero()) continue;
    out += out.empty() ? "" : " ";
    out += base_symbols[i];
    if (e.denominator() != 1)
      out += fmt::format("^({}/{})", e.numerator(), e.denominator());
    else if (e.numerator() != 1)
      out += fmt::format("^{}", e.numerator());
  }
  return out;
}

std::string to_string(const Dimension& d, const std::string& preferred) {
  const std::string base = base_units(d);
  std::string name;
  for (const NamedUnit& u : named_units())
    if (u.dimension == d && (preferred == u.symbol || (name.empty() && std::string(u.symbol) != "J"))) name = u.symbol;
  return name.empty() || name == base ? base : fmt::format("{} ({})", base, name);
}

std::string term_text(const ex& e, std::size_t limit) {
  std::string text = ordered_text(e);
  if (text.size() > limit) text = text.substr(0, limit) + "...";
  return text;
}

// Of a sum whose terms disagree, the two a message names: the first term in the order of their
// text and the first after it that disagrees with it (GiNaC's own order differs between runs).
DimensionMismatch DimensionAnalysis::first_disagreement(const ex& sum) {
  std::vector<std::pair<std::string, ex>> terms;
  for (const ex& term : sum) terms.emplace_back(term_text(term, std::string::npos), term);
  std::sort(terms.begin(), terms.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::optional<Dimension> common;
  ex first;
  for (const auto& [text, term] : terms) {
    const std::optional<Dimension> d = of(term);
    if (!d) continue;
    if (!common) {
      common = d;
      first = term;
    } else if (*d != *common) {
      return {DimensionMismatch::Kind::sum, first, term, *common, *d};
    }
  }
  EOMGEN_UNREACHABLE("first_disagreement: a sum whose terms all agree");
}

std::string DimensionMismatch::describe() const {
  switch (kind) {
    case Kind::sum:
      return fmt::format("the terms '{}' and '{}' have different dimensions, {} and {}", term_text(first),
                         term_text(second), to_string(first_dimension), to_string(second_dimension));
    case Kind::argument:
      return fmt::format("the argument '{}' of '{}' has dimension {}, expected dimensionless", term_text(first),
                         term_text(second), to_string(first_dimension));
    case Kind::arguments:
      return fmt::format("the arguments '{}' and '{}' of atan2 have different dimensions, {} and {}",
                         term_text(first), term_text(second), to_string(first_dimension),
                         to_string(second_dimension));
    case Kind::exponent:
      return fmt::format("the power with base '{}' ({}) and exponent '{}' ({}) needs a dimensionless base where "
                         "the exponent is not a rational number, and a dimensionless exponent",
                         term_text(first), to_string(first_dimension), term_text(second),
                         to_string(second_dimension));
  }
  EOMGEN_UNREACHABLE("DimensionMismatch::describe: a Kind outside its enumerators");
}

std::optional<Dimension> DimensionAnalysis::of(const ex& e) {
  if (const std::optional<Dimension>* known = memo_.find(e)) return *known;
  std::optional<Dimension> d = measure(e);
  memo_.emplace(e, d);
  return d;
}

std::optional<Dimension> DimensionAnalysis::measure(const ex& e) {
  if (GiNaC::is_a<GiNaC::numeric>(e)) return e.is_zero() ? std::nullopt : std::optional<Dimension>(Dimension());
  if (GiNaC::is_a<GiNaC::constant>(e)) return Dimension();
  if (GiNaC::is_a<GiNaC::symbol>(e)) {
    const auto it = symbols_.find(e);
    EOMGEN_DEMAND(it != symbols_.end(), fmt::format("DimensionAnalysis: the symbol '{}' has no dimension", term_text(e)));
    return it->second;
  }
  if (GiNaC::is_a<GiNaC::add>(e)) {
    std::optional<Dimension> common;
    for (const ex& term : e) {
      const std::optional<Dimension> d = of(term);
      if (!d) continue;
      if (!common) common = d;
      else if (*d != *common) throw DimensionError(first_disagreement(e));  // named in a fixed order
    }
    return common;
  }
  if (GiNaC::is_a<GiNaC::mul>(e) || GiNaC::is_a<GiNaC::ncmul>(e)) {
    Dimension product;
    for (const ex& factor : e) {
      const std::optional<Dimension> d = of(factor);
      if (!d) return std::nullopt;
      product = product * *d;
    }
    return product;
  }
  if (GiNaC::is_a<GiNaC::power>(e)) {
    const ex base = e.op(0), exponent = e.op(1);
    const std::optional<Dimension> b = of(base);
    if (GiNaC::is_a<GiNaC::numeric>(exponent) && GiNaC::ex_to<GiNaC::numeric>(exponent).is_rational()) {
      if (!b) return std::nullopt;
      const GiNaC::numeric k = GiNaC::ex_to<GiNaC::numeric>(exponent);
      if (b->is_dimensionless()) return Dimension();
      // exponents of dimensioned quantities are small (the language bounds them by 100)
      EOMGEN_DEMAND(GiNaC::abs(k.numer()) < 1000000 && k.denom() < 1000000,
                    fmt::format("DimensionAnalysis: the exponent {} is too large", term_text(exponent)));
      return b->power(Exponent(k.numer().to_long(), k.denom().to_long()));
    }
    const std::optional<Dimension> x = of(exponent);
    if ((b && !b->is_dimensionless()) || (x && !x->is_dimensionless()))
      throw DimensionError({DimensionMismatch::Kind::exponent, base, exponent, b.value_or(Dimension()),
                            x.value_or(Dimension())});
    return Dimension();
  }
  if (GiNaC::is_a<GiNaC::function>(e)) return function(e);
  EOMGEN_UNREACHABLE(fmt::format("DimensionAnalysis: no dimension for '{}'", term_text(e)));
}

std::optional<Dimension> DimensionAnalysis::function(const ex& e) {
  const std::string name = GiNaC::ex_to<GiNaC::function>(e).get_name();
  // a quantity's magnitude or its real part keeps its dimension
  if (name == "abs" || name == "conjugate" || name == "real_part" || name == "imag_part") return of(e.op(0));
  if (name == "atan2") {
    const std::optional<Dimension> y = of(e.op(0)), x = of(e.op(1));
    if (y && x && *y != *x) throw DimensionError({DimensionMismatch::Kind::arguments, e.op(0), e.op(1), *y, *x});
    return Dimension();
  }
  // a sign is dimensionless whatever its argument's dimension
  if (name == "csgn" || name == "step") {
    of(e.op(0));
    return Dimension();
  }
  // sin, cos, exp, log... and any other function: a series in its argument, which must be a number
  for (const ex& argument : e) require_dimensionless(argument, of(argument), e);
  return Dimension();
}

std::optional<std::pair<ex, Dimension>> first_term_not_of(DimensionAnalysis& analysis, const ex& value,
                                                          const Dimension& expected) {
  const std::vector<ex> terms = GiNaC::is_a<GiNaC::add>(value) ? std::vector<ex>(value.begin(), value.end())
                                                                : std::vector<ex>{value};
  std::optional<std::pair<ex, Dimension>> wrong;
  std::string wrong_text;
  for (const ex& term : terms) {
    const std::optional<Dimension> d = analysis.of(term);
    if (!d || *d == expected) continue;
    const std::string text = term_text(term, std::string::npos);
    if (!wrong || text < wrong_text) wrong.emplace(term, *d), wrong_text = text;
  }
  return wrong;
}

}  // namespace eomgen
