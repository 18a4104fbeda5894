#pragma once
// Assembles one self-contained C++ header (Eigen only) from a model and its derived equations.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "eomgen/codegen/cpp_identifier.hpp"  // the spelling of the model's names in the header
#include "eomgen/codegen/ir.hpp"
#include "eomgen/derivation/equations_of_motion.hpp"
#include "eomgen/derivation/header_functions.hpp"
#include "eomgen/derivation/model_equations.hpp"

namespace eomgen {

struct SymbolicLinearization;  // eomgen/derivation/linearization.hpp

struct EmitOptions {
  std::string outer_namespace = "eomgen_models";
  std::string source_name;  // file name shown in the banner (sanitized)
  /// false: print every output as its own tree, without shared temporaries (for comparison)
  bool share_subexpressions = true;
};

/// Operation counts of one generated function.
struct FunctionStatistics {
  std::string function;
  ir::OperationCounts unoptimized;  // every output as its own tree, no sharing
  ir::OperationCounts optimized;    // the emitted straight-line code
};

/// The name of the statistics of the Constants: the operations done once per parameter set.
inline constexpr const char* constants_statistics_name = "Constants (per parameter set)";

struct EmittedModel {
  std::string header;
  /// the Constants first (constants_statistics_name), then each function's operations per call
  std::vector<FunctionStatistics> statistics;
  /// why the header has no forward_dynamics() (constraints, not a tree), empty if it has one
  std::string no_forward_dynamics;
  /// With forward_dynamics(): its estimated operations per call, those of M and F together with
  /// the runtime's Cholesky path instead (its measured cost as operations: 120 + 14 n^2), and
  /// whether the header tells the runtime to prefer it (prefers_forward_dynamics: it takes
  /// fewer); derive_header_functions chose, this reports it.
  double forward_dynamics_operations = 0, mass_matrix_path_operations = 0;
  bool prefers_forward_dynamics = false;
  /// Where the emitted M and F come from: Kane's closed form of the equations, or the
  /// composite-rigid-body M and Newton-Euler F (composite_body.hpp), whichever has fewer
  /// estimated operations; the estimate of the recursions is NaN for a model that has none
  /// (then `no_forward_dynamics` says why).
  bool mass_matrix_from_recursions = false;
  double estimated_operations_recursions = 0;
  /// With forward_dynamics_derivatives(): the form emitted, and every form derived with its
  /// estimated operations; empty otherwise, and `no_forward_dynamics_derivatives` says why
  /// where a linearization was asked for.
  std::optional<ForwardDynamicsDerivatives::Form> forward_dynamics_derivatives;
  std::vector<std::pair<ForwardDynamicsDerivatives::Form, double>> forward_dynamics_derivatives_estimates;
  std::string no_forward_dynamics_derivatives;
};

/// The header of a model: its metadata and every function of `functions`, lowered and printed;
/// which functions and in which form is derive_header_functions' choice, not this one's.
/// \throws EmitError if an expression cannot be printed, or if model.independent_speeds is neither
///         empty nor nq - nc distinct coordinate indices.
EmittedModel emit_model(const Model& model, const HeaderFunctions& functions, const EmitOptions& options = {});

/// emit_model of derive_header_functions(model, equations): the header's functions derived, then printed.
EmittedModel emit_model(const Model& model, const ModelEquations& equations, const EmitOptions& options = {});

/// The same header with linearization_terms() besides: A and B about any operating point, from
/// exact derivatives (for gain scheduling). `linearization` is linearize_symbolic(model, equations).
/// \throws EmitError as the overload without a linearization.
EmittedModel emit_model(const Model& model, const ModelEquations& equations,
                        const SymbolicLinearization& linearization, const EmitOptions& options = {});

}  // namespace eomgen
