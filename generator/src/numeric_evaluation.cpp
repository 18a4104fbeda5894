#include "eomgen/numeric_evaluation.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "eomgen/error.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;
using GiNaC::is_a;

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? ", " : "") + items[i];
  return out;
}

// Evaluates expressions in double precision from the numbers of the model's symbols and of the
// intermediates. Walking the tree in doubles (rather than GiNaC's subs and evalf) is linear in
// the size of the shared graph, and a pole gives inf instead of a GiNaC exception, whose
// unwinding from inside subs leaks the half-built expression.
class Evaluator {
 public:
  void set(const ex& symbol, double value) { values_[symbol] = value; }

  // e as a real number, possibly inf or NaN (an intermediate may be, harmlessly or not)
  double value(const ex& e, const std::string& what) const;

  // e as a finite real number; `what` names the entry in messages
  double finite(const ex& e, const std::string& what) const {
    const double x = value(e, what);
    if (!std::isfinite(x))
      throw Error(fmt::format("evaluating {} at this state: the result is not finite (a division by zero, "
                              "or a root or logarithm of a negative number)", what));
    return x;
  }

 private:
  double function(const ex& e, const std::string& what) const;

  std::map<ex, double, GiNaC::ex_is_less> values_;  // looked up, never iterated
};

double Evaluator::value(const ex& e, const std::string& what) const {
  if (is_a<GiNaC::numeric>(e)) {
    const GiNaC::numeric& n = GiNaC::ex_to<GiNaC::numeric>(e);
    if (!n.is_real()) throw Error(fmt::format("evaluating {}: the expression has a complex number", what));
    return n.to_double();
  }
  if (is_a<GiNaC::symbol>(e)) {
    const auto it = values_.find(e);
    if (it == values_.end())
      throw Error(fmt::format("evaluating {}: it depends on '{}', which has no value here", what,
                              GiNaC::ex_to<GiNaC::symbol>(e).get_name()));
    return it->second;
  }
  if (is_a<GiNaC::add>(e) || is_a<GiNaC::mul>(e)) {
    const bool sum = is_a<GiNaC::add>(e);
    double x = sum ? 0.0 : 1.0;
    for (std::size_t i = 0; i < e.nops(); ++i) x = sum ? x + value(e.op(i), what) : x * value(e.op(i), what);
    return x;
  }
  if (is_a<GiNaC::power>(e)) {
    const double base = value(e.op(0), what);
    if (e.op(1).is_equal(GiNaC::numeric(1, 2))) return std::sqrt(base);
    return std::pow(base, value(e.op(1), what));
  }
  if (is_a<GiNaC::constant>(e)) return GiNaC::ex_to<GiNaC::numeric>(e.evalf()).to_double();
  if (is_a<GiNaC::function>(e)) return function(e, what);
  throw Error(fmt::format("evaluating {}: this kind of expression has no numeric evaluation here", what));
}

double Evaluator::function(const ex& e, const std::string& what) const {
  using unary = double (*)(double);
  static const std::pair<const char*, unary> functions[] = {
      {"sin", std::sin},     {"cos", std::cos},     {"tan", std::tan},     {"asin", std::asin},
      {"acos", std::acos},   {"atan", std::atan},   {"sinh", std::sinh},   {"cosh", std::cosh},
      {"tanh", std::tanh},   {"asinh", std::asinh}, {"acosh", std::acosh}, {"atanh", std::atanh},
      {"exp", std::exp},     {"log", std::log},     {"abs", std::fabs}};
  const std::string name = GiNaC::ex_to<GiNaC::function>(e).get_name();
  if (name == "atan2" && e.nops() == 2) return std::atan2(value(e.op(0), what), value(e.op(1), what));
  for (const auto& [known, f] : functions)
    if (name == known && e.nops() == 1) return f(value(e.op(0), what));
  throw Error(fmt::format("evaluating {}: the function '{}' has no numeric evaluation here", what, name));
}

Eigen::MatrixXd evaluate_matrix(const GiNaC::matrix& m, const Evaluator& eval, const std::string& name) {
  Eigen::MatrixXd out(m.rows(), m.cols());
  for (unsigned i = 0; i < m.rows(); ++i)
    for (unsigned j = 0; j < m.cols(); ++j) out(i, j) = eval.finite(m(i, j), fmt::format("{}[{},{}]", name, i + 1, j + 1));
  return out;
}

Eigen::VectorXd evaluate_column(const GiNaC::matrix& m, const Evaluator& eval, const std::string& name) {
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
      // accelerations are what the equations are solved for, so they cannot be given
      const bool acceleration = v.find(name).has_value();
      throw Error(fmt::format("evaluating at a state: {} '{}'; accepted names: {}",
                              acceleration ? "accelerations are solved for, not given:" : "unknown name", name,
                              join(accepted)));
    }
    out[it->second] = value;
  }
  return out;
}

NumericEquations evaluate_equations(const Model& model, const EquationsOfMotion& eom, const NamedValues& values) {
  Evaluator eval;
  for (const auto& [symbol, value] : numeric_substitution(model, values))
    eval.set(symbol, GiNaC::ex_to<GiNaC::numeric>(value).to_double());
  // each intermediate refers only to earlier ones, so one pass in order gives them all
  for (const auto& d : eom.subexpressions.definitions())
    eval.set(d.symbol, eval.value(d.value, "intermediate " + d.symbol.get_name()));

  NumericEquations out;
  out.mass_matrix = evaluate_matrix(eom.mass_matrix, eval, "M");
  out.forcing = evaluate_column(eom.forcing, eval, "F");
  out.constraint_jacobian = evaluate_matrix(eom.constraint_jacobian, eval, "Xi");
  out.constraint_rate_term = evaluate_column(eom.constraint_rate_term, eval, "Xi_t");
  out.constraint_acceleration_term = evaluate_column(eom.constraint_acceleration_term, eval, "constraint_bias");
  out.holonomic_residuals = evaluate_column(eom.holonomic_residuals, eval, "phi");
  out.kinetic_energy = eval.finite(eom.kinetic_energy, "T");
  out.potential_energy = eval.finite(eom.potential_energy, "V");
  std::size_t k = 0;
  for (const Output& o : model.outputs)
    for (std::size_t i = 0; i < o.components.size(); ++i, ++k) {
      const std::string label = o.labels.size() == o.components.size() ? o.labels[i]
                                : o.components.size() == 1         ? o.name
                                                                   : fmt::format("{}_{}", o.name, i + 1);
      out.outputs.emplace_back(label, eval.finite(output_component(model, eom, k), "output '" + label + "'"));
    }
  return out;
}

AccelerationSolution solve_accelerations(const NumericEquations& eq) {
  const Eigen::Index n = eq.mass_matrix.rows(), m = eq.constraint_jacobian.rows();
  AccelerationSolution out;
  if (m == 0) {
    // M is symmetric positive definite for a proper choice of coordinates; a singular or
    // indefinite M means the coordinates are redundant and need a constraint
    const Eigen::LLT<Eigen::MatrixXd> llt(eq.mass_matrix);
    if (llt.info() != Eigen::Success || llt.rcond() < std::numeric_limits<double>::epsilon())
      throw Error("solving M qdd = F: the mass matrix is not positive definite at this state "
                  "(redundant coordinates need a constraint)");
    out.qdd = llt.solve(eq.forcing);
    out.lambda.resize(0);
    return out;
  }
  // [[M, -Xi^T], [-Xi, 0]] [qdd; lambda] = [F; dXi/dt qd + dXi_t/dt], CONVENTIONS.md (KKT)
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + m, n + m);
  K.topLeftCorner(n, n) = eq.mass_matrix;
  K.topRightCorner(n, m) = -eq.constraint_jacobian.transpose();
  K.bottomLeftCorner(m, n) = -eq.constraint_jacobian;
  Eigen::VectorXd rhs(n + m);
  rhs << eq.forcing, eq.constraint_acceleration_term;
  // full pivoting: M alone may be singular (quaternions) while K is regular
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(K);
  if (!lu.isInvertible())
    throw Error(fmt::format("solving the KKT system [[M, -Xi^T], [-Xi, 0]]: the matrix is singular at this "
                            "state (rank {} of {}): the constraints are dependent, or M is singular on "
                            "the directions they allow",
                            lu.rank(), n + m));
  const Eigen::VectorXd x = lu.solve(rhs);
  out.qdd = x.head(n);
  out.lambda = x.tail(m);
  return out;
}

}  // namespace eomgen
