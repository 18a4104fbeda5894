#include "linearization_program.hpp"

#include <fmt/format.h>

#include <cmath>

#include "eomgen/base/error.hpp"
#include "eomgen/mechanics/variables.hpp"

namespace eomgen {

using GiNaC::ex;
using GiNaC::ex_to;

std::shared_ptr<const LinearizationProgram> compile_program(const Model& model, const ModelEquations& eom,
                                                            const SymbolicLinearization& lin) {
  const Variables& vars = model.system.variables();
  std::vector<ex> inputs{vars.time()};
  for (const Coordinate& c : vars.coordinates()) inputs.push_back(c.q), inputs.push_back(c.qd);
  for (const Input& u : vars.inputs()) inputs.push_back(u.symbol);
  for (const Parameter& p : vars.parameters()) inputs.push_back(p.symbol);
  for (const Coordinate& c : vars.coordinates()) inputs.push_back(c.qdd);
  for (const auto& l : lin.lambda) inputs.push_back(l);
  auto program = std::make_shared<LinearizationProgram>(std::move(inputs));
  ExpressionTape& tape = program->tape;
  // the derived parameters first, each from the parameters and those before it
  for (const DerivedParameter& d : vars.derived_parameters())
    tape.define(d.symbol, d.definition, "derived parameter " + d.name);
  for (const auto& d : eom.subexpressions.definitions()) tape.define(d.symbol, d.value, "intermediate " + d.symbol.get_name());
  for (const auto& d : lin.derivatives.definitions()) tape.define(d.symbol, d.value, "derivative " + d.symbol.get_name());
  const auto matrix = [&](const GiNaC::matrix& m, const std::string& name) {
    LinearizationProgram::Matrix out{m.rows(), m.cols(), {}, name};
    for (unsigned i = 0; i < m.rows(); ++i)
      for (unsigned j = 0; j < m.cols(); ++j)
        out.registers.push_back(tape.compile(m(i, j), fmt::format("{}[{},{}]", name, i + 1, j + 1)));
    return out;
  };
  program->M = matrix(eom.mass_matrix, "M");
  program->F = matrix(eom.forcing, "F");
  program->Xi = matrix(eom.constraint_jacobian, "Xi");
  program->Xi_t = matrix(eom.constraint_rate_term, "Xi_t");
  program->b = matrix(eom.constraint_acceleration_term, "b");
  program->phi = matrix(eom.holonomic_residuals, "phi");
  program->K = matrix(lin.K, "K");
  program->D = matrix(lin.D, "D");
  program->B_u = matrix(lin.B_u, "B_u");
  program->S_q = matrix(lin.S_q, "S_q");
  program->S_qd = matrix(lin.S_qd, "S_qd");
  program->C_q = matrix(lin.C_q, "C_q");
  return program;
}

PointEvaluation::PointEvaluation(const Model& model, const LinearizationProgram& program, const NamedValues& point)
    : program_(program) {
  const GiNaC::exmap values = numeric_substitution(model, point);  // checks the names
  for (const ex& s : program.inputs) {
    const auto it = values.find(s);
    inputs_.push_back(it == values.end() ? 0.0 : ex_to<GiNaC::numeric>(it->second).to_double());
  }
  program_.tape.evaluate(inputs_, registers_);
}

void PointEvaluation::set_accelerations(const Eigen::VectorXd& qdd, const Eigen::VectorXd& lambda) {
  const std::size_t first = inputs_.size() - static_cast<std::size_t>(qdd.size() + lambda.size());
  for (Eigen::Index j = 0; j < qdd.size(); ++j) inputs_[first + static_cast<std::size_t>(j)] = qdd(j);
  for (Eigen::Index r = 0; r < lambda.size(); ++r) inputs_[first + static_cast<std::size_t>(qdd.size() + r)] = lambda(r);
  program_.tape.evaluate(inputs_, registers_);
}

Eigen::MatrixXd PointEvaluation::matrix(const LinearizationProgram::Matrix& m) const {
  Eigen::MatrixXd out(m.rows, m.cols);
  for (Eigen::Index i = 0; i < m.rows; ++i)
    for (Eigen::Index j = 0; j < m.cols; ++j) {
      const double x = registers_[m.registers[static_cast<std::size_t>(i * m.cols + j)]];
      if (!std::isfinite(x))
        throw Error(fmt::format("evaluating {}[{},{}] at this state: the result is not finite (a division by zero, "
                                "or a root or logarithm of a negative number)",
                                m.name, i + 1, j + 1));
      out(i, j) = x;
    }
  return out;
}

NumericEquations PointEvaluation::equations() const {
  NumericEquations e;
  e.mass_matrix = matrix(program_.M);
  e.forcing = matrix(program_.F);
  e.constraint_jacobian = matrix(program_.Xi);
  e.constraint_rate_term = matrix(program_.Xi_t);
  e.constraint_acceleration_term = matrix(program_.b);
  e.holonomic_residuals = matrix(program_.phi);
  return e;
}

eomrt::LinearizationTerms<double> PointEvaluation::terms() const {
  eomrt::LinearizationTerms<double> t;
  t.K = matrix(program_.K);
  t.D = matrix(program_.D);
  t.B_u = matrix(program_.B_u);
  t.S_q = matrix(program_.S_q);
  t.S_qd = matrix(program_.S_qd);
  return t;
}

}  // namespace eomgen
