#pragma once
// Prints a straight-line program as C++ statements. The printer owns the C++ spelling of the
// IR (variables, targets, calls), precedence and number formatting; it knows nothing of GiNaC.
#include <string>
#include <vector>

#include "eomgen/codegen/ir.hpp"

namespace eomgen {

struct CppPrintOptions {
  std::string scalar = "Scalar";     // type of temporaries and literals
  std::string indent = "    ";
  std::string temporary_prefix = "w";
  /// false: no temporaries, every output written as its own expression tree (the
  /// unoptimized baseline of the benchmarks; exponentially long for deep chains)
  bool share_subexpressions = true;
  /// the model's parameter names, in order: parameter k is read as p.<cpp_identifier(name k)>
  std::vector<std::string> parameter_names;
  /// the object parameters are read from: the argument p, or the copy c.p inside a Constants
  std::string parameters = "p";
  /// the model's derived parameter names, in order: derived parameter k is read (and, as the
  /// target Array::derived_parameters k, written) as <derived_parameters>.<cpp_identifier(name k)>
  std::vector<std::string> derived_parameter_names;
  /// where the derived parameters are: the Constants' member, or c.derived inside a function
  std::string derived_parameters = "derived";
};

/// Statements computing every output of the program: shared values become
/// `const Scalar w0 = ...;`, values used once are written inline at their use.
std::string print_cpp(const ir::Program& program, const CppPrintOptions& options = {});

/// A double as a C++ literal wrapped in the scalar type: "Scalar(0.5)", "Scalar(2)".
std::string cpp_number(double value, const std::string& scalar);

/// The argument of a generated function that holds variables of this kind: "q", "qd", "p",
/// "c" (the Constants), ...
const char* cpp_argument_name(ir::VariableKind kind);
/// The argument (or, for a scalar, the local) that holds an array: "M", "F", "T", "S_q", ...
const char* cpp_array_name(ir::Array array);

/// How a generated function reads a variable: "t", "q(0)", "lambda(1)", "p.m" (with
/// options.parameters "p"), "c.k3".
/// \pre a parameter's index is below options.parameter_names.size()
std::string cpp_variable(const ir::Variable& variable, const CppPrintOptions& options);
/// The lvalue of a target: "M(0, 1)", "F(2)", "T", "k3" (a member of the Constants).
/// \pre not a derived parameter, which needs the names of the options
std::string cpp_target(const ir::Target& target);
/// The same, and a derived parameter by its name: "derived.d1".
std::string cpp_target(const ir::Target& target, const CppPrintOptions& options);

}  // namespace eomgen
