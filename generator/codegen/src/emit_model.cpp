#include "eomgen/codegen/emit_model.hpp"

#include <fmt/format.h>

#include <set>

#include "eomgen/base/error.hpp"
#include "eomgen/codegen/cpp_printer.hpp"
#include "eomgen/derivation/header_functions.hpp"
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

// the function table lowered and printed, then the header
EmittedModel emit(const Model& model, const HeaderFunctions& functions, const EmitOptions& options) {
  const ModelEquations& eom = *functions.equations;
  check_independent_speeds(model, eom);
  CppPrintOptions print;
  print.share_subexpressions = options.share_subexpressions;
  for (const Parameter& p : model.system.variables().parameters()) print.parameter_names.push_back(p.name);
  std::vector<LoweringTarget> derived_parameters;
  for (const DerivedParameter& d : model.system.variables().derived_parameters()) {
    derived_parameters.push_back({{ir::Array::derived_parameters, print.derived_parameter_names.size(), 0}, d.definition});
    print.derived_parameter_names.push_back(d.name);
  }
  const std::vector<FunctionSpec> table = function_table(model, functions);
  EmittedFunctions printed = emit_functions(table, derived_parameters, functions.intermediates(),
                                            bind_variables(model, functions.linearization, print), print);
  if (functions.linearization) printed.source += linearization_source(eom.constraint_count > 0);
  EmittedModel emitted;
  emitted.statistics = std::move(printed.statistics);
  emitted.no_forward_dynamics = functions.no_forward_dynamics;
  if (functions.forward_dynamics) emitted.forward_dynamics_operations = functions.forward_dynamics->estimated_operations;
  emitted.mass_matrix_path_operations = functions.mass_matrix_path_operations;
  emitted.prefers_forward_dynamics = functions.prefers_forward_dynamics;
  emitted.mass_matrix_from_recursions = functions.mass_matrix_form.form == FunctionForm::recursions;
  emitted.estimated_operations_recursions = emitted.mass_matrix_from_recursions
                                                ? functions.mass_matrix_form.estimated_operations
                                                : functions.mass_matrix_form.estimated_operations_other;
  if (const auto& d = functions.forward_dynamics_derivatives) {
    emitted.forward_dynamics_derivatives = d->form;
    emitted.forward_dynamics_derivatives_estimates = d->candidates;
  }
  emitted.no_forward_dynamics_derivatives = functions.no_forward_dynamics_derivatives;
  const std::uint64_t hash = model_fingerprint(model, table, printed.source);
  emitted.header = assemble_header(model, functions, printed.source, hash, options);
  return emitted;
}

}  // namespace

EmittedModel emit_model(const Model& model, const HeaderFunctions& functions, const EmitOptions& options) {
  return emit(model, functions, options);
}

EmittedModel emit_model(const Model& model, const ModelEquations& eom, const EmitOptions& options) {
  return emit(model, derive_header_functions(model, eom), options);
}

EmittedModel emit_model(const Model& model, const ModelEquations& eom, const SymbolicLinearization& linearization,
                        const EmitOptions& options) {
  return emit(model, derive_header_functions(model, eom, &linearization), options);
}

}  // namespace eomgen
