#include "eomgen/mechanics/variables.hpp"

#include "eomgen/symbolic/expression_map.hpp"
#include "eomgen/symbolic/graph_calculus.hpp"
#include "eomgen/symbolic/ordered_text.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>

#include "eomgen/base/error.hpp"

namespace eomgen {
namespace {

bool is_identifier(const std::string& name) {
  if (name.empty() || !(std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_'))
    return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
  });
}

const char* const greek[] = {"alpha", "beta", "gamma", "delta", "epsilon", "zeta", "eta", "theta",
                             "iota", "kappa", "lambda", "mu", "nu", "xi", "pi", "rho", "sigma", "tau",
                             "upsilon", "phi", "chi", "psi", "omega", "Gamma", "Delta", "Theta",
                             "Lambda", "Xi", "Pi", "Sigma", "Upsilon", "Phi", "Psi", "Omega"};

// a letter group as LaTeX: Greek names become commands, one letter stays, longer words upright
std::string tex_word(const std::string& word) {
  for (const char* g : greek)
    if (word == g) return std::string("\\") + g;
  if (word.size() <= 1) return word;
  return "\\mathrm{" + word + "}";
}

GiNaC::ex code(SymbolKind kind) { return static_cast<int>(kind); }

// Collects every symbol of e into out. Expressions from compounded rotations share
// subtrees, so they are small graphs but exponentially large trees: each shared node is
// visited once (ExpressionMap: one lookup per node, never a comparison of trees).
void collect_symbols(const GiNaC::ex& e, GiNaC::exset& out, ExpressionMap<bool>& visited) {
  if (GiNaC::is_a<GiNaC::symbol>(e)) {
    out.insert(e);
    return;
  }
  if (e.nops() == 0 || !visited.emplace(e, true).second) return;
  for (std::size_t i = 0; i < e.nops(); ++i) collect_symbols(e.op(i), out, visited);
}

void collect_symbols(const GiNaC::ex& e, GiNaC::exset& out) {
  ExpressionMap<bool> visited;
  collect_symbols(e, out, visited);
}

}  // namespace

std::string tex_name(const std::string& name) {
  // rates and accelerations get dots over the coordinate's own TeX name
  auto ends_with = [&](const std::string& suffix) {
    return name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
  };
  if (ends_with("_ddot")) return "\\ddot{" + tex_name(name.substr(0, name.size() - 5)) + "}";
  if (ends_with("_dot")) return "\\dot{" + tex_name(name.substr(0, name.size() - 4)) + "}";
  // base_rest -> base_{rest}; trailing digits -> subscript
  const auto underscore = name.find('_');
  if (underscore != std::string::npos && underscore > 0 && underscore + 1 < name.size())
    return tex_name(name.substr(0, underscore)) + "_{" + tex_name(name.substr(underscore + 1)) + "}";
  std::size_t digits = name.size();
  while (digits > 0 && std::isdigit(static_cast<unsigned char>(name[digits - 1]))) --digits;
  if (digits > 0 && digits < name.size()) return tex_word(name.substr(0, digits)) + "_{" + name.substr(digits) + "}";
  return tex_word(name);
}

Variables::Variables() : time_("t") {
  names_.insert("t");
  kinds_[time_] = code(SymbolKind::time);
}

void Variables::check_name(const std::string& name) const {
  if (!is_identifier(name))
    throw ModelError(fmt::format("declaring '{}': a name must be an identifier "
                                 "(a letter or '_' followed by letters, digits or '_')", name));
  if (names_.count(name))
    throw ModelError(fmt::format("declaring '{}': the name is already used", name));
}

void Variables::claim_name(const std::string& name) {
  check_name(name);
  names_.insert(name);
}

Coordinate Variables::add_coordinate(const std::string& name, const std::string& unit) {
  // the rate and acceleration names are reserved too, so "x_dot" cannot be declared twice;
  // all three are checked before any is claimed, so a failed declaration changes nothing
  check_name(name);
  check_name(name + "_dot");
  check_name(name + "_ddot");
  claim_name(name);
  claim_name(name + "_dot");
  claim_name(name + "_ddot");
  Coordinate c{name, GiNaC::realsymbol(name, tex_name(name)),
               GiNaC::realsymbol(name + "_dot", tex_name(name + "_dot")),
               GiNaC::realsymbol(name + "_ddot", tex_name(name + "_ddot")), unit};
  kinds_[c.q] = code(SymbolKind::coordinate);
  kinds_[c.qd] = code(SymbolKind::rate);
  kinds_[c.qdd] = code(SymbolKind::acceleration);
  rate_to_zero_[c.qd] = 0;
  acceleration_to_zero_[c.qdd] = 0;
  coordinates_.push_back(c);
  return coordinates_.back();
}

Parameter Variables::add_parameter(const std::string& name, double default_value,
                                          const std::string& unit) {
  claim_name(name);
  Parameter p{name, GiNaC::realsymbol(name, tex_name(name)), default_value, unit};
  kinds_[p.symbol] = code(SymbolKind::parameter);
  default_values_[p.symbol] = default_value;
  parameters_.push_back(p);
  return parameters_.back();
}

DerivedParameter Variables::add_derived_parameter(const std::string& name, const GiNaC::ex& definition,
                                                 const std::string& unit) {
  check_name(name);
  // numbers and the parameters declared so far only: then the definitions, in order, compute
  // every derived parameter from values already known
  std::optional<std::string> other;
  const GiNaC::exset symbols = symbols_of(definition);
  for (const GiNaC::ex& s : symbols) {
    const std::optional<SymbolKind> kind = kind_of(s);
    const std::string symbol_name = GiNaC::ex_to<GiNaC::symbol>(s).get_name();
    if ((!kind || !is_parameter_kind(*kind)) && (!other || symbol_name < *other)) other = symbol_name;
  }
  if (other)
    throw ModelError(fmt::format("parameter '{}': its definition names '{}', which is no parameter declared before "
                                 "it: expected numbers, parameters and derived parameters declared before it",
                                 name, *other));
  DoubleEvaluator at_defaults;
  for (const GiNaC::ex& s : symbols)
    at_defaults.set(s, GiNaC::ex_to<GiNaC::numeric>(default_values_.at(s)).to_double());
  const double value = at_defaults.value(definition, fmt::format("parameter '{}'", name));
  if (!std::isfinite(value))
    throw ModelError(fmt::format("parameter '{}': the value at the other parameters' default values is not a finite "
                                 "real number: expected a definition that has one", name));
  claim_name(name);
  DerivedParameter d{name, GiNaC::realsymbol(name, tex_name(name)), definition, value, unit};
  kinds_[d.symbol] = code(SymbolKind::derived_parameter);
  default_values_[d.symbol] = value;
  derived_parameters_.push_back(d);
  return derived_parameters_.back();
}

Input Variables::add_input(const std::string& name, const std::string& unit) {
  claim_name(name);
  Input u{name, GiNaC::realsymbol(name, tex_name(name)), unit};
  kinds_[u.symbol] = code(SymbolKind::input);
  inputs_.push_back(u);
  return inputs_.back();
}

std::optional<GiNaC::realsymbol> Variables::find(const std::string& name) const {
  if (name == "t") return time_;
  for (const auto& c : coordinates_) {
    if (c.name == name) return c.q;
    if (c.qd.get_name() == name) return c.qd;
    if (c.qdd.get_name() == name) return c.qdd;
  }
  for (const auto& p : parameters_)
    if (p.name == name) return p.symbol;
  for (const auto& d : derived_parameters_)
    if (d.name == name) return d.symbol;
  for (const auto& u : inputs_)
    if (u.name == name) return u.symbol;
  return std::nullopt;
}

std::optional<SymbolKind> Variables::kind_of(const GiNaC::ex& symbol) const {
  auto it = kinds_.find(symbol);
  if (it == kinds_.end()) return std::nullopt;
  return static_cast<SymbolKind>(GiNaC::ex_to<GiNaC::numeric>(it->second).to_int());
}

std::optional<std::size_t> Variables::coordinate_index(const GiNaC::ex& symbol) const {
  for (std::size_t k = 0; k < coordinates_.size(); ++k) {
    const auto& c = coordinates_[k];
    if (symbol.is_equal(c.q) || symbol.is_equal(c.qd) || symbol.is_equal(c.qdd)) return k;
  }
  return std::nullopt;
}

void Variables::require_known_symbols(const GiNaC::ex& e, const std::string& what) const {
  GiNaC::exset symbols;
  collect_symbols(e, symbols);
  // the set iterates in GiNaC's address-seeded order: name the alphabetically first unknown
  // symbol, so that the message is the same in every process
  std::optional<std::string> unknown;
  for (const auto& s : symbols)
    if (kinds_.find(s) == kinds_.end()) {
      const std::string name = GiNaC::ex_to<GiNaC::symbol>(s).get_name();
      if (!unknown || name < *unknown) unknown = name;
    }
  if (unknown)
    throw ModelError(fmt::format("{}: '{}' is not a time, coordinate, rate, parameter or input of this model",
                                 what, *unknown));
}

GiNaC::ex Variables::time_derivative(const GiNaC::ex& e) const {
  GiNaC::exset symbols;
  collect_symbols(e, symbols);
  GiNaC::exmap rates;  // each symbol's rate
  for (const auto& s : symbols) {
    auto kind = kind_of(s);
    if (!kind)
      throw DerivationError(fmt::format("time derivative: '{}' is not a symbol of this model",
                                        GiNaC::ex_to<GiNaC::symbol>(s).get_name()));
    switch (*kind) {
      case SymbolKind::time:
        rates[s] = 1;
        break;
      case SymbolKind::coordinate:
        rates[s] = coordinates_[*coordinate_index(s)].qd;
        break;
      case SymbolKind::rate:
        rates[s] = coordinates_[*coordinate_index(s)].qdd;
        break;
      case SymbolKind::acceleration:
        throw DerivationError(fmt::format(
            "time derivative: the expression contains the acceleration '{}', whose rate is not "
            "a variable of the model", GiNaC::ex_to<GiNaC::symbol>(s).get_name()));
      case SymbolKind::input:
        throw DerivationError(fmt::format(
            "time derivative: the expression contains the input '{}', whose rate is unknown; "
            "inputs may appear in loads but not in positions, rotations or constraints",
            GiNaC::ex_to<GiNaC::symbol>(s).get_name()));
      case SymbolKind::parameter:
      case SymbolKind::derived_parameter:
        break;
    }
  }
  return directional_derivative(e, rates);
}

std::vector<std::size_t> Variables::parameters_in(const GiNaC::ex& e) const {
  // the parameters of each derived parameter, in order: each from those before it
  std::vector<std::vector<bool>> of_derived;
  std::vector<bool> used(parameters_.size(), false);
  const auto mark = [&](const GiNaC::ex& expression, std::vector<bool>& into) {
    for (const GiNaC::ex& s : symbols_of(expression)) {
      for (std::size_t k = 0; k < parameters_.size(); ++k)
        if (s.is_equal(parameters_[k].symbol)) into[k] = true;
      for (std::size_t k = 0; k < of_derived.size(); ++k)
        if (s.is_equal(derived_parameters_[k].symbol))
          for (std::size_t j = 0; j < into.size(); ++j) into[j] = into[j] || of_derived[k][j];
    }
  };
  for (const DerivedParameter& d : derived_parameters_) {
    of_derived.emplace_back(parameters_.size(), false);
    mark(d.definition, of_derived.back());
  }
  mark(e, used);
  std::vector<std::size_t> indices;
  for (std::size_t k = 0; k < used.size(); ++k)
    if (used[k]) indices.push_back(k);
  return indices;
}

void Variables::evaluate_derived_parameters(DoubleEvaluator& values) const {
  for (const DerivedParameter& d : derived_parameters_) {
    const double value = values.value(d.definition, fmt::format("derived parameter '{}'", d.name));
    if (!std::isfinite(value))
      throw Error(fmt::format("derived parameter '{}' = {}: its value at these parameters is not a finite real number",
                              d.name, ordered_text(d.definition)));
    values.set(d.symbol, value);
  }
}

bool is_parameter_kind(SymbolKind kind) {
  switch (kind) {
    case SymbolKind::parameter:
    case SymbolKind::derived_parameter:
      return true;
    case SymbolKind::time:
    case SymbolKind::coordinate:
    case SymbolKind::rate:
    case SymbolKind::acceleration:
    case SymbolKind::input:
      return false;
  }
  EOMGEN_UNREACHABLE("is_parameter_kind: a SymbolKind outside its enumerators");
}

GiNaC::exset symbols_of(const GiNaC::ex& e) {
  GiNaC::exset symbols;
  collect_symbols(e, symbols);
  return symbols;
}

std::optional<double> value_in_doubles(const GiNaC::ex& e, const GiNaC::exmap& values) {
  DoubleEvaluator evaluator;
  for (const GiNaC::ex& symbol : symbols_of(e)) {  // e's few, not the map's hundreds
    const auto value = values.find(symbol);
    if (value == values.end()) continue;
    const GiNaC::ex number = value->second.evalf();
    if (GiNaC::is_a<GiNaC::numeric>(number) && GiNaC::ex_to<GiNaC::numeric>(number).is_real())
      evaluator.set(symbol, GiNaC::ex_to<GiNaC::numeric>(number).to_double());
  }
  try {
    return evaluator.value(e, "an expression");
  } catch (const Error&) {  // a symbol without a value, a complex number
    return std::nullopt;
  }
}

bool Variables::contains(const GiNaC::ex& e, SymbolKind kind) const {
  for (const GiNaC::ex& s : symbols_of(e))
    if (kind_of(s) == kind) return true;
  return false;
}

GiNaC::ex Variables::at_rest(const GiNaC::ex& e) const { return substitute(e, rate_to_zero_); }

GiNaC::ex Variables::without_accelerations(const GiNaC::ex& e) const { return substitute(e, acceleration_to_zero_); }

GiNaC::lst Variables::coordinate_list() const {
  GiNaC::lst l;
  for (const auto& c : coordinates_) l.append(c.q);
  return l;
}

GiNaC::lst Variables::rate_list() const {
  GiNaC::lst l;
  for (const auto& c : coordinates_) l.append(c.qd);
  return l;
}

}  // namespace eomgen
