// The derived equations against the model's units, term by term.
#include "eomgen/derivation/dimension_check.hpp"

#include <fmt/format.h>

#include <optional>
#include <string>

#include "eomgen/base/error.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;

class Checker {
 public:
  explicit Checker(const DimensionMap& dimensions) : analysis_(dimensions) {}

  void intermediates(const Subexpressions& shared) {
    for (const Subexpressions::Definition& d : shared.definitions()) {
      const std::optional<Dimension> dimension = measure(d.value, fmt::format("the intermediate '{}'", d.symbol.get_name()));
      // zero is never bound; an intermediate that is one anyway fits as a number
      analysis_.define(d.symbol, dimension.value_or(Dimension()));
    }
  }

  // every term of `value` has dimension `expected`
  void terms(const ex& value, const Dimension& expected, const std::string& where) {
    try {
      if (const auto wrong = first_term_not_of(analysis_, value, expected))
        fail(where, fmt::format("the term '{}' has dimension {}, expected {}", term_text(wrong->first),
                                to_string(wrong->second, "J"), to_string(expected, "J")));
    } catch (const DimensionError& e) {
      fail(where, e.mismatch().describe());
    }
  }

  std::optional<Dimension> measure(const ex& value, const std::string& where) {
    try {
      return analysis_.of(value);
    } catch (const DimensionError& e) {
      fail(where, e.mismatch().describe());
    }
  }

  Dimension of(const ex& symbol) { return *analysis_.of(symbol); }

  [[noreturn]] static void fail(const std::string& where, const std::string& what) {
    throw DerivationError(fmt::format("the derived equations break the model's units (a bug in eomgen): {}: {}", where,
                                      what));
  }

 private:
  DimensionAnalysis analysis_;
};

}  // namespace

void check_dimensions(const EquationsOfMotion& eom, const Variables& vars, const DimensionMap& dimensions) {
  if (dimensions.empty()) return;
  Checker check(dimensions);
  check.intermediates(eom.subexpressions);
  const auto& coordinates = vars.coordinates();
  const std::size_t n = coordinates.size();
  for (std::size_t i = 0; i < n; ++i) {
    // row i is the equation of q_i: generalized forces, J per unit of q_i
    const Dimension row = dimension::joule() / check.of(coordinates[i].q);
    for (std::size_t j = 0; j < n; ++j)
      check.terms(eom.mass_matrix(i, j), row / check.of(coordinates[j].qdd),
                  fmt::format("M({}, {}), row of '{}', column of '{}'", i + 1, j + 1, coordinates[i].name,
                              coordinates[j].name));
    check.terms(eom.forcing(i, 0), row, fmt::format("F({}), row of '{}'", i + 1, coordinates[i].name));
  }
  check.terms(eom.kinetic_energy, dimension::joule(), "T");
  check.terms(eom.potential_energy, dimension::joule(), "V");
  for (std::size_t r = 0; r < eom.constraint_count; ++r) {
    // the row's dimension is that of its first term; every other must agree
    GiNaC::exvector parts;
    for (std::size_t j = 0; j < n; ++j) parts.push_back(eom.constraint_jacobian(r, j) * coordinates[j].qd);
    parts.push_back(eom.constraint_rate_term(r, 0));
    const std::string where = fmt::format("constraint row {} (Xi qd + Xi_t)", r + 1);
    std::optional<Dimension> dimension;
    for (const ex& part : parts)
      if (!dimension && !part.is_zero()) dimension = check.measure(part, where);
    if (!dimension) continue;
    for (const ex& part : parts) check.terms(part, *dimension, where);
    check.terms(eom.constraint_acceleration_term(r, 0), *dimension / dimension::s(), fmt::format("b({})", r + 1));
  }
  for (unsigned r = 0; r < eom.holonomic_residuals.rows(); ++r)
    check.measure(eom.holonomic_residuals(r, 0), fmt::format("phi({})", r + 1));
}

}  // namespace eomgen
