#include "eomgen/codegen/emit_model.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <optional>
#include <set>

#include "eomgen/base/error.hpp"
#include "eomgen/codegen/cpp_printer.hpp"
#include "eomgen/derivation/articulated_body.hpp"
#include "eomgen/derivation/composite_body.hpp"
#include "eomgen/derivation/linearization.hpp"
#include "function_source.hpp"
#include "function_table.hpp"
#include "header_assembly.hpp"
#include "linearization_source.hpp"
#include "variable_binding.hpp"

namespace eomgen {
namespace {

// a Model assembled through the API skips the parser's checks of the `independent` statement
void check_independent_speeds(const Model& model, const ModelEquations& eom) {
  const std::vector<std::size_t>& independent = model.independent_speeds;
  if (independent.empty()) return;
  const std::size_t n = model.system.variables().coordinate_count(), m = eom.constraint_count;
  if (independent.size() + m != n)
    throw EmitError(fmt::format("emitting '{}': expected nq - nc = {} independent speeds, got {}", model.name,
                                static_cast<long>(n) - static_cast<long>(m), independent.size()));
  std::set<std::size_t> seen;
  for (std::size_t i = 0; i < independent.size(); ++i)
    if (independent[i] >= n || !seen.insert(independent[i]).second)
      throw EmitError(fmt::format("emitting '{}': independent speed {} is coordinate index {}: expected distinct "
                                  "indices below nq = {}", model.name, i, independent[i], n));
}

// operations per call of the named function (0 when the table has none)
double operations_of(const std::vector<FunctionStatistics>& statistics, const std::string& name) {
  for (const FunctionStatistics& s : statistics)
    if (s.function == name) return double(s.optimized.total());
  return 0;
}

// The runtime's Cholesky path after M and F (factorization, pivot-ratio test, solve, finiteness
// test) in operations of generated code. The peer benchmark (docs/performance.md) measured it at
// 60 ns for n = 2, 130 for 4, 280 to 480 for 8, 810 for 16 and 3,600 for 32: the per-entry work
// of Eigen's LLT, not its n^3/6 multiply-adds, dominates at these sizes; generated straight-line
// code runs at about 0.25 ns per operation.
double cholesky_path_operations(double n) { return 120 + 14 * n * n; }

// Forward dynamics two ways: the articulated-body recursion, or M and F with the runtime's
// Cholesky path. The recursion wins almost everywhere; a closed-form M and F much smaller than
// it (a model of one or two bodies) can still take the other.
void compare_forward_dynamics(EmittedModel& emitted, std::size_t n) {
  emitted.forward_dynamics_operations = operations_of(emitted.statistics, "forward_dynamics");
  emitted.mass_matrix_path_operations =
      operations_of(emitted.statistics, "mass_matrix_and_forcing") + cholesky_path_operations(double(n));
  emitted.prefers_forward_dynamics = emitted.forward_dynamics_operations < emitted.mass_matrix_path_operations;
}

// The closed form's estimate of the resolution it was derived in (KinematicsResolution)
double closed_form_estimate(const EquationsOfMotion& eom) {
  switch (eom.resolution) {
    case KinematicsResolution::inertial: return eom.estimated_operations_inertial;
    case KinematicsResolution::local: return eom.estimated_operations_local;
  }
  EOMGEN_UNREACHABLE("a KinematicsResolution without an estimate");
}

// The recursive M and F where the model has them and they are estimated to take fewer
// operations than the closed form; records the choice in `emitted`.
const CompositeBodyEquations* recursions_if_smaller(const std::variant<CompositeBodyEquations, std::string>& derived,
                                                    const EquationsOfMotion& eom, EmittedModel& emitted) {
  const CompositeBodyEquations* recursive = std::get_if<CompositeBodyEquations>(&derived);
  emitted.estimated_operations_recursions =
      recursive ? recursive->estimated_operations : std::numeric_limits<double>::quiet_NaN();
  emitted.mass_matrix_from_recursions = recursive && recursive->estimated_operations < closed_form_estimate(eom);
  return emitted.mass_matrix_from_recursions ? recursive : nullptr;
}

// the function table lowered and printed, then the generic linearization() and the header
EmittedModel emit(const Model& model, const ModelEquations& eom, const SymbolicLinearization* linearization,
                  const EmitOptions& options) {
  check_independent_speeds(model, eom);
  CppPrintOptions print;
  print.share_subexpressions = options.share_subexpressions;
  for (const Parameter& p : model.system.variables().parameters()) print.parameter_names.push_back(p.name);
  std::vector<LoweringTarget> derived_parameters;
  for (const DerivedParameter& d : model.system.variables().derived_parameters()) {
    derived_parameters.push_back({{ir::Array::derived_parameters, print.derived_parameter_names.size(), 0}, d.definition});
    print.derived_parameter_names.push_back(d.name);
  }
  EmittedModel emitted;
  const std::variant<ForwardDynamics, std::string> derived = derive_forward_dynamics(model.system);
  std::optional<std::variant<CompositeBodyEquations, std::string>> recursions;
  const CompositeBodyEquations* recursive = nullptr;
  switch (eom.dynamics) {
    case DynamicsForm::recursions:  // M and F are the recursions' already
      emitted.estimated_operations_recursions = eom.estimated_operations_recursions;
      emitted.mass_matrix_from_recursions = true;
      break;
    case DynamicsForm::closed_form:
      recursions = derive_composite_body_equations(model.system);
      recursive = recursions_if_smaller(*recursions, eom, emitted);
      break;
  }
  FunctionTableParts parts{linearization, std::get_if<ForwardDynamics>(&derived), recursive};
  const ForwardDynamics* forward = parts.forward_dynamics;
  const std::vector<FunctionSpec> table = function_table(eom, parts);
  std::vector<const Subexpressions*> intermediates{&eom.subexpressions};
  if (linearization) intermediates.push_back(&linearization->derivatives);
  if (forward) intermediates.push_back(&forward->subexpressions);
  if (parts.recursive_mass_matrix) intermediates.push_back(&parts.recursive_mass_matrix->subexpressions);
  EmittedFunctions functions =
      emit_functions(table, derived_parameters, intermediates, bind_variables(model, linearization, print), print);
  if (linearization) functions.source += linearization_source(eom.constraint_count > 0);
  const std::uint64_t hash = model_fingerprint(model, table, functions.source);
  emitted.statistics = std::move(functions.statistics);
  if (forward)
    compare_forward_dynamics(emitted, eom.coordinate_count);
  else
    emitted.no_forward_dynamics = std::get<std::string>(derived);
  emitted.header = assemble_header(model, eom, functions.source, hash, linearization != nullptr,
                                   ForwardDynamicsChoice{forward != nullptr, emitted.prefers_forward_dynamics}, options);
  return emitted;
}

}  // namespace

EmittedModel emit_model(const Model& model, const ModelEquations& eom, const EmitOptions& options) {
  return emit(model, eom, nullptr, options);
}

EmittedModel emit_model(const Model& model, const ModelEquations& eom, const SymbolicLinearization& linearization,
                        const EmitOptions& options) {
  return emit(model, eom, &linearization, options);
}

}  // namespace eomgen
