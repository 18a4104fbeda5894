#pragma once
// Assembles one self-contained C++ header (Eigen only) from a model and its derived equations.
#include <string>
#include <vector>

#include "eomgen/derivation/equations_of_motion.hpp"
#include "eomgen/codegen/cpp_identifier.hpp"  // the spelling of the model's names in the header
#include "eomgen/codegen/ir.hpp"
#include "eomgen/derivation/model_equations.hpp"

namespace eomgen {

struct EmitOptions {
  std::string outer_namespace = "eomgen_models";
  std::string source_name;  // file name shown in the banner (sanitized)
  /// false: print every output as its own tree, without shared temporaries (for comparison)
  bool share_subexpressions = true;
  /// also emit linearization_terms() and linearization(): A and B about any operating point,
  /// from exact derivatives (for gain scheduling)
  bool linearization = false;
};

/// Operation counts of one generated function.
struct FunctionStatistics {
  std::string function;
  ir::OperationCounts unoptimized;  // every output as its own tree, no sharing
  ir::OperationCounts optimized;    // the emitted straight-line code
};

struct EmittedModel {
  std::string header;
  std::vector<FunctionStatistics> statistics;
};

/// \throws EmitError if an expression cannot be printed, or if model.independent_speeds is neither
///         empty nor nq - nc distinct coordinate indices.
EmittedModel emit_model(const Model& model, const ModelEquations& equations, const EmitOptions& options = {});

}  // namespace eomgen
