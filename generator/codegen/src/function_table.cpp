#include "function_table.hpp"

#include <fmt/format.h>

#include "eomgen/derivation/articulated_body.hpp"
#include "eomgen/derivation/composite_body.hpp"
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

FunctionSpec function(std::string name, std::string doc, std::vector<VariableKind> reads, std::vector<Array> writes) {
  return FunctionSpec{std::move(name), std::move(doc), std::move(reads), std::move(writes), {}, {}};
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
    add_matrix(f, Array::acceleration_constraint_by_q, linearization.S_q);
    add_matrix(f, Array::acceleration_constraint_by_qd, linearization.S_qd);
  }
  return f;
}

}  // namespace

std::vector<FunctionSpec> function_table(const ModelEquations& eom, const FunctionTableParts& parts) {
  std::vector<FunctionSpec> table;
  if (const CompositeBodyEquations* recursive = parts.recursive_mass_matrix)
    add_dynamics(table, recursive->mass_matrix, recursive->forcing);
  else
    add_dynamics(table, eom.mass_matrix, eom.forcing);
  add_constraints(table, eom);
  add_energies_and_outputs(table, eom);
  if (parts.forward_dynamics) table.push_back(forward_dynamics(*parts.forward_dynamics));
  if (parts.linearization) table.push_back(linearization_terms(*parts.linearization, eom.constraint_count > 0));
  return table;
}

bool returns_scalar(const FunctionSpec& function) {
  return function.writes.size() == 1 && ir::rank(function.writes.front()) == 0;
}

}  // namespace eomgen
