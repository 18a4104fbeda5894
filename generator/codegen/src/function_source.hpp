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
  std::string source;                         ///< every function, in the table's order
  std::vector<FunctionStatistics> statistics;  ///< one per function
};

/// Lowers the functions jointly (a subexpression shared by M and F is one node for
/// mass_matrix, forcing and mass_matrix_and_forcing alike) and prints each.
/// \throws EmitError for a symbol missing from `variables` or a function with no C++ form.
EmittedFunctions emit_functions(const std::vector<FunctionSpec>& table,
                                const std::vector<const Subexpressions*>& intermediates,
                                const VariableNames& variables, const CppPrintOptions& print);

/// One function: documentation, signature, using-declarations, the program's statements, zeros
/// for the entries it does not compute (structural zeros) and the mirrored entries.
std::string function_source(const FunctionSpec& function, const ir::Program& program, const CppPrintOptions& print);

}  // namespace eomgen
