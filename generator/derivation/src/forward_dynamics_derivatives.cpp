#include "forward_dynamics_derivatives.hpp"

#include <fmt/format.h>

#include <memory>
#include <optional>
#include <utility>
#include <variant>

#include "eomgen/symbolic/graph_calculus.hpp"
#include "chain_rule.hpp"
#include "ldl_factor.hpp"
#include "newton_euler.hpp"
#include "operation_estimate.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;
using GiNaC::matrix;
using Form = ForwardDynamicsDerivatives::Form;

std::vector<ex> state_and_input_symbols(const Variables& variables) {
  std::vector<ex> symbols;
  for (const Coordinate& c : variables.coordinates()) symbols.push_back(c.q);
  for (const Coordinate& c : variables.coordinates()) symbols.push_back(c.qd);
  for (const Input& u : variables.inputs()) symbols.push_back(u.symbol);
  return symbols;
}

// One form's derivatives as it is derived: its sets of intermediates, and M's factors where it
// solves with them.
class Candidate {
 public:
  Candidate(Form form, const Variables& variables) : variables_(variables), n_(unsigned(variables.coordinate_count())) {
    d_.form = form;
    d_.accelerations = matrix(n_, 1);
    d_.by_coordinates = matrix(n_, n_);
    d_.by_rates = matrix(n_, n_);
    d_.by_inputs = matrix(n_, unsigned(variables.inputs().size()));
  }
  // moved, never copied: it owns its sets of intermediates
  Candidate(const Candidate&) = delete;
  Candidate(Candidate&&) = default;

  /// A new set of intermediates, after those made before it.
  Subexpressions& next_set() {
    d_.intermediates.push_back(std::make_unique<Subexpressions>("fd"));
    return *d_.intermediates.back();
  }

  /// M factored (its pivots kept) and qdd = M^-1 F, in a set of their own.
  void factor_mass_matrix(const ForwardDynamicsSources& s) {
    Subexpressions& z = next_set();
    factors_ = ldl_factor(s.mass_matrix, z, d_.pivots);
    d_.accelerations = ldl_solve(factors_, s.forcing, z);
  }

  /// qdd -> M^-1 F, for the expressions that hold the symbols qdd
  GiNaC::exmap accelerations_at_the_solution() const {
    GiNaC::exmap at;
    for (unsigned j = 0; j < n_; ++j) at[variables_.coordinates()[j].qdd] = d_.accelerations(j, 0);
    return at;
  }

  /// -M^-1 K, -M^-1 D and M^-1 B_u, every column with the factors, bound in `z`
  void solve(const matrix& K, const matrix& D, const matrix& B_u, Subexpressions& z) {
    const unsigned nu = B_u.cols();
    matrix right(n_, 2 * n_ + nu);
    for (unsigned i = 0; i < n_; ++i) {
      for (unsigned k = 0; k < n_; ++k) right(i, k) = -K(i, k), right(i, n_ + k) = -D(i, k);
      for (unsigned k = 0; k < nu; ++k) right(i, 2 * n_ + k) = B_u(i, k);
    }
    const matrix x = ldl_solve(factors_, right, z);
    for (unsigned i = 0; i < n_; ++i) {
      for (unsigned k = 0; k < n_; ++k) d_.by_coordinates(i, k) = x(i, k), d_.by_rates(i, k) = x(i, n_ + k);
      for (unsigned k = 0; k < nu; ++k) d_.by_inputs(i, k) = x(i, 2 * n_ + k);
    }
  }

  ForwardDynamicsDerivatives& derivatives() { return d_; }

  /// The operations of every entry, pivot and acceleration, the intermediates of `sources` and
  /// of its own sets counted once each.
  double estimate(std::vector<const Subexpressions*> sources) const {
    GiNaC::exvector entries(d_.pivots.begin(), d_.pivots.end());
    for (const matrix* m : {&d_.accelerations, &d_.by_coordinates, &d_.by_rates, &d_.by_inputs})
      for (unsigned i = 0; i < m->rows(); ++i)
        for (unsigned j = 0; j < m->cols(); ++j) entries.push_back((*m)(i, j));
    for (const auto& z : d_.intermediates) sources.push_back(z.get());
    return estimated_operations(entries, sources, variables_);
  }

 private:
  const Variables& variables_;
  const unsigned n_;
  ForwardDynamicsDerivatives d_;
  LdlFactors factors_;
};

// Every definition of `source` that holds a key of `at` (directly or through an earlier one)
// bound again in `z` with the values of `at` in its place; `at` maps each to its new symbol.
void rebind_at(const Subexpressions& source, GiNaC::exmap& at, Subexpressions& z) {
  for (const Subexpressions::Definition& definition : source.definitions()) {
    const ex value = substitute(definition.value, at);
    if (!value.is_equal(definition.value)) at[definition.symbol] = z.bind(value);
  }
}

// K, D, B_u of the linearization, whose intermediates hold the symbols qdd: those that do are
// bound again at qdd = M^-1 F, the others shared as they are
Candidate by_linearization(const Variables& variables, const ForwardDynamicsSources& s) {
  Candidate c(Form::mass_matrix_and_linearization, variables);
  c.factor_mass_matrix(s);
  Subexpressions& z = c.next_set();
  GiNaC::exmap at = c.accelerations_at_the_solution();
  rebind_at(s.linearization.derivatives, at, z);
  const unsigned n = s.mass_matrix.rows();
  matrix K(n, n);
  for (unsigned i = 0; i < n; ++i)
    for (unsigned k = 0; k < n; ++k) K(i, k) = substitute(s.linearization.K(i, k), at);
  c.solve(K, s.linearization.D, s.linearization.B_u, z);
  return c;
}

// K, D, B_u by the chain rule through the Newton-Euler recursion of M qdd - F, its accelerations
// M^-1 F (constants to the chain rule: it takes the partial derivatives at fixed qdd); nullopt
// where the bodies form no tree
std::optional<Candidate> by_newton_euler(const MechanicalSystem& system, const ForwardDynamicsSources& s) {
  const Variables& variables = system.variables();
  Candidate c(Form::mass_matrix_and_newton_euler, variables);
  Subexpressions& recursion = c.next_set();
  const auto torques = derive_newton_euler_torques(system, recursion);
  const matrix* tau = std::get_if<matrix>(&torques);
  if (!tau) return std::nullopt;
  c.factor_mass_matrix(s);
  Subexpressions& at_solution = c.next_set();
  GiNaC::exmap at = c.accelerations_at_the_solution();
  rebind_at(recursion, at, at_solution);
  Subexpressions& z = c.next_set();
  const ChainRule rule({&recursion, &at_solution}, state_and_input_symbols(variables), z);
  const unsigned n = tau->rows(), nu = unsigned(variables.inputs().size());
  matrix K(n, n), D(n, n), B_u(n, nu);
  for (unsigned i = 0; i < n; ++i) {
    const std::vector<ex> gradient = rule.total(substitute((*tau)(i, 0), at));
    for (unsigned k = 0; k < n; ++k) K(i, k) = z.bind(gradient[k]), D(i, k) = z.bind(gradient[n + k]);
    for (unsigned k = 0; k < nu; ++k) B_u(i, k) = z.bind(-gradient[2 * n + k]);
  }
  c.solve(K, D, B_u, z);
  return c;
}

// the chain rule through the recursion's intermediates: each gets its derivatives by q, qd and
// u as intermediates of its own (those by qd and u structurally zero where it depends on q only)
Candidate by_recursion(const Variables& variables, const ForwardDynamics& fd,
                       const std::vector<const Subexpressions*>& sources) {
  Candidate c(Form::chain_rule_through_recursion, variables);
  Subexpressions& z = c.next_set();
  const ChainRule rule(sources, state_and_input_symbols(variables), z);
  ForwardDynamicsDerivatives& d = c.derivatives();
  const unsigned n = fd.accelerations.rows(), nu = d.by_inputs.cols();
  for (unsigned i = 0; i < n; ++i) {
    const std::vector<ex> gradient = rule.total(fd.accelerations(i, 0));
    for (unsigned k = 0; k < n; ++k) d.by_coordinates(i, k) = z.bind(gradient[k]), d.by_rates(i, k) = z.bind(gradient[n + k]);
    for (unsigned k = 0; k < nu; ++k) d.by_inputs(i, k) = z.bind(gradient[2 * n + k]);
  }
  d.pivots = fd.pivots;
  d.accelerations = fd.accelerations;
  return c;
}

}  // namespace

std::variant<ForwardDynamicsDerivatives, std::string> derive_forward_dynamics_derivatives(
    const MechanicalSystem& system, const ForwardDynamicsSources& sources, std::optional<Form> only) {
  const Variables& variables = system.variables();
  std::vector<const Subexpressions*> all = sources.intermediates;
  all.push_back(&sources.linearization.derivatives);
  const auto wanted = [&](Form form) { return !only || *only == form; };
  std::vector<Candidate> candidates;
  if (sources.forward_dynamics && wanted(Form::chain_rule_through_recursion))
    candidates.push_back(by_recursion(variables, *sources.forward_dynamics, sources.intermediates));
  if (wanted(Form::mass_matrix_and_linearization)) candidates.push_back(by_linearization(variables, sources));
  if (wanted(Form::mass_matrix_and_newton_euler))
    if (std::optional<Candidate> c = by_newton_euler(system, sources)) candidates.push_back(std::move(*c));
  if (candidates.empty())
    return fmt::format("the model admits no {}: it has no recursive forward dynamics or its bodies form no tree",
                       to_string(*only));
  std::vector<std::pair<Form, double>> estimates;
  std::size_t best = 0;
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    estimates.emplace_back(candidates[k].derivatives().form, candidates[k].estimate(all));
    if (estimates[k].second < estimates[best].second) best = k;
  }
  ForwardDynamicsDerivatives chosen = std::move(candidates[best].derivatives());
  chosen.estimated_operations = estimates[best].second;
  chosen.candidates = std::move(estimates);
  return chosen;
}

}  // namespace eomgen
