#pragma once
// Prints a straight-line program as C++ statements. The printer owns precedence and number
// formatting; it knows nothing of GiNaC.
#include <string>

#include "eomgen/codegen/ir.hpp"

namespace eomgen {

struct CppPrintOptions {
  std::string scalar = "Scalar";     // type of temporaries and literals
  std::string indent = "    ";
  std::string temporary_prefix = "w";
  /// false: no temporaries, every output written as its own expression tree (the
  /// unoptimized baseline of the benchmarks; exponentially long for deep chains)
  bool share_subexpressions = true;
};

/// Statements computing every output of the program: shared values become
/// `const Scalar w0 = ...;`, values used once are written inline at their use.
std::string print_cpp(const ir::Program& program, const CppPrintOptions& options = {});

/// A double as a C++ literal wrapped in the scalar type: "Scalar(0.5)", "Scalar(2)".
std::string cpp_number(double value, const std::string& scalar);

}  // namespace eomgen
