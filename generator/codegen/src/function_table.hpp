#pragma once
// The function table: which functions a generated model has, what each reads and writes, and
// the value of every entry it writes, as derive_header_functions chose them. Everything here
// is symbolic; function_source.hpp spells it.
#include <string>
#include <utility>
#include <vector>

#include "eomgen/codegen/ir.hpp"
#include "eomgen/codegen/lower.hpp"
#include "eomgen/derivation/header_functions.hpp"

namespace eomgen {

/// The size of an argument a function writes, as constant expressions of the generated Model
/// ("nq", "3", ...).
struct ArgumentShape {
  std::string rows, cols;
};

/// One generated function (a static member of the generated Model).
struct FunctionSpec {
  std::string name;  ///< of the member function, e.g. "mass_matrix"
  std::string doc;   ///< one line of documentation
  /// its inputs, in the order of its arguments
  std::vector<ir::VariableKind> reads;
  /// its outputs, as arguments after the inputs; a single scalar (T, V) is returned instead
  std::vector<ir::Array> writes;
  /// the size of each output, in the order of `writes`
  std::vector<ArgumentShape> shapes;
  /// every entry it writes, structural zeros included, in the order they are computed
  std::vector<LoweringTarget> targets;
  /// entries copied after the body (first = second): the lower triangle of M
  std::vector<std::pair<ir::Target, ir::Target>> mirrors;
  /// returns whether every entry of Array::pivots among the targets (held in a local array) is
  /// positive and every entry it writes finite: forward_dynamics
  bool returns_regularity = false;
  /// inverse_dynamics of a model with constraints: the targets give tau = M qdd - F and Xi (a
  /// local array); the function then splits tau into the constraint forces Xi^T lambda and the
  /// rest, orthogonal to them (the least tau that gives qdd)
  bool splits_constraint_forces = false;
  /// an overload without the first output computes it into a local array: the derivatives of
  /// qdd are taken at qdd, which a caller may want (a step's stages) or not
  bool first_output_optional = false;
};

/// M, F, the constraint terms, T, V, the outputs, then forward_dynamics, inverse_dynamics, the
/// gravity forces and the Coriolis matrix, the output Jacobians, the regressor and
/// linearization_terms and forward_dynamics_derivatives, as `functions` has them.
std::vector<FunctionSpec> function_table(const Model& model, const HeaderFunctions& functions);

/// The name of the Jacobian function of an output, and of its bias.
std::string output_jacobian_name(const Output& output);
std::string output_bias_name(const Output& output);

/// True if the function returns its single scalar output instead of writing arguments.
bool returns_scalar(const FunctionSpec& function);

/// The function as its overload without the first output takes it (first_output_optional).
FunctionSpec without_first_output(const FunctionSpec& function);

}  // namespace eomgen
