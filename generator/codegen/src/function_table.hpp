#pragma once
// The function table: which functions a generated model has, what each reads and writes, and
// the value of every entry it writes. Everything here is symbolic; function_source.hpp spells it.
#include <string>
#include <utility>
#include <vector>

#include "eomgen/codegen/ir.hpp"
#include "eomgen/codegen/lower.hpp"
#include "eomgen/derivation/model_equations.hpp"

namespace eomgen {

struct SymbolicLinearization;
struct ForwardDynamics;
struct CompositeBodyEquations;

/// One generated function (a static member of the generated Model).
struct FunctionSpec {
  std::string name;  ///< of the member function, e.g. "mass_matrix"
  std::string doc;   ///< one line of documentation
  /// its inputs, as arguments, sorted in the order of VariableKind (t, q and p always)
  std::vector<ir::VariableKind> reads;
  /// its outputs, as arguments after the inputs; a single scalar (T, V) is returned instead
  std::vector<ir::Array> writes;
  /// every entry it writes, structural zeros included, in the order they are computed
  std::vector<LoweringTarget> targets;
  /// entries copied after the body (first = second): the lower triangle of M
  std::vector<std::pair<ir::Target, ir::Target>> mirrors;
  /// returns whether every entry of Array::pivots among the targets (held in a local array) is
  /// positive and every entry it writes finite: forward_dynamics
  bool returns_regularity = false;
};

/// Optional parts of a model's function table, each derived from the same model.
struct FunctionTableParts {
  /// linearize_symbolic of the same model and equations: adds linearization_terms
  const SymbolicLinearization* linearization = nullptr;
  /// derive_forward_dynamics: adds forward_dynamics
  const ForwardDynamics* forward_dynamics = nullptr;
  /// derive_composite_body_equations: M and F from it instead of from the equations
  const CompositeBodyEquations* recursive_mass_matrix = nullptr;
};

/// The functions of every model, then forward_dynamics, then linearization_terms, as `parts` has them.
std::vector<FunctionSpec> function_table(const ModelEquations& equations, const FunctionTableParts& parts = {});

/// True if the function returns its single scalar output instead of writing arguments.
bool returns_scalar(const FunctionSpec& function);

}  // namespace eomgen
