#include "function_source.hpp"

#include "eomgen/base/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <iterator>
#include <set>

#include "eomgen/codegen/parameter_constants.hpp"

namespace eomgen {
namespace {

using ir::Array;
using ir::VariableKind;

// the type alias of the generated Model that holds an array
const char* array_type(Array array) {
  switch (array) {
    case Array::mass_matrix:
    case Array::stiffness:
    case Array::damping:
      return "MassMatrix";
    case Array::forcing:
    case Array::accelerations:
      return "Vector";
    case Array::pivots: EOMGEN_UNREACHABLE("the pivots are local to forward_dynamics, never an argument");
    case Array::constraint_jacobian:
    case Array::acceleration_constraint_by_q:
    case Array::acceleration_constraint_by_qd:
      return "ConstraintJacobian";
    case Array::constraint_rate_term:
    case Array::constraint_acceleration_term:
      return "ConstraintVector";
    case Array::holonomic_residuals: return "HolonomicVector";
    case Array::outputs: return "OutputVector";
    case Array::input_matrix: return "InputMatrix";
    case Array::kinetic_energy:
    case Array::potential_energy:
      return "Scalar";
    case Array::constants:
    case Array::derived_parameters:
      break;  // members of the Constants, never an argument
  }
  EOMGEN_UNREACHABLE("an ir::Array value that is not an enumerator");
}

// the declaration of the argument holding the variables of a kind
std::string input_declaration(VariableKind kind) {
  const char* name = cpp_argument_name(kind);
  switch (kind) {
    case VariableKind::time: return fmt::format("const Scalar& {}", name);
    case VariableKind::parameter: return fmt::format("const Parameters<Scalar>& {}", name);
    case VariableKind::input: return fmt::format("const Inputs<Scalar>& {}", name);
    case VariableKind::multiplier: return fmt::format("const ConstraintVector<Scalar>& {}", name);
    case VariableKind::derived_parameter:
      EOMGEN_UNREACHABLE("the derived parameters are read through the Constants, never an argument");
    case VariableKind::constant: return fmt::format("const Constants<Scalar>& {}", name);
    case VariableKind::coordinate:
    case VariableKind::rate:
    case VariableKind::acceleration:
      return fmt::format("const Vector<Scalar>& {}", name);
  }
  EOMGEN_UNREACHABLE("an ir::VariableKind value that is not an enumerator");
}

// every argument may go unused in a particular model (M of a pendulum ignores t); `parameters`
// is how the function takes the parameters: as Parameters (p) or as their Constants (c)
std::string signature(const FunctionSpec& f, VariableKind parameters) {
  assert(std::is_sorted(f.reads.begin(), f.reads.end()));  // t, q, qd, u, p, qdd, lambda
  std::vector<std::string> declarations;
  for (VariableKind kind : f.reads)
    declarations.push_back(input_declaration(kind == VariableKind::parameter ? parameters : kind));
  if (!returns_scalar(f))
    for (Array array : f.writes) declarations.push_back(fmt::format("{}<Scalar>& {}", array_type(array), cpp_array_name(array)));
  std::string s;
  for (std::size_t k = 0; k < declarations.size(); ++k) s += (k ? ", " : "") + std::string("[[maybe_unused]] ") + declarations[k];
  return s;
}

// `using std::sin; ...` for every call op, six to a line, so that unqualified calls find the
// <cmath> overloads, and argument-dependent lookup those of a user's scalar type
std::string math_using_declarations(const std::string& indent) {
  std::string s;
  const std::size_t count = std::size(ir::call_ops);
  for (std::size_t i = 0; i < count; ++i)
    s += fmt::format("{}using std::{};{}", i % 6 == 0 ? indent : " ", ir::call_ops[i].cpp_name,
                     i % 6 == 5 || i + 1 == count ? "\n" : "");
  return s;
}

// the overload taking Parameters: it builds their Constants for this one call
std::string forwarding_source(const FunctionSpec& f, const CppPrintOptions& print) {
  const bool scalar = returns_scalar(f), returns = scalar || f.returns_regularity;
  std::string arguments;
  for (VariableKind kind : f.reads)
    arguments += std::string(arguments.empty() ? "" : ", ") +
                 (kind == VariableKind::parameter ? "Constants<Scalar>(p)" : cpp_argument_name(kind));
  if (!scalar)
    for (Array array : f.writes) arguments += std::string(", ") + cpp_array_name(array);
  return fmt::format(
      "\n  /// {}\n  /// From the parameters: computes their Constants for this call alone (to evaluate\n"
      "  /// repeatedly, build the Constants once and call the overload above).\n  template <class Scalar>\n"
      "  static {} {}({}) noexcept {{\n{}{}{}({});\n  }}\n",
      f.doc, scalar ? "Scalar" : f.returns_regularity ? "bool" : "void", f.name, signature(f, VariableKind::parameter),
      print.indent, returns ? "return " : "", f.name, arguments);
}

// `Scalar k0, k1, ...;`, ten to a line
std::string constant_members(std::size_t count) {
  std::string s;
  for (std::size_t k = 0; k < count; ++k)
    s += fmt::format("{}k{}{}", k % 10 == 0 ? "    Scalar " : ", ", k, k % 10 == 9 || k + 1 == count ? ";\n" : "");
  return s;
}

std::size_t pivot_count(const FunctionSpec& f) {
  return static_cast<std::size_t>(std::count_if(f.targets.begin(), f.targets.end(), [](const LoweringTarget& t) {
    return t.target.array == Array::pivots;
  }));
}

// M is positive definite exactly when every pivot is; NaN fails both tests
std::string regularity_check(const FunctionSpec& f, std::size_t pivots, const std::string& indent) {
  std::string s = fmt::format("{}bool regular = true;\n", indent);
  if (pivots > 0)
    s += fmt::format("{}for (int k = 0; k < {}; ++k) regular = regular && pivot(k) > Scalar(0);\n", indent, pivots);
  s += fmt::format("{}using std::isfinite;\n", indent);
  for (Array array : f.writes)
    s += fmt::format("{}for (int k = 0; k < {}.size(); ++k) regular = regular && isfinite({}(k));\n", indent,
                     cpp_array_name(array), cpp_array_name(array));
  return s + fmt::format("{}return regular;\n", indent);
}

}  // namespace

std::string constants_source(const ir::Program& derived_parameters, const ir::Program& constants,
                             const CppPrintOptions& print) {
  const bool derived = !print.derived_parameter_names.empty();
  std::string s =
      "\n  /// The values of the functions below that depend on the parameters only, computed once per\n"
      "  /// parameter set. Immutable: for other parameters, build other Constants.\n"
      "  template <class Scalar>\n  class Constants {\n   public:\n"
      "    /// Computes every constant from a copy of the parameters.\n"
      "    explicit Constants(const Parameters<Scalar>& parameters) noexcept : p(parameters) {";
  if (constants.outputs.empty() && derived_parameters.outputs.empty()) {
    s += "}\n";
  } else {
    CppPrintOptions body = print;
    body.indent += "  ";
    s += "\n" + math_using_declarations(body.indent);
    if (!derived_parameters.outputs.empty()) {
      // each as written: a tree reading the parameters and the derived parameters before it
      CppPrintOptions written = body;
      written.share_subexpressions = false;
      s += body.indent + "// the derived parameters, each from the parameters and those before it\n" +
           print_cpp(derived_parameters, written);
    }
    s += print_cpp(constants, body) + "    }\n";
  }
  s += "    /// The parameters these constants were computed from.\n"
       "    const Parameters<Scalar>& parameters() const noexcept { return p; }\n";
  if (derived)
    s += "    /// The derived parameters, computed from them.\n"
         "    const DerivedParameters<Scalar>& derived_parameters() const noexcept { return derived; }\n";
  s += "\n   private:\n    friend struct Model;\n    Parameters<Scalar> p;\n";
  if (derived) s += "    DerivedParameters<Scalar> derived;\n";
  return s + constant_members(constants.outputs.size()) + "  };\n";
}

std::string function_source(const FunctionSpec& f, const ir::Program& program, const CppPrintOptions& print) {
  const bool scalar = returns_scalar(f);
  const std::string result = scalar ? cpp_target(f.targets.front().target) : std::string();
  std::string code = fmt::format("\n  /// {}\n  template <class Scalar>\n  static {} {}({}) noexcept {{\n", f.doc,
                                 scalar ? "Scalar" : f.returns_regularity ? "bool" : "void", f.name,
                                 signature(f, VariableKind::constant));
  code += math_using_declarations(print.indent);
  if (scalar) code += fmt::format("{}Scalar {} = Scalar(0);\n", print.indent, result);
  const std::size_t pivots = pivot_count(f);
  if (pivots > 0) code += fmt::format("{}Eigen::Matrix<Scalar, {}, 1> pivot;\n", print.indent, pivots);
  code += print_cpp(program, print);
  // structural zeros are written as zeros, not computed
  std::set<ir::Target> computed;
  for (const ir::Assignment& a : program.outputs) computed.insert(a.target);
  for (const LoweringTarget& target : f.targets)
    if (!computed.count(target.target) && !scalar)
      code += fmt::format("{}{} = Scalar(0);\n", print.indent, cpp_target(target.target));
  for (const auto& [target, source] : f.mirrors)
    code += fmt::format("{}{} = {};\n", print.indent, cpp_target(target),
                        computed.count(source) ? cpp_target(source) : "Scalar(0)");
  if (scalar) code += fmt::format("{}return {};\n", print.indent, result);
  if (f.returns_regularity) code += regularity_check(f, pivots, print.indent);
  return code + "  }\n" + forwarding_source(f, print);
}

EmittedFunctions emit_functions(const std::vector<FunctionSpec>& table,
                                const std::vector<LoweringTarget>& derived_parameters,
                                const std::vector<const Subexpressions*>& intermediates,
                                const VariableNames& variables, const CppPrintOptions& print) {
  std::vector<std::vector<LoweringTarget>> targets;
  for (const FunctionSpec& f : table) targets.push_back(f.targets);
  const std::vector<ir::Program> programs = lower_functions(targets, intermediates, variables);
  const ir::Program derived = lower(derived_parameters, Subexpressions(), variables);
  // the baseline without sharing keeps every value where it is used
  const ConstantSplit split = print.share_subexpressions ? split_constants(programs) : ConstantSplit{{}, programs};
  EmittedFunctions emitted;
  // the derived parameters are computed as written, each tree whole, however they are printed
  emitted.statistics.push_back(
      {constants_statistics_name,
       ir::count_operations_without_sharing(split.constants) + ir::count_operations_without_sharing(derived),
       ir::count_operations(split.constants) + ir::count_operations_without_sharing(derived)});
  emitted.source = constants_source(derived, split.constants, print);
  // inside the per-call functions the parameters are the copy held by the Constants, and so
  // are the derived parameters
  CppPrintOptions per_call = print;
  per_call.parameters = std::string(cpp_argument_name(VariableKind::constant)) + ".p";
  per_call.derived_parameters =
      std::string(cpp_argument_name(VariableKind::constant)) + "." + cpp_argument_name(VariableKind::derived_parameter);
  for (std::size_t k = 0; k < table.size(); ++k) {
    emitted.statistics.push_back({table[k].name, ir::count_operations_without_sharing(programs[k]),
                                  ir::count_operations(split.per_call[k])});
    emitted.source += function_source(table[k], split.per_call[k], per_call);
  }
  return emitted;
}

}  // namespace eomgen
