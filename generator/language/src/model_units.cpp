// The unit check of a model that gives units: coordinates' dimensions inferred from the rotations
// and points they enter, then every obligation the elaborator recorded checked term by term.
#include "model_units.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <utility>

#include "eomgen/base/error.hpp"

namespace eomgen::syntax {
namespace {

using GiNaC::ex;

std::string at_text(const SourceLocation& at) { return fmt::format("{}:{}:{}", at.file, at.line, at.column); }

bool before(const SourceLocation& a, const SourceLocation& b) {
  return std::make_pair(a.line, a.column) < std::make_pair(b.line, b.column);
}

// functions whose arguments are dimensionless (the rest keep or compare theirs)
bool takes_a_number(const ex& f) {
  const std::string name = GiNaC::ex_to<GiNaC::function>(f).get_name();
  return name != "abs" && name != "atan2" && name != "csgn" && name != "step" && name != "conjugate" &&
         name != "real_part" && name != "imag_part";
}

}  // namespace

void UnitChecks::note(const Statement& s) {
  auto consider = [&](const std::optional<Unit>& unit) {
    if (unit && (!first_ || before(unit->location, *first_))) first_ = unit->location;
  };
  consider(s.unit);
  for (const std::optional<Unit>& unit : s.units) consider(unit);
}

void UnitChecks::missing(const std::string& kind, const std::string& name, const SourceLocation& at,
                         const std::string& where) const {
  throw SourceError(at, fmt::format("{} '{}' has no unit, but the model gives units (the first at {}): expected "
                                    "[UNIT] {}, or [-] for a dimensionless {}",
                                    kind, name, at_text(*first_), where, kind));
}

void UnitChecks::parameter(const Parameter& p, const std::optional<Unit>& unit, const SourceLocation& at) {
  if (!active()) return;
  if (!unit) missing("parameter", p.name, at, "after its value");
  known_[p.symbol] = unit->dimension;
  parameters_.define(p.symbol, unit->dimension);
}

void UnitChecks::coordinate(const Coordinate& c, const std::optional<Unit>& unit) {
  if (!active()) return;
  if (!unit) {
    unknown_.push_back(c);
    return;
  }
  known_[c.q] = unit->dimension;
  known_[c.qd] = unit->dimension / dimension::s();
  known_[c.qdd] = unit->dimension / (dimension::s() * dimension::s());
}

void UnitChecks::input(const Input& u, const std::optional<Unit>& unit, const SourceLocation& at) {
  if (!active()) return;
  if (!unit) missing("input", u.name, at, "after its name");
  known_[u.symbol] = unit->dimension;
}

void UnitChecks::derived_parameter(const DerivedParameter& d, const std::optional<Unit>& unit,
                                   const SourceLocation& at, const std::string& what) {
  if (!active()) return;
  if (unit) {
    known_[d.symbol] = unit->dimension;
    parameters_.define(d.symbol, unit->dimension);
    require(d.definition, expect(unit->dimension, at, what, "its unit [" + unit->text + "]"));
    return;
  }
  // the symbols of the definition were declared before it, so their dimensions are known
  try {
    known_[d.symbol] = parameters_.of(d.definition).value_or(Dimension());
    parameters_.define(d.symbol, known_[d.symbol]);
  } catch (const DimensionError& e) {
    throw SourceError(at, fmt::format("{}: {}", what, e.mismatch().describe()));
  }
}

void UnitChecks::require(const ex& value, const Obligation& obligation) {
  if (!active() || value.is_zero()) return;
  obligations_.push_back(obligation);
  obligations_.back().value = value;
}

void UnitChecks::require(const Vector& v, const Obligation& each) {
  if (!active()) return;
  for (const auto& [frame, components] : v.terms())
    for (unsigned i = 0; i < 3; ++i) require(components(i, 0), each);
}

void UnitChecks::require(const GiNaC::matrix& entries, const Obligation& each) {
  if (!active()) return;
  for (unsigned i = 0; i < entries.rows(); ++i)
    for (unsigned j = 0; j < entries.cols(); ++j) require(entries(i, j), each);
}

void UnitChecks::require_consistent(const ex& value, const SourceLocation& at, const std::string& what) {
  if (!active()) return;
  Obligation o;
  o.at = at;
  o.what = what;
  require(value, o);
}

bool UnitChecks::has_unknown(const ex& e) const {
  for (const Coordinate& c : unknown_)
    if (e.has(c.q) || e.has(c.qd) || e.has(c.qdd)) return true;
  return false;
}

void UnitChecks::fix(const Coordinate& c, const Dimension& d, DimensionAnalysis& analysis) {
  analysis.define(c.q, d);
  analysis.define(c.qd, d / dimension::s());
  analysis.define(c.qdd, d / (dimension::s() * dimension::s()));
  unknown_.erase(std::find_if(unknown_.begin(), unknown_.end(), [&](const Coordinate& u) { return u.name == c.name; }));
}

// What `value`, of dimension `expected`, says of the coordinates of unknown dimension: in a
// term where one factor holds them all, that factor has the dimension the others leave; where it
// is such a coordinate or a power of it, that fixes the coordinate. A function's argument is
// dimensionless. Returns whether a coordinate was fixed.
bool UnitChecks::infer(const ex& value, const Dimension& expected, DimensionAnalysis& analysis) {
  if (GiNaC::is_a<GiNaC::add>(value)) {
    bool fixed = false;
    for (const ex& term : value) fixed = infer(term, expected, analysis) || fixed;
    return fixed;
  }
  const std::vector<ex> factors = GiNaC::is_a<GiNaC::mul>(value) ? std::vector<ex>(value.begin(), value.end())
                                                                  : std::vector<ex>{value};
  Dimension known;
  const ex* open = nullptr;
  bool fixed = false;
  for (const ex& f : factors) {
    if (!has_unknown(f)) {
      std::optional<Dimension> d;
      try {
        d = analysis.of(f);
      } catch (const DimensionError&) {
        return fixed;  // reported by the check
      }
      if (!d) return fixed;
      known = known * *d;
    } else if (GiNaC::is_a<GiNaC::function>(f) && takes_a_number(f)) {
      for (const ex& argument : f) fixed = infer(argument, Dimension(), analysis) || fixed;
    } else if (open) {
      return fixed;  // two factors hold unknowns: this term fixes neither
    } else {
      open = &f;
    }
  }
  if (!open) return fixed;
  const Dimension needed = expected / known;
  ex base = *open;
  Exponent power = 1;
  if (GiNaC::is_a<GiNaC::power>(base) && GiNaC::is_a<GiNaC::numeric>(base.op(1)) &&
      GiNaC::ex_to<GiNaC::numeric>(base.op(1)).is_rational() && !base.op(1).is_zero()) {
    const GiNaC::numeric k = GiNaC::ex_to<GiNaC::numeric>(base.op(1));
    if (GiNaC::abs(k.numer()) > 1000 || k.denom() > 1000) return fixed;
    power = Exponent(k.numer().to_long(), k.denom().to_long());
    base = base.op(0);
  }
  const Dimension base_needed = needed.power(Exponent(power.denominator(), power.numerator()));
  for (const Coordinate& c : unknown_)
    if (base.is_equal(c.q)) {
      fix(c, base_needed, analysis);
      return true;
    }
  if (GiNaC::is_a<GiNaC::add>(base)) return infer(base, base_needed, analysis) || fixed;
  return fixed;
}

void UnitChecks::check(const Obligation& o, DimensionAnalysis& analysis) const {
  try {
    if (!o.expected) {
      analysis.of(o.value);
      return;
    }
    Dimension expected = *o.expected;
    if (!o.power.is_zero()) {
      const std::optional<Dimension> relative = analysis.of(o.relative);
      if (!relative) return;  // zero: nothing to compare with
      expected = expected * relative->power(o.power);
    }
    if (const auto wrong = first_term_not_of(analysis, o.value, expected))
      throw SourceError(o.at, fmt::format("{}: the term '{}' has dimension {}, expected {} for {}", o.what,
                                          term_text(wrong->first), to_string(wrong->second, o.preferred),
                                          to_string(expected, o.preferred), o.role));
  } catch (const DimensionError& e) {
    throw SourceError(o.at, fmt::format("{}: {}", o.what, e.mismatch().describe()));
  }
}

DimensionMap UnitChecks::finish(const Variables& vars, const std::vector<SourceLocation>& coordinate_locations) {
  if (!active()) return {};
  known_[vars.time()] = dimension::s();
  DimensionAnalysis analysis(known_);
  // angles first: a coordinate that turns a frame is an angle even where a point uses it too
  for (const Evidence evidence : {Evidence::rotation, Evidence::position}) {
    bool fixed = true;
    while (fixed && !unknown_.empty()) {
      fixed = false;
      for (const Obligation& o : obligations_)
        if (o.evidence != Evidence::none && o.evidence <= evidence && o.expected && !unknown_.empty())
          fixed = infer(o.value, *o.expected, analysis) || fixed;
    }
  }
  if (!unknown_.empty()) {
    const Coordinate& c = unknown_.front();
    std::size_t k = 0;
    while (vars.coordinates()[k].name != c.name) ++k;
    throw SourceError(coordinate_locations.at(k),
                      fmt::format("coordinate '{}' has no unit, and the rotations and points it enters do not fix "
                                  "one, but the model gives units (the first at {}): expected '{} [UNIT]'",
                                  c.name, at_text(*first_), c.name));
  }
  for (const Coordinate& c : vars.coordinates())
    for (const ex& symbol : {ex(c.q), ex(c.qd), ex(c.qdd)})
      if (!known_.count(symbol)) {
        // inferred: the analysis knows it
        known_[symbol] = *analysis.of(symbol);
      }
  for (const Obligation& o : obligations_) check(o, analysis);
  return known_;
}

}  // namespace eomgen::syntax
