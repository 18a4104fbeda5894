#include "function_table.hpp"

#include "eomgen/base/error.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "eomgen/codegen/cpp_identifier.hpp"
#include "eomgen/derivation/linearization.hpp"

namespace eomgen {
namespace {

using ir::Array;
using ir::VariableKind;

const std::vector<VariableKind> positions = {VariableKind::time, VariableKind::coordinate, VariableKind::parameter};
const std::vector<VariableKind> states = {VariableKind::time, VariableKind::coordinate, VariableKind::rate,
                                          VariableKind::parameter};
const std::vector<VariableKind> states_and_inputs = {VariableKind::time, VariableKind::coordinate, VariableKind::rate,
                                                     VariableKind::input, VariableKind::parameter};

void add_matrix(FunctionSpec& f, Array array, const GiNaC::matrix& a) {
  for (unsigned i = 0; i < a.rows(); ++i)
    for (unsigned j = 0; j < a.cols(); ++j) f.targets.push_back({{array, i, j}, a(i, j)});
}

void add_vector(FunctionSpec& f, Array array, const GiNaC::matrix& v) {
  for (unsigned i = 0; i < v.rows(); ++i) f.targets.push_back({{array, i, 0}, v(i, 0)});
}

// M is symmetric: its upper triangle is computed, the lower one copied
void add_mass_matrix(FunctionSpec& f, const GiNaC::matrix& mass_matrix) {
  const unsigned n = mass_matrix.rows();
  for (unsigned i = 0; i < n; ++i)
    for (unsigned j = i; j < n; ++j) f.targets.push_back({{Array::mass_matrix, i, j}, mass_matrix(i, j)});
  for (unsigned i = 0; i < n; ++i)
    for (unsigned j = i + 1; j < n; ++j) f.mirrors.push_back({{Array::mass_matrix, j, i}, {Array::mass_matrix, i, j}});
}

// the size of an output argument of a fixed size
ArgumentShape shape_of(Array array) {
  switch (array) {
    case Array::mass_matrix:
    case Array::stiffness:
    case Array::damping:
    case Array::coriolis_matrix:
    case Array::acceleration_by_coordinates:
    case Array::acceleration_by_rates:
      return {"nq", "nq"};
    case Array::forcing:
    case Array::accelerations:
    case Array::generalized_forces:
    case Array::gravity_forces:
      return {"nq", "1"};
    case Array::constraint_jacobian:
    case Array::acceleration_constraint_by_q:
    case Array::acceleration_constraint_by_qd:
      return {"nc", "nq"};
    case Array::constraint_rate_term:
    case Array::constraint_acceleration_term:
    case Array::multipliers:
      return {"nc", "1"};
    case Array::holonomic_residuals: return {"nh", "1"};
    case Array::outputs: return {"ny", "1"};
    case Array::input_matrix:
    case Array::acceleration_by_inputs:
      return {"nq", "nu"};
    case Array::regressor: return {"nq", "npi"};
    case Array::inertial_parameters: return {"npi", "1"};
    case Array::kinetic_energy:
    case Array::potential_energy:
      return {"1", "1"};
    case Array::output_jacobian:
    case Array::output_bias:
      EOMGEN_UNREACHABLE("an output's Jacobian has the size of its output, given by the table");
    case Array::pivots:
    case Array::constants:
    case Array::derived_parameters:
      EOMGEN_UNREACHABLE("a local array or a member of the Constants, never an argument");
  }
  EOMGEN_UNREACHABLE("an ir::Array value that is not an enumerator");
}

FunctionSpec function(std::string name, std::string doc, std::vector<VariableKind> reads, std::vector<Array> writes) {
  FunctionSpec f{std::move(name), std::move(doc), std::move(reads), std::move(writes), {}, {}, {}};
  for (Array a : f.writes) f.shapes.push_back(shape_of(a));
  return f;
}

// the mass matrix and the forcing, alone and together (one pass over their shared terms)
void add_dynamics(std::vector<FunctionSpec>& table, const GiNaC::matrix& mass_matrix, const GiNaC::matrix& forcing) {
  FunctionSpec mass = function("mass_matrix", "M(q, t), symmetric positive (semi)definite", positions,
                               {Array::mass_matrix});
  add_mass_matrix(mass, mass_matrix);
  FunctionSpec f = function("forcing", "F(q, qd, t, u): everything of Lagrange's equations except M qdd",
                                  states_and_inputs, {Array::forcing});
  add_vector(f, Array::forcing, forcing);
  FunctionSpec both = function("mass_matrix_and_forcing", "M and F together, sharing their common subexpressions",
                               states_and_inputs, {Array::mass_matrix, Array::forcing});
  add_mass_matrix(both, mass_matrix);
  add_vector(both, Array::forcing, forcing);
  table.insert(table.end(), {mass, f, both});
}

// Xi, Xi_t, b and phi of the constraints (empty arrays without constraints)
void add_constraints(std::vector<FunctionSpec>& table, const ModelEquations& eom) {
  FunctionSpec jacobian = function("constraint_jacobian", "Xi(q, t) of the Pfaffian constraints Xi qd + Xi_t = 0",
                                   positions, {Array::constraint_jacobian});
  add_matrix(jacobian, Array::constraint_jacobian, eom.constraint_jacobian);
  FunctionSpec rate = function("constraint_rate_term", "Xi_t(q, t)", positions, {Array::constraint_rate_term});
  add_vector(rate, Array::constraint_rate_term, eom.constraint_rate_term);
  FunctionSpec acceleration = function("constraint_acceleration_term", "dXi/dt qd + dXi_t/dt, so that Xi qdd + b = 0",
                                       states, {Array::constraint_acceleration_term});
  add_vector(acceleration, Array::constraint_acceleration_term, eom.constraint_acceleration_term);
  FunctionSpec residuals = function("holonomic_residuals", "phi(q, t) of the holonomic constraints", positions,
                                    {Array::holonomic_residuals});
  add_vector(residuals, Array::holonomic_residuals, eom.holonomic_residuals);
  table.insert(table.end(), {jacobian, rate, acceleration, residuals});
}

// T, V and the model's outputs
void add_energies_and_outputs(std::vector<FunctionSpec>& table, const ModelEquations& eom) {
  FunctionSpec kinetic = function("kinetic_energy", "T(q, qd, t)", states, {Array::kinetic_energy});
  kinetic.targets.push_back({{Array::kinetic_energy, 0, 0}, eom.kinetic_energy});
  FunctionSpec potential = function("potential_energy", "V(q, t)", positions, {Array::potential_energy});
  potential.targets.push_back({{Array::potential_energy, 0, 0}, eom.potential_energy});
  FunctionSpec outputs = function("outputs", "the model's named outputs, in the order of output_names",
                                  states_and_inputs, {Array::outputs});
  for (std::size_t k = 0; k < eom.outputs().size(); ++k)
    outputs.targets.push_back({{Array::outputs, k, 0}, eom.outputs()[k]});
  table.insert(table.end(), {kinetic, potential, outputs});
}

// qdd without M, for a tree without constraints; the pivots come first, as they are computed
FunctionSpec forward_dynamics(const ForwardDynamics& fd) {
  const char* how = nullptr;
  switch (fd.form) {
    case ForwardDynamics::Form::articulated_body: how = "by the articulated-body algorithm"; break;
    case ForwardDynamics::Form::mass_matrix: how = "by the composite-body M and F and M's LDL^T factors"; break;
  }
  FunctionSpec f = function("forward_dynamics",
                            fmt::format("qdd of M qdd = F {}; false if M is not positive definite (a pivot is not "
                                        "positive) or qdd is not finite", how),
                            states_and_inputs, {Array::accelerations});
  for (std::size_t k = 0; k < fd.pivots.size(); ++k) f.targets.push_back({{Array::pivots, k, 0}, fd.pivots[k]});
  add_vector(f, Array::accelerations, fd.accelerations);
  f.returns_regularity = true;
  return f;
}

// the model-specific terms of the generated linearization() (linearization_source.hpp)
FunctionSpec linearization_terms(const SymbolicLinearization& linearization, bool constrained) {
  FunctionSpec f = function("linearization_terms",
                            constrained ? "K = dR/dq, D = dR/dqd, B_u = dF/du of R = M qdd - F - Xi^T lambda, and S_q, "
                                          "S_qd of S = Xi qdd + b, at the given qdd and lambda"
                                        : "K = dR/dq, D = dR/dqd, B_u = dF/du of R = M qdd - F, at the given qdd",
                            states_and_inputs, {Array::stiffness, Array::damping, Array::input_matrix});
  f.reads.push_back(VariableKind::acceleration);
  add_matrix(f, Array::stiffness, linearization.K);
  add_matrix(f, Array::damping, linearization.D);
  add_matrix(f, Array::input_matrix, linearization.B_u);
  if (constrained) {
    f.reads.push_back(VariableKind::multiplier);
    f.writes.insert(f.writes.end(), {Array::acceleration_constraint_by_q, Array::acceleration_constraint_by_qd});
    f.shapes.insert(f.shapes.end(), {shape_of(Array::acceleration_constraint_by_q), shape_of(Array::acceleration_constraint_by_qd)});
    add_matrix(f, Array::acceleration_constraint_by_q, linearization.S_q);
    add_matrix(f, Array::acceleration_constraint_by_qd, linearization.S_qd);
  }
  return f;
}

// qdd, dqdd/dq, dqdd/dqd and dqdd/du (qdd optional: an overload leaves it out), the pivots first,
// as forward_dynamics has them
FunctionSpec forward_dynamics_derivatives(const ForwardDynamicsDerivatives& d) {
  const char* how = nullptr;
  switch (d.form) {
    case ForwardDynamicsDerivatives::Form::chain_rule_through_recursion:
      how = "by the chain rule through the recursive forward dynamics";
      break;
    case ForwardDynamicsDerivatives::Form::mass_matrix_and_linearization:
      how = "as -M^-1 dR/dq, -M^-1 dR/dqd, M^-1 dF/du of R = M qdd - F at qdd = M^-1 F";
      break;
    case ForwardDynamicsDerivatives::Form::mass_matrix_and_newton_euler:
      how = "as -M^-1 dR/dq, -M^-1 dR/dqd, M^-1 dF/du of R = M qdd - F at qdd = M^-1 F, R by Newton-Euler";
      break;
  }
  FunctionSpec f = function("forward_dynamics_derivatives",
                            fmt::format("dqdd/dq, dqdd/dqd and dqdd/du of the forward dynamics qdd = M^-1 F, {}; false "
                                        "if M is not positive definite (a pivot is not positive) or an entry is not "
                                        "finite", how),
                            states_and_inputs,
                            {Array::accelerations, Array::acceleration_by_coordinates, Array::acceleration_by_rates,
                             Array::acceleration_by_inputs});
  for (std::size_t k = 0; k < d.pivots.size(); ++k) f.targets.push_back({{Array::pivots, k, 0}, d.pivots[k]});
  add_vector(f, Array::accelerations, d.accelerations);
  add_matrix(f, Array::acceleration_by_coordinates, d.by_coordinates);
  add_matrix(f, Array::acceleration_by_rates, d.by_rates);
  add_matrix(f, Array::acceleration_by_inputs, d.by_inputs);
  f.returns_regularity = true;
  f.first_output_optional = true;
  return f;
}

const std::vector<VariableKind> with_accelerations = {VariableKind::time,         VariableKind::coordinate,
                                                      VariableKind::rate,         VariableKind::acceleration,
                                                      VariableKind::input,        VariableKind::parameter};

// tau = M qdd - F; with constraints also Xi, to split tau (FunctionSpec::splits_constraint_forces)
FunctionSpec inverse_dynamics(const HeaderFunctions& h) {
  const bool constrained = h.equations->constraint_count > 0;
  const char* how = nullptr;
  switch (h.inverse_dynamics_form.form) {
    case FunctionForm::closed_form: how = "from M and F"; break;
    case FunctionForm::recursions: how = "by the Newton-Euler recursion"; break;
  }
  FunctionSpec f = function(
      "inverse_dynamics",
      constrained ? fmt::format("tau and lambda with M qdd = F + Xi^T lambda + tau for a qdd that satisfies the "
                                "constraints, tau the least (orthogonal to every row of Xi); M qdd - F {}", how)
                  : fmt::format("tau = M qdd - F: the generalized forces to add to produce qdd, {}", how),
      with_accelerations, {Array::generalized_forces});
  add_vector(f, Array::generalized_forces, h.inverse_dynamics);
  if (constrained) {
    f.writes.push_back(Array::multipliers);
    f.shapes.push_back({"nc", "1"});
    add_matrix(f, Array::constraint_jacobian, h.equations->constraint_jacobian);
    f.splits_constraint_forces = true;
  }
  return f;
}

// g = dV/dq and C of the Christoffel symbols
void add_coriolis_and_gravity(std::vector<FunctionSpec>& table, const HeaderFunctions& h) {
  if (!h.gravity_forces || !h.coriolis_matrix) return;
  FunctionSpec g = function("gravity_forces", "G(q) = dV/dq: the generalized forces of gravity and springs, "
                            "with C qd + G = -F at zero input and no other loads",
                            {VariableKind::coordinate, VariableKind::parameter}, {Array::gravity_forces});
  add_vector(g, Array::gravity_forces, *h.gravity_forces);
  FunctionSpec C = function("coriolis_matrix", "C(q, qd) from the Christoffel symbols of M: dM/dt - 2 C is "
                            "skew-symmetric",
                            {VariableKind::coordinate, VariableKind::rate, VariableKind::parameter},
                            {Array::coriolis_matrix});
  add_matrix(C, Array::coriolis_matrix, *h.coriolis_matrix);
  table.insert(table.end(), {g, C});
}

// J and Jdot qd of every output that is a position or a velocity
void add_output_jacobians(std::vector<FunctionSpec>& table, const Model& model, const HeaderFunctions& h) {
  for (const OutputJacobian& jac : h.output_jacobians) {
    const Output& output = model.outputs[jac.output];
    const std::string rows = std::to_string(output.components.size());
    bool velocity = false;
    switch (jac.level) {
      case OutputJacobian::Level::position: velocity = false; break;
      case OutputJacobian::Level::velocity: velocity = true; break;
    }
    FunctionSpec J = function(output_jacobian_name(output),
                              fmt::format("J = {} of the output {}", velocity ? "dy/dqd" : "dy/dq",
                                          cpp_comment_text(output.name)),
                              positions, {});
    J.writes.push_back(Array::output_jacobian);
    J.shapes.push_back({rows, "nq"});
    add_matrix(J, Array::output_jacobian, jac.jacobian);
    FunctionSpec b = function(output_bias_name(output),
                              fmt::format("Jdot qd of the output {}: its {} at qdd = 0",
                                          cpp_comment_text(output.name), velocity ? "rate" : "acceleration"),
                              states, {});
    b.writes.push_back(Array::output_bias);
    b.shapes.push_back({rows, "1"});
    add_vector(b, Array::output_bias, jac.bias);
    table.insert(table.end(), {J, b});
  }
}

void add_regressor(std::vector<FunctionSpec>& table, const HeaderFunctions& h) {
  if (!h.regressor) return;
  const BaseParameters* base = h.base_parameters ? &*h.base_parameters : nullptr;
  FunctionSpec Y = function("regressor",
                            base ? "Y with M qdd - F = Y pi + (the loads other than gravity, negated), pi the "
                                   "identifiable base parameters (inertial_parameter_names)"
                                 : "Y with M qdd - F = Y pi + (the loads other than gravity, negated), pi the "
                                   "inertial parameters (inertial_parameter_names)",
                            {VariableKind::time, VariableKind::coordinate, VariableKind::rate,
                             VariableKind::acceleration, VariableKind::parameter},
                            {Array::regressor});
  FunctionSpec pi = function("inertial_parameters",
                             base ? "pi of the model's parameters: each base parameter's combination of the bodies' "
                                    "m, m c and inertia about their origins"
                                  : "pi of the model's parameters: every body's m, m c and inertia about its "
                                    "origin, in its frame",
                             {VariableKind::parameter}, {Array::inertial_parameters});
  if (!base) {
    add_matrix(Y, Array::regressor, *h.regressor);
    add_vector(pi, Array::inertial_parameters, h.inertial_parameters);
  } else {
    // the kept columns of Y; each base parameter its column's own plus its combination's
    for (unsigned i = 0; i < h.regressor->rows(); ++i)
      for (std::size_t k = 0; k < base->independent.size(); ++k)
        Y.targets.push_back({{Array::regressor, i, k}, (*h.regressor)(i, static_cast<unsigned>(base->independent[k]))});
    for (std::size_t k = 0; k < base->independent.size(); ++k) {
      GiNaC::ex value = 0;
      for (Eigen::Index j = 0; j < base->combination.cols(); ++j)
        if (const double c = base->combination(static_cast<Eigen::Index>(k), j); c != 0)
          value += GiNaC::numeric(c) * h.inertial_parameters(static_cast<unsigned>(j), 0);
      pi.targets.push_back({{Array::inertial_parameters, k, 0}, value});
    }
  }
  table.insert(table.end(), {Y, pi});
}

}  // namespace

std::string output_jacobian_name(const Output& output) { return "output_jacobian_" + cpp_identifier(output.name); }
std::string output_bias_name(const Output& output) { return "output_bias_" + cpp_identifier(output.name); }

std::vector<FunctionSpec> function_table(const Model& model, const HeaderFunctions& h) {
  const ModelEquations& eom = *h.equations;
  std::vector<FunctionSpec> table;
  add_dynamics(table, h.mass_matrix, h.forcing);
  add_constraints(table, eom);
  add_energies_and_outputs(table, eom);
  if (h.forward_dynamics) table.push_back(forward_dynamics(*h.forward_dynamics));
  if (h.controller_functions) table.push_back(inverse_dynamics(h));
  add_coriolis_and_gravity(table, h);
  add_output_jacobians(table, model, h);
  add_regressor(table, h);
  if (h.linearization) table.push_back(linearization_terms(*h.linearization, eom.constraint_count > 0));
  if (h.forward_dynamics_derivatives) table.push_back(forward_dynamics_derivatives(*h.forward_dynamics_derivatives));
  return table;
}

bool returns_scalar(const FunctionSpec& function) {
  return function.writes.size() == 1 && ir::rank(function.writes.front()) == 0;
}

FunctionSpec without_first_output(const FunctionSpec& function) {
  EOMGEN_DEMAND(function.first_output_optional && function.writes.size() > 1,
                "only a function whose first output is optional has an overload without it");
  FunctionSpec f = function;
  const Array dropped = f.writes.front();
  f.writes.erase(f.writes.begin());
  f.shapes.erase(f.shapes.begin());
  f.targets.erase(std::remove_if(f.targets.begin(), f.targets.end(),
                                 [&](const LoweringTarget& t) { return t.target.array == dropped; }),
                  f.targets.end());
  f.first_output_optional = false;
  return f;
}

}  // namespace eomgen
