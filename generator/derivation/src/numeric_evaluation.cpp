#include "eomgen/derivation/numeric_evaluation.hpp"

#include "eomgen/symbolic/double_evaluator.hpp"

#include <fmt/format.h>

#include "eomgen/base/error.hpp"
#include "eomrt/regularity.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;
using GiNaC::is_a;

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? ", " : "") + items[i];
  return out;
}


Eigen::VectorXd evaluate_column(const GiNaC::matrix& m, const DoubleEvaluator& eval, const std::string& name) {
  Eigen::VectorXd out(m.rows());
  for (unsigned i = 0; i < m.rows(); ++i) out(i) = eval.finite(m(i, 0), fmt::format("{}[{}]", name, i + 1));
  return out;
}

}  // namespace

GiNaC::exmap numeric_substitution(const Model& model, const NamedValues& values) {
  const Variables& v = model.system.variables();
  GiNaC::exmap out;
  std::map<std::string, ex> by_name;
  std::vector<std::string> accepted;  // in declaration order, for the error message
  auto accept = [&](const std::string& name, const ex& symbol, double default_value) {
    accepted.push_back(name);
    by_name.emplace(name, symbol);
    out[symbol] = default_value;
  };
  accept("t", v.time(), 0.0);
  for (const Coordinate& c : v.coordinates()) {
    accept(c.name, c.q, 0.0);
    accept(c.qd.get_name(), c.qd, 0.0);
  }
  for (const Input& u : v.inputs()) accept(u.name, u.symbol, 0.0);
  for (const Parameter& p : v.parameters()) accept(p.name, p.symbol, p.default_value);
  for (const auto& [name, value] : values) {
    const auto it = by_name.find(name);
    if (it == by_name.end()) {
      // accelerations are what the equations are solved for, and derived parameters follow the
      // parameters, so neither can be given
      const std::optional<GiNaC::realsymbol> symbol = v.find(name);
      const bool derived = symbol && v.kind_of(*symbol) == SymbolKind::derived_parameter;
      throw Error(fmt::format("evaluating at a state: {} '{}'; accepted names: {}",
                              derived ? "derived parameters are computed from the parameters, not given:"
                              : symbol ? "accelerations are solved for, not given:"
                                       : "unknown name",
                              name, join(accepted)));
    }
    out[it->second] = value;
  }
  // the derived parameters from the parameters just given, in their order
  DoubleEvaluator parameters;
  for (const Parameter& p : v.parameters()) parameters.set(p.symbol, GiNaC::ex_to<GiNaC::numeric>(out.at(p.symbol)).to_double());
  v.evaluate_derived_parameters(parameters);
  for (const DerivedParameter& d : v.derived_parameters())
    out[d.symbol] = parameters.value(d.symbol, "derived parameter '" + d.name + "'");
  return out;
}

Eigen::MatrixXd evaluate_matrix(const GiNaC::matrix& m, const DoubleEvaluator& eval, const std::string& name) {
  Eigen::MatrixXd out(m.rows(), m.cols());
  for (unsigned i = 0; i < m.rows(); ++i)
    for (unsigned j = 0; j < m.cols(); ++j) out(i, j) = eval.finite(m(i, j), fmt::format("{}[{},{}]", name, i + 1, j + 1));
  return out;
}

DoubleEvaluator evaluator_at(const Model& model, const ModelEquations& eom, const NamedValues& values) {
  DoubleEvaluator eval;
  for (const auto& [symbol, value] : numeric_substitution(model, values))
    eval.set(symbol, GiNaC::ex_to<GiNaC::numeric>(value).to_double());
  // each intermediate refers only to earlier ones, so one pass in order gives them all
  for (const auto& d : eom.subexpressions.definitions())
    eval.set(d.symbol, eval.value(d.value, "intermediate " + d.symbol.get_name()));
  return eval;
}

NumericEquations evaluate_equations(const Model& model, const ModelEquations& eom, const NamedValues& values) {
  const DoubleEvaluator eval = evaluator_at(model, eom, values);

  NumericEquations out;
  out.mass_matrix = evaluate_matrix(eom.mass_matrix, eval, "M");
  out.forcing = evaluate_column(eom.forcing, eval, "F");
  out.constraint_jacobian = evaluate_matrix(eom.constraint_jacobian, eval, "Xi");
  out.constraint_rate_term = evaluate_column(eom.constraint_rate_term, eval, "Xi_t");
  out.constraint_acceleration_term = evaluate_column(eom.constraint_acceleration_term, eval, "b");
  out.holonomic_residuals = evaluate_column(eom.holonomic_residuals, eval, "phi");
  out.kinetic_energy = eval.finite(eom.kinetic_energy, "T");
  out.potential_energy = eval.finite(eom.potential_energy, "V");
  std::size_t k = 0;
  for (const Output& o : model.outputs)
    for (std::size_t i = 0; i < o.components.size(); ++i, ++k) {
      const std::string label = o.labels.size() == o.components.size() ? o.labels[i]
                                : o.components.size() == 1         ? o.name
                                                                   : fmt::format("{}_{}", o.name, i + 1);
      out.outputs.emplace_back(label, eval.finite(eom.output_component(k), "output '" + label + "'"));
    }
  return out;
}

eomrt::KktSystem<double> factorize_kkt(const NumericEquations& eq) {
  eomrt::KktSystem<double> kkt;
  if (kkt.compute(eq.mass_matrix, eq.constraint_jacobian) == eomrt::DynamicsStatus::ok) return kkt;
  // the rank, for the message only, counts the pivots above the same threshold
  Eigen::FullPivLU<Eigen::MatrixXd> lu(kkt.matrix());
  lu.setThreshold(eomrt::default_singular_rcond<double>());
  throw Error(fmt::format("solving the KKT system [[M, -Xi^T], [-Xi, 0]]: the matrix is singular at this "
                          "state (rank {} of {}): the constraints are dependent, or M is singular on "
                          "the directions they allow",
                          lu.rank(), kkt.matrix().rows()));
}

AccelerationSolution solve_accelerations(const NumericEquations& eq, const eomrt::KktSystem<double>& kkt) {
  const Eigen::Index n = eq.mass_matrix.rows(), m = eq.constraint_jacobian.rows();
  // [[M, -Xi^T], [-Xi, 0]] [qdd; lambda] = [F; dXi/dt qd + dXi_t/dt], docs/conventions.md (KKT)
  Eigen::VectorXd x(n + m);
  x << eq.forcing, eq.constraint_acceleration_term;
  kkt.solve_in_place(x);
  return {x.head(n), x.tail(m)};
}

AccelerationSolution solve_accelerations(const NumericEquations& eq) {
  if (eq.constraint_jacobian.rows() > 0) return solve_accelerations(eq, factorize_kkt(eq));
  // M is symmetric positive definite for a proper choice of coordinates; a singular or
  // indefinite M means the coordinates are redundant and need a constraint
  const Eigen::LLT<Eigen::MatrixXd> llt(eq.mass_matrix);
  if (!eomrt::cholesky_is_regular(llt, eomrt::default_singular_rcond<double>()))
    throw Error("solving M qdd = F: the mass matrix is not positive definite at this state "
                "(redundant coordinates need a constraint)");
  return {llt.solve(eq.forcing), Eigen::VectorXd(0)};
}

std::string explain_singular_mass_matrix(const Model& model, const ModelEquations& eom, const NamedValues& values,
                                         const Eigen::MatrixXd& mass_matrix) {
  const auto& coordinates = model.system.variables().coordinates();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(mass_matrix);
  if (eigen.info() != Eigen::Success) return "the mass matrix is not a finite symmetric matrix at this state";
  // the direction M does not resist: the coordinates that move along it
  const Eigen::VectorXd null = eigen.eigenvectors().col(0);
  std::string names;
  for (Eigen::Index j = 0; j < null.size(); ++j)
    if (std::abs(null(j)) > 0.1 * null.cwiseAbs().maxCoeff())
      names += (names.empty() ? "" : ", ") + coordinates[static_cast<std::size_t>(j)].name;
  // regular a little away? every coordinate moved at once, by distinct small amounts (a gimbal
  // lock stays locked while only the locked pair moves), at two deterministic states
  bool regular_nearby = false;
  for (const double sign : {1.0, -1.0}) {
    NamedValues moved = values;
    for (std::size_t j = 0; j < coordinates.size(); ++j) {
      const auto it = values.find(coordinates[j].name);
      moved[coordinates[j].name] = (it == values.end() ? 0.0 : it->second) + sign * 0.01 * (1 + 0.37 * static_cast<double>(j));
    }
    try {
      const Eigen::LLT<Eigen::MatrixXd> llt(evaluate_equations(model, eom, moved).mass_matrix);
      regular_nearby = regular_nearby || eomrt::cholesky_is_regular(llt, eomrt::default_singular_rcond<double>());
    } catch (const Error&) {
      // a pole nearby: no evidence either way
    }
  }
  if (regular_nearby)
    return fmt::format("the mass matrix is singular at this state but not near it: a coordinate singularity (as the "
                       "gimbal lock of Euler angles) in {}, which describe fewer independent motions here than "
                       "elsewhere; evaluate away from it, or describe the rotation without one (a quaternion)",
                       names);
  return fmt::format("the mass matrix is singular at this state and near it, along {}: the coordinates are redundant "
                     "(they need a constraint) or a body lacks the mass or inertia to resist that motion",
                     names);
}

NumericControllerFunctions evaluate_controller_functions(const Model& model, const ModelEquations& eom,
                                                         const HeaderFunctions& functions, const NamedValues& values,
                                                         const Eigen::VectorXd& qdd) {
  DoubleEvaluator eval = evaluator_at(model, eom, values);
  const auto& coordinates = model.system.variables().coordinates();
  for (std::size_t k = 0; k < coordinates.size(); ++k) eval.set(coordinates[k].qdd, qdd(static_cast<Eigen::Index>(k)));
  // the intermediates beyond the equations' own, in order (the linearization's are not needed)
  for (const auto& z : functions.owned)
    for (const auto& d : z->definitions()) eval.set(d.symbol, eval.value(d.value, "intermediate " + d.symbol.get_name()));
  if (functions.forward_dynamics)
    for (const auto& d : functions.forward_dynamics->subexpressions.definitions())
      eval.set(d.symbol, eval.value(d.value, "intermediate " + d.symbol.get_name()));
  NumericControllerFunctions out;
  out.inverse_dynamics = evaluate_matrix(functions.inverse_dynamics, eval, "inverse dynamics");
  if (functions.gravity_forces) out.gravity_forces = evaluate_matrix(*functions.gravity_forces, eval, "G");
  if (functions.coriolis_matrix) out.coriolis_matrix = evaluate_matrix(*functions.coriolis_matrix, eval, "C");
  for (const OutputJacobian& jac : functions.output_jacobians) {
    const std::string& name = model.outputs[jac.output].name;
    out.output_jacobians.push_back({name, evaluate_matrix(jac.jacobian, eval, "the Jacobian of " + name),
                                    evaluate_matrix(jac.bias, eval, "the bias of " + name)});
  }
  if (functions.regressor) {
    out.regressor = evaluate_matrix(*functions.regressor, eval, "Y");
    out.inertial_parameters = evaluate_matrix(functions.inertial_parameters, eval, "pi");
  }
  return out;
}

}  // namespace eomgen
