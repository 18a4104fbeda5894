#include "parameter_coefficients.hpp"

#include <vector>

#include "eomgen/symbolic/expression_map.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;

bool parameter_only(const ex& e, const Variables& variables) {
  if (GiNaC::is_a<GiNaC::symbol>(e)) {
    const auto kind = variables.kind_of(e);
    return kind && is_parameter_kind(*kind);
  }
  for (std::size_t i = 0; i < e.nops(); ++i)
    if (!parameter_only(e.op(i), variables)) return false;
  return true;
}

}  // namespace

ex collect_parameter_coefficients(const ex& sum, const Variables& variables) {
  if (!GiNaC::is_a<GiNaC::add>(sum)) return sum;
  // the groups in the order of their first term, so the result does not depend on how the
  // monomials compare
  std::vector<ex> monomials;
  ExpressionMap<GiNaC::exvector> coefficients;
  for (std::size_t i = 0; i < sum.nops(); ++i) {
    const ex term = sum.op(i);
    GiNaC::exvector parameter_factors, state_factors;
    const bool product = GiNaC::is_a<GiNaC::mul>(term);
    for (std::size_t j = 0; j < (product ? term.nops() : 1); ++j) {
      const ex factor = product ? term.op(j) : term;
      (parameter_only(factor, variables) ? parameter_factors : state_factors).push_back(factor);
    }
    const ex monomial = GiNaC::mul(state_factors);
    auto [coefficient, inserted] = coefficients.emplace(monomial, {});
    if (inserted) monomials.push_back(monomial);
    coefficient->push_back(GiNaC::mul(parameter_factors));
  }
  GiNaC::exvector terms;
  for (const ex& monomial : monomials) terms.push_back(GiNaC::add(coefficients[monomial]) * monomial);
  return GiNaC::add(terms);
}

}  // namespace eomgen
