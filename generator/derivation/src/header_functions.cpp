#include "eomgen/derivation/header_functions.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "eomgen/base/error.hpp"
#include "eomgen/derivation/composite_body.hpp"
#include "eomgen/derivation/linearization.hpp"
#include "eomgen/symbolic/graph_calculus.hpp"
#include "base_parameters.hpp"
#include "chain_rule.hpp"
#include "forward_dynamics_derivatives.hpp"
#include "newton_euler.hpp"
#include "operation_estimate.hpp"
#include "symbol_dependence.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;
using GiNaC::matrix;

constexpr double not_derived = std::numeric_limits<double>::quiet_NaN();

// The runtime's Cholesky path after M and F (factorization, pivot-ratio test, solve, finiteness
// test) in operations of generated code. The peer benchmark (docs/performance.md) measured it at
// 60 ns for n = 2, 130 for 4, 280 to 480 for 8, 810 for 16 and 3,600 for 32: the per-entry work
// of Eigen's LLT, not its n^3/6 multiply-adds, dominates at these sizes; generated straight-line
// code runs at about 0.25 ns per operation.
double cholesky_path_operations(double n) { return 120 + 14 * n * n; }

// The closed form's estimate of the resolution it was derived in (KinematicsResolution)
double closed_form_estimate(const EquationsOfMotion& eom) {
  switch (eom.resolution) {
    case KinematicsResolution::inertial: return eom.estimated_operations_inertial;
    case KinematicsResolution::local: return eom.estimated_operations_local;
  }
  EOMGEN_UNREACHABLE("a KinematicsResolution without an estimate");
}

Subexpressions& own(HeaderFunctions& h, const char* prefix) {
  h.owned.push_back(std::make_unique<Subexpressions>(prefix));
  return *h.owned.back();
}

GiNaC::exvector entries(const matrix& m) {
  GiNaC::exvector out;
  for (unsigned i = 0; i < m.rows(); ++i)
    for (unsigned j = 0; j < m.cols(); ++j) out.push_back(m(i, j));
  return out;
}

class Derivation {
 public:
  Derivation(const Model& model, const ModelEquations& eom, HeaderFunctions& h)
      : model_(model), eom_(eom), vars_(model.system.variables()), n_(unsigned(vars_.coordinate_count())), h_(h),
        recursions_(own(h, "c")) {}

  void run(const HeaderOptions& options) {
    dynamics();
    forward_dynamics();
    forward_dynamics_derivatives(options.forward_dynamics_derivatives_form);
    h_.controller_functions = options.controller_functions;
    if (!options.controller_functions) return;
    inverse_dynamics();
    Subexpressions& first = own(h_, "d");
    std::vector<ex> coordinates, rates;
    for (const Coordinate& c : vars_.coordinates()) coordinates.push_back(c.q), rates.push_back(c.qd);
    const ChainRule by_coordinates({&eom_.subexpressions, &recursions_}, coordinates, first);
    const ChainRule by_rates({&eom_.subexpressions, &recursions_}, rates, first);
    coriolis_and_gravity(by_coordinates, first);
    output_jacobians(by_coordinates, by_rates, first);
    output_biases(first);
    regressor();
  }

 private:
  double estimate(const GiNaC::exvector& e) const {
    return estimated_operations(e, {&eom_.subexpressions, &recursions_}, vars_);
  }

  // M and F: the closed form, or the recursions where they are estimated to take fewer operations
  void dynamics() {
    h_.mass_matrix = eom_.mass_matrix;
    h_.forcing = eom_.forcing;
    switch (eom_.dynamics) {
      case DynamicsForm::recursions:  // derive_equations took them already
        h_.mass_matrix_form = {FunctionForm::recursions, eom_.estimated_operations_recursions, closed_form_estimate(eom_)};
        return;
      case DynamicsForm::closed_form: break;
    }
    const double closed = closed_form_estimate(eom_);
    h_.mass_matrix_form = {FunctionForm::closed_form, closed, not_derived};
    auto terms = derive_composite_body_terms(model_.system, recursions_);
    const auto* recursive = std::get_if<RecursiveMassMatrixAndForcing>(&terms);
    if (!recursive) return;
    const double estimate = estimated_operations(recursive->mass_matrix, recursive->forcing, recursions_, vars_);
    h_.mass_matrix_form.estimated_operations_other = estimate;
    if (!(estimate < closed)) return;
    h_.mass_matrix = recursive->mass_matrix;
    h_.forcing = recursive->forcing;
    h_.mass_matrix_form = {FunctionForm::recursions, estimate, closed};
  }

  void forward_dynamics() {
    std::variant<ForwardDynamics, std::string> derived = derive_forward_dynamics(model_.system);
    if (auto* reason = std::get_if<std::string>(&derived)) {
      h_.no_forward_dynamics = *reason;
      return;
    }
    h_.forward_dynamics = std::move(std::get<ForwardDynamics>(derived));
    h_.mass_matrix_path_operations = h_.mass_matrix_form.estimated_operations + cholesky_path_operations(n_);
    h_.prefers_forward_dynamics = h_.forward_dynamics->estimated_operations < h_.mass_matrix_path_operations;
  }

  // dqdd/d[q, qd, u] where the header has the linearization's terms to take them from
  void forward_dynamics_derivatives(std::optional<ForwardDynamicsDerivatives::Form> form) {
    if (!h_.linearization) return;
    if (eom_.constraint_count > 0) {
      h_.no_forward_dynamics_derivatives =
          "the model has constraints: the header solves the KKT system for them at each call (kkt_derivatives)";
      return;
    }
    std::vector<const Subexpressions*> sets{&eom_.subexpressions, &recursions_};
    const ForwardDynamics* fd = h_.forward_dynamics ? &*h_.forward_dynamics : nullptr;
    if (fd) sets.push_back(&fd->subexpressions);
    try {
      auto derived = derive_forward_dynamics_derivatives(
          model_.system, {h_.mass_matrix, h_.forcing, sets, *h_.linearization, fd}, form);
      if (auto* reason = std::get_if<std::string>(&derived))
        h_.no_forward_dynamics_derivatives = *reason;
      else
        h_.forward_dynamics_derivatives = std::move(std::get<ForwardDynamicsDerivatives>(derived));
    } catch (const DerivationError& e) {
      h_.no_forward_dynamics_derivatives = e.what();
    }
  }

  // M qdd - F from M and F, or by Newton-Euler on the tree of the bodies: the smaller estimate
  void inverse_dynamics() {
    matrix tau(n_, 1);
    for (unsigned i = 0; i < n_; ++i) {
      ex sum = -h_.forcing(i, 0);
      for (unsigned j = 0; j < n_; ++j) sum += h_.mass_matrix(i, j) * vars_.coordinates()[j].qdd;
      tau(i, 0) = sum;
    }
    h_.inverse_dynamics = tau;
    h_.inverse_dynamics_form = {FunctionForm::closed_form, estimate(entries(tau)), not_derived};
    auto recursive = derive_newton_euler_torques(model_.system, recursions_);
    const matrix* torques = std::get_if<matrix>(&recursive);
    if (!torques) return;
    const double estimated = estimate(entries(*torques));
    FormChoice& choice = h_.inverse_dynamics_form;
    choice.estimated_operations_other = estimated;
    if (!(estimated < choice.estimated_operations)) return;
    h_.inverse_dynamics = *torques;
    choice = {FunctionForm::recursions, estimated, choice.estimated_operations};
  }

  // g = dV/dq and C_kj = sum_i 1/2 (dM_kj/dq_i + dM_ki/dq_j - dM_ij/dq_k) qd_i, where M and V do
  // not depend on t (with a prescribed motion dM/dt has a part of its own). The Christoffel
  // symbols are n^3: beyond coriolis_matrix_limit coordinates (a chain of 32 would take 126,000
  // operations and seven seconds to emit) the header has neither.
  void coriolis_and_gravity(const ChainRule& rule, Subexpressions& out) {
    if (n_ > coriolis_matrix_limit) {
      h_.no_coriolis_and_gravity = fmt::format("C of the Christoffel symbols grows like n^3: not derived beyond {} "
                                               "coordinates", coriolis_matrix_limit);
      return;
    }
    const SymbolDependence dependence({&eom_.subexpressions, &recursions_}, vars_);
    const auto moves = [&](const ex& e) {
      return dependence.depends_on(e, SymbolKind::time) || dependence.depends_on(e, SymbolKind::rate) ||
             dependence.depends_on(e, SymbolKind::input);
    };
    for (const ex& e : entries(h_.mass_matrix))
      if (moves(e)) {
        h_.no_coriolis_and_gravity = "M depends on t: C of the Christoffel symbols leaves out dM/dt";
        return;
      }
    if (moves(eom_.potential_energy)) {
      h_.no_coriolis_and_gravity = "V depends on t or on the rates";
      return;
    }
    try {
      const std::vector<ex> dV = rule.total(eom_.potential_energy);
      matrix g(n_, 1);
      for (unsigned k = 0; k < n_; ++k) g(k, 0) = out.bind(dV[k]);
      // dM[i][j][k] = dM_ij/dq_k, i <= j
      std::vector<std::vector<std::vector<ex>>> dM(n_, std::vector<std::vector<ex>>(n_));
      for (unsigned i = 0; i < n_; ++i)
        for (unsigned j = i; j < n_; ++j) {
          std::vector<ex> gradient = rule.total(h_.mass_matrix(i, j));
          for (ex& d : gradient) d = out.bind(d);
          dM[i][j] = dM[j][i] = std::move(gradient);
        }
      matrix C(n_, n_);
      for (unsigned k = 0; k < n_; ++k)
        for (unsigned j = 0; j < n_; ++j) {
          // a flat sum of products of bound derivatives: a product of a sum would leave GiNaC's
          // extraction of its content (whose sign follows its term order) to the lowering
          GiNaC::exvector terms;
          for (unsigned i = 0; i < n_; ++i) {
            const ex& qd = vars_.coordinates()[i].qd;
            for (const ex& d : {dM[k][j][i], dM[k][i][j]}) terms.push_back(d * qd / 2);
            terms.push_back(-dM[i][j][k] * qd / 2);
          }
          C(k, j) = out.bind(GiNaC::add(terms));
        }
      h_.gravity_forces = g;
      h_.coriolis_matrix = C;
    } catch (const DerivationError& e) {
      h_.no_coriolis_and_gravity = e.what();
    }
  }

  // The Jacobians of the outputs that are positions (dy/dq) or velocities linear in the rates
  // (dy/dqd); their biases follow (output_biases)
  void output_jacobians(const ChainRule& by_coordinates, const ChainRule& by_rates, Subexpressions& out) {
    const SymbolDependence dependence({&eom_.subexpressions, &recursions_}, vars_);
    std::size_t first = 0;
    for (std::size_t o = 0; o < model_.outputs.size(); first += model_.outputs[o].components.size(), ++o) {
      const std::size_t size = model_.outputs[o].components.size();
      bool coordinates = false, speeds = false, other = false;
      for (std::size_t k = first; k < first + size; ++k) {
        const ex& y = eom_.outputs()[k];
        coordinates = coordinates || dependence.depends_on(y, SymbolKind::coordinate);
        speeds = speeds || dependence.depends_on(y, SymbolKind::rate);
        other = other || dependence.depends_on(y, SymbolKind::input) || dependence.depends_on(y, SymbolKind::acceleration);
      }
      if (other || (!coordinates && !speeds)) continue;
      OutputJacobian jac;
      jac.output = o;
      jac.first_component = first;
      jac.level = speeds ? OutputJacobian::Level::velocity : OutputJacobian::Level::position;
      jac.jacobian = matrix(unsigned(size), n_);
      jac.bias = matrix(unsigned(size), 1);
      try {
        for (std::size_t k = 0; k < size; ++k) {
          const std::vector<ex> d = (speeds ? by_rates : by_coordinates).total(eom_.outputs()[first + k]);
          for (unsigned j = 0; j < n_; ++j) jac.jacobian(unsigned(k), j) = out.bind(d[j]);
        }
      } catch (const DerivationError&) {
        continue;  // an output of a function without a derivative has no Jacobian
      }
      if (speeds && !linear_in_rates(jac.jacobian, out)) continue;
      h_.output_jacobians.push_back(jac);
    }
  }

  // a velocity output's Jacobian is free of the rates, or the output is not linear in them
  bool linear_in_rates(const matrix& J, const Subexpressions& out) const {
    const SymbolDependence dependence({&eom_.subexpressions, &recursions_, &out}, vars_);
    for (const ex& e : entries(J))
      if (dependence.depends_on(e, SymbolKind::rate)) return false;
    return true;
  }

  // the rates at qdd = 0: q -> qd, qd -> 0, t -> 1
  GiNaC::exmap rates_at_zero_acceleration() const {
    GiNaC::exmap rates{{vars_.time(), 1}};
    for (const Coordinate& c : vars_.coordinates()) rates[c.q] = c.qd;
    return rates;
  }

  // the bias of every output Jacobian, as derivatives along the motion at qdd = 0 (forward mode:
  // the graph once, not once per coordinate): yd for a velocity output, ydd, the derivative of
  // yd, for a position output
  void output_biases(Subexpressions& first) {
    if (h_.output_jacobians.empty()) return;
    DirectionalRule once({&eom_.subexpressions, &recursions_}, rates_at_zero_acceleration(), first);
    try {
      std::vector<ex> outputs;
      for (const OutputJacobian& jac : h_.output_jacobians)
        for (unsigned k = 0; k < jac.bias.rows(); ++k) outputs.push_back(eom_.outputs()[jac.first_component + k]);
      const std::vector<ex> rates = once(outputs);
      std::vector<ex> position_rates;
      std::size_t next = 0;
      for (OutputJacobian& jac : h_.output_jacobians)
        for (unsigned k = 0; k < jac.bias.rows(); ++k) {
          const ex d = first.bind(rates[next++]);
          switch (jac.level) {
            case OutputJacobian::Level::velocity: jac.bias(k, 0) = d; break;
            case OutputJacobian::Level::position: position_rates.push_back(d); break;
          }
        }
      if (position_rates.empty()) return;
      Subexpressions& second = own(h_, "e");
      DirectionalRule twice({&eom_.subexpressions, &recursions_, &first}, rates_at_zero_acceleration(), second);
      const std::vector<ex> accelerations = twice(position_rates);
      next = 0;
      for (OutputJacobian& jac : h_.output_jacobians)
        if (jac.level == OutputJacobian::Level::position)
          for (unsigned k = 0; k < jac.bias.rows(); ++k) jac.bias(k, 0) = second.bind(accelerations[next++]);
    } catch (const DerivationError& e) {
      // a Jacobian whose derivative does not exist (abs, sign) has no bias: the output loses both
      h_.output_jacobians.clear();
      h_.no_output_jacobians = e.what();
    }
  }

  void regressor() {
    auto derived = derive_regressor(model_.system, recursions_);
    if (auto* reason = std::get_if<std::string>(&derived)) {
      h_.no_regressor = *reason;
      return;
    }
    RegressorTerms& terms = std::get<RegressorTerms>(derived);
    h_.regressor = terms.Y;
    h_.inertial_parameters = terms.parameters;
    h_.inertial_parameter_names = std::move(terms.names);
    h_.inertial_parameter_origins = std::move(terms.origins);
  }

  const Model& model_;
  const ModelEquations& eom_;
  const Variables& vars_;
  const unsigned n_;
  HeaderFunctions& h_;
  Subexpressions& recursions_;
};

}  // namespace

const char* to_string(FunctionForm form) {
  switch (form) {
    case FunctionForm::closed_form: return "closed form";
    case FunctionForm::recursions: return "recursions";
  }
  EOMGEN_UNREACHABLE("a FunctionForm value that is not an enumerator");
}

const char* to_string(ForwardDynamicsDerivatives::Form form) {
  switch (form) {
    case ForwardDynamicsDerivatives::Form::chain_rule_through_recursion: return "chain rule through the recursion";
    case ForwardDynamicsDerivatives::Form::mass_matrix_and_linearization: return "M^-1 of the linearization's K, D, B_u";
    case ForwardDynamicsDerivatives::Form::mass_matrix_and_newton_euler:
      return "M^-1 of K, D, B_u through Newton-Euler";
  }
  EOMGEN_UNREACHABLE("a ForwardDynamicsDerivatives::Form value that is not an enumerator");
}

std::vector<const Subexpressions*> HeaderFunctions::intermediates() const {
  std::vector<const Subexpressions*> all{&equations->subexpressions};
  if (linearization) all.push_back(&linearization->derivatives);
  if (forward_dynamics) all.push_back(&forward_dynamics->subexpressions);
  for (const auto& z : owned) all.push_back(z.get());
  if (forward_dynamics_derivatives)
    for (const auto& z : forward_dynamics_derivatives->intermediates) all.push_back(z.get());
  return all;
}

ModelEquations with_function_intermediates(const ModelEquations& equations, const HeaderFunctions& functions,
                                           GiNaC::exmap& renamed) {
  ModelEquations merged = equations;
  for (const auto& z : functions.owned)
    for (const Subexpressions::Definition& d : z->definitions())
      renamed[d.symbol] = merged.subexpressions.adopt(substitute(d.value, renamed));
  return merged;
}

HeaderFunctions derive_header_functions(const Model& model, const ModelEquations& equations,
                                        const SymbolicLinearization* linearization, const HeaderOptions& options) {
  HeaderFunctions h;
  h.equations = &equations;
  h.linearization = linearization;
  Derivation(model, equations, h).run(options);
  if (options.controller_functions && options.base_regressor) h.base_parameters = find_base_parameters(model, equations, h);
  return h;
}

}  // namespace eomgen
