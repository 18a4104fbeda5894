#include "forward_dynamics_derivatives.hpp"

#include <limits>
#include <memory>
#include <utility>

#include "eomgen/symbolic/graph_calculus.hpp"
#include "chain_rule.hpp"
#include "ldl_factor.hpp"
#include "operation_estimate.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;
using GiNaC::matrix;

unsigned input_count(const Variables& variables) { return unsigned(variables.inputs().size()); }

std::vector<ex> state_and_input_symbols(const Variables& variables) {
  std::vector<ex> symbols;
  for (const Coordinate& c : variables.coordinates()) symbols.push_back(c.q);
  for (const Coordinate& c : variables.coordinates()) symbols.push_back(c.qd);
  for (const Input& u : variables.inputs()) symbols.push_back(u.symbol);
  return symbols;
}

ForwardDynamicsDerivatives empty_derivatives(unsigned n, unsigned nu) {
  ForwardDynamicsDerivatives d;
  d.by_coordinates = matrix(n, n);
  d.by_rates = matrix(n, n);
  d.by_inputs = matrix(n, nu);
  d.intermediates = std::make_unique<Subexpressions>("fd");
  return d;
}

// -M^-1 K, -M^-1 D and M^-1 B_u with K at qdd = M^-1 F: M factored once (LDL^T), every column
// solved with the factors. The linearization's intermediates that hold the symbols qdd are
// bound again with the solved qdd in their place; the others are shared as they are.
ForwardDynamicsDerivatives by_mass_matrix(const Variables& variables, const ForwardDynamicsSources& s) {
  const unsigned n = s.mass_matrix.rows(), nu = input_count(variables);
  ForwardDynamicsDerivatives d = empty_derivatives(n, nu);
  Subexpressions& z = *d.intermediates;
  const LdlFactors factors = ldl_factor(s.mass_matrix, z, d.pivots);
  const matrix qdd = ldl_solve(factors, s.forcing, z);
  GiNaC::exmap at;
  for (unsigned j = 0; j < n; ++j) at[variables.coordinates()[j].qdd] = qdd(j, 0);
  for (const Subexpressions::Definition& definition : s.linearization.derivatives.definitions()) {
    const ex value = substitute(definition.value, at);
    if (!value.is_equal(definition.value)) at[definition.symbol] = z.bind(value);
  }
  matrix right(n, 2 * n + nu);
  for (unsigned i = 0; i < n; ++i) {
    for (unsigned k = 0; k < n; ++k) {
      right(i, k) = -substitute(s.linearization.K(i, k), at);
      right(i, n + k) = -s.linearization.D(i, k);
    }
    for (unsigned k = 0; k < nu; ++k) right(i, 2 * n + k) = s.linearization.B_u(i, k);
  }
  const matrix x = ldl_solve(factors, right, z);
  for (unsigned i = 0; i < n; ++i) {
    for (unsigned k = 0; k < n; ++k) d.by_coordinates(i, k) = x(i, k), d.by_rates(i, k) = x(i, n + k);
    for (unsigned k = 0; k < nu; ++k) d.by_inputs(i, k) = x(i, 2 * n + k);
  }
  return d;
}

// the chain rule through the recursion's intermediates: each gets its derivatives by q, qd and
// u as intermediates of its own (those by qd and u structurally zero where it depends on q only)
ForwardDynamicsDerivatives by_recursion(const Variables& variables, const ForwardDynamics& fd,
                                        const std::vector<const Subexpressions*>& intermediates) {
  const unsigned n = fd.accelerations.rows(), nu = input_count(variables);
  ForwardDynamicsDerivatives d = empty_derivatives(n, nu);
  Subexpressions& z = *d.intermediates;
  const ChainRule rule(intermediates, state_and_input_symbols(variables), z);
  for (unsigned i = 0; i < n; ++i) {
    const std::vector<ex> gradient = rule.total(fd.accelerations(i, 0));
    for (unsigned k = 0; k < n; ++k) {
      d.by_coordinates(i, k) = z.bind(gradient[k]);
      d.by_rates(i, k) = z.bind(gradient[n + k]);
    }
    for (unsigned k = 0; k < nu; ++k) d.by_inputs(i, k) = z.bind(gradient[2 * n + k]);
  }
  d.pivots = fd.pivots;
  return d;
}

double estimate(const ForwardDynamicsDerivatives& d, std::vector<const Subexpressions*> intermediates,
                const Variables& variables) {
  GiNaC::exvector entries(d.pivots.begin(), d.pivots.end());
  for (const matrix* m : {&d.by_coordinates, &d.by_rates, &d.by_inputs})
    for (unsigned i = 0; i < m->rows(); ++i)
      for (unsigned j = 0; j < m->cols(); ++j) entries.push_back((*m)(i, j));
  intermediates.push_back(d.intermediates.get());
  return estimated_operations(entries, intermediates, variables);
}

}  // namespace

ForwardDynamicsDerivatives derive_forward_dynamics_derivatives(const Variables& variables,
                                                               const ForwardDynamicsSources& sources) {
  std::vector<const Subexpressions*> intermediates = sources.intermediates;
  intermediates.push_back(&sources.linearization.derivatives);
  ForwardDynamicsDerivatives closed = by_mass_matrix(variables, sources);
  const double closed_operations = estimate(closed, intermediates, variables);
  closed.form = {FunctionForm::closed_form, closed_operations, std::numeric_limits<double>::quiet_NaN()};
  if (!sources.forward_dynamics) return closed;
  ForwardDynamicsDerivatives recursive = by_recursion(variables, *sources.forward_dynamics, sources.intermediates);
  const double recursive_operations = estimate(recursive, sources.intermediates, variables);
  if (!(recursive_operations < closed_operations)) {
    closed.form.estimated_operations_other = recursive_operations;
    return closed;
  }
  recursive.form = {FunctionForm::recursions, recursive_operations, closed_operations};
  return recursive;
}

}  // namespace eomgen
