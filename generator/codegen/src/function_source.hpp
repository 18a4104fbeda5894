#pragma once
// The generated functions as C++: lowering of the whole function table at once, then each
// function printed as a static member template of the generated Model.
#include <string>
#include <vector>

#include "eomgen/codegen/cpp_printer.hpp"
#include "eomgen/codegen/emit_model.hpp"
#include "eomgen/codegen/ir.hpp"
#include "function_table.hpp"

namespace eomgen {

struct EmittedFunctions {
  std::string source;  ///< the Constants class, then every function in the table's order
  /// the Constants first (named constants_statistics_name), then one per function: its per-call part
  std::vector<FunctionStatistics> statistics;
};

/// Lowers the functions jointly (a subexpression shared by M and F is one node for
/// mass_matrix, forcing and mass_matrix_and_forcing alike), takes their parameter-only values
/// out into the Constants (split_constants; not with print.share_subexpressions off, the
/// baseline) and prints the Constants class and each function. `derived_parameters` holds the
/// definition of each derived parameter (Target{Array::derived_parameters, k, 0}), in order;
/// the Constants compute them first.
/// \throws EmitError for a symbol missing from `variables` or a function with no C++ form.
EmittedFunctions emit_functions(const std::vector<FunctionSpec>& table,
                                const std::vector<LoweringTarget>& derived_parameters,
                                const std::vector<const Subexpressions*>& intermediates,
                                const VariableNames& variables, const CppPrintOptions& print);

/// One function: the overload taking the Constants (documentation, signature, using-declarations,
/// the per-call program's statements, zeros for the entries it does not compute (structural
/// zeros) and the mirrored entries), then the overload taking the Parameters, which builds the
/// Constants and calls it. The first is the first definition of the name in the header, the one
/// a text-based operation counter (bench/peers/count_ops.py) reads.
std::string function_source(const FunctionSpec& function, const ir::Program& program, const CppPrintOptions& print);

/// The generated Constants class: a copy of the parameters, the derived parameters computed by
/// `derived_parameters` (each definition as written, reading those before it) and the constants
/// computed by `constants` (outputs Target{Array::constants, k, 0}, members k0, k1, ...).
std::string constants_source(const ir::Program& derived_parameters, const ir::Program& constants,
                             const CppPrintOptions& print);

}  // namespace eomgen
