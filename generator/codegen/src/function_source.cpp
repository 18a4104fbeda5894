#include "function_source.hpp"

#include "eomgen/base/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <initializer_list>
#include <iterator>
#include <set>

#include "eomgen/codegen/angle_sums.hpp"
#include "eomgen/codegen/parameter_constants.hpp"

namespace eomgen {
namespace {

using ir::Array;
using ir::VariableKind;

// the template parameter of a vector input's type, empty for the others
const char* template_parameter(VariableKind kind) {
  switch (kind) {
    case VariableKind::coordinate: return "DerivedQ";
    case VariableKind::rate: return "DerivedQd";
    case VariableKind::input: return "DerivedU";
    case VariableKind::acceleration: return "DerivedQdd";
    case VariableKind::multiplier: return "DerivedLambda";
    case VariableKind::time:
    case VariableKind::parameter:
    case VariableKind::constant:
      return "";
    case VariableKind::derived_parameter:
      EOMGEN_UNREACHABLE("the derived parameters are read through the Constants, never an argument");
  }
  EOMGEN_UNREACHABLE("an ir::VariableKind value that is not an enumerator");
}

// the C++ constant of the number of entries of a vector input
const char* input_size(VariableKind kind) {
  switch (kind) {
    case VariableKind::coordinate:
    case VariableKind::rate:
    case VariableKind::acceleration:
      return "nq";
    case VariableKind::input: return "nu";
    case VariableKind::multiplier: return "nc";
    case VariableKind::time:
    case VariableKind::parameter:
    case VariableKind::constant:
    case VariableKind::derived_parameter:
      break;
  }
  EOMGEN_UNREACHABLE("the size of an input that is not a vector");
}

// the template parameter of the type of output argument k
std::string output_parameter(std::size_t k) { return fmt::format("Out{}", k); }

// What a function's text needs to know besides its table entry: whether the scalar type comes
// from a vector input (its first) or from the Parameters and Constants (a function of the
// parameters alone), and which arguments its statements read.
struct Arguments {
  std::string scalar_source;  // the template parameter whose ::Scalar is Scalar, or empty
  std::set<VariableKind> read;
  std::set<Array> written;
};

Arguments arguments_of(const FunctionSpec& f, const ir::Program& program) {
  Arguments a;
  for (VariableKind kind : f.reads)
    if (a.scalar_source.empty() && *template_parameter(kind)) a.scalar_source = template_parameter(kind);
  for (const ir::Instruction& in : program.instructions)
    if (in.op == ir::Op::variable) {
      VariableKind kind = in.variable.kind;
      // the parameters, the derived parameters and the constants are all read through c
      if (kind == VariableKind::parameter || kind == VariableKind::derived_parameter) kind = VariableKind::constant;
      a.read.insert(kind);
    }
  for (const LoweringTarget& t : f.targets) a.written.insert(t.target.array);
  if (f.splits_constraint_forces) a.written.insert(Array::multipliers);
  return a;
}

// `template <class DerivedQ, ..., class Out0, ...>`
std::string template_header(const FunctionSpec& f, const Arguments& a) {
  std::vector<std::string> parameters;
  if (a.scalar_source.empty()) parameters.push_back("class Scalar");
  for (VariableKind kind : f.reads)
    if (*template_parameter(kind)) parameters.push_back(fmt::format("class {}", template_parameter(kind)));
  if (!returns_scalar(f))
    for (std::size_t k = 0; k < f.writes.size(); ++k) parameters.push_back("class " + output_parameter(k));
  std::string s;
  for (const std::string& p : parameters) s += (s.empty() ? "" : ", ") + p;
  return "  template <" + s + ">\n";
}

// the scalar type as the signature spells it (before `using Scalar` is in scope)
std::string scalar_type(const Arguments& a) {
  return a.scalar_source.empty() ? "Scalar" : fmt::format("typename {}::Scalar", a.scalar_source);
}

// Inputs take any Eigen expression of the right size (a block, a Map over a plain array,
// Inputs::Zero()) and outputs any writable one (a forwarding reference, so that a temporary
// block binds too); `parameters` is how the function takes the parameters: as Parameters (p)
// or as their Constants (c). Only an argument the statements do not read is [[maybe_unused]].
std::string signature(const FunctionSpec& f, const Arguments& a, VariableKind parameters, bool mark_unused) {
  const std::string scalar = scalar_type(a);
  std::vector<std::string> declarations;
  for (VariableKind kind : f.reads) {
    const VariableKind as = kind == VariableKind::parameter ? parameters : kind;
    const char* name = cpp_argument_name(as);
    std::string d;
    if (*template_parameter(kind))
      d = fmt::format("const Eigen::MatrixBase<{}>& {}", template_parameter(kind), name);
    else if (as == VariableKind::time)
      d = fmt::format("const {}& {}", scalar, name);
    else
      d = fmt::format("const {}<{}>& {}", as == VariableKind::constant ? "Constants" : "Parameters", scalar, name);
    const VariableKind read_as = kind == VariableKind::parameter ? VariableKind::constant : kind;
    declarations.push_back((mark_unused && !a.read.count(read_as) ? "[[maybe_unused]] " : "") + d);
  }
  if (!returns_scalar(f))
    for (std::size_t k = 0; k < f.writes.size(); ++k)
      declarations.push_back(fmt::format("{}{}&& {}", mark_unused && !a.written.count(f.writes[k]) ? "[[maybe_unused]] " : "",
                                         output_parameter(k), cpp_array_name(f.writes[k])));
  std::string s;
  for (std::size_t k = 0; k < declarations.size(); ++k) s += (k ? ", " : "") + declarations[k];
  return s;
}

// `using Scalar = ...;` and a test of the size of every vector and matrix argument: at compile
// time where the expression's size is fixed, else by eigen_assert
std::string argument_checks(const FunctionSpec& f, const Arguments& a, bool alias_scalar, const std::string& indent) {
  std::string s;
  if (alias_scalar && !a.scalar_source.empty()) s += fmt::format("{}using Scalar = typename {}::Scalar;\n", indent, a.scalar_source);
  for (VariableKind kind : f.reads)
    if (*template_parameter(kind))
      s += fmt::format("{}static_assert(fits<{}>({}, 1), \"{}: expected a column of {} entries\");\n", indent,
                       template_parameter(kind), input_size(kind), cpp_argument_name(kind), input_size(kind));
  if (!returns_scalar(f))
    for (std::size_t k = 0; k < f.writes.size(); ++k)
      s += fmt::format("{}static_assert(fits<std::decay_t<{}>>({}, {}), \"{}: expected {} x {}\");\n", indent,
                       output_parameter(k), f.shapes[k].rows, f.shapes[k].cols, cpp_array_name(f.writes[k]),
                       f.shapes[k].rows, f.shapes[k].cols);
  std::string sizes;
  for (VariableKind kind : f.reads)
    if (*template_parameter(kind))
      sizes += fmt::format("{}{}.size() == {}", sizes.empty() ? "" : " && ", cpp_argument_name(kind), input_size(kind));
  if (!returns_scalar(f))
    for (std::size_t k = 0; k < f.writes.size(); ++k)
      sizes += fmt::format("{}{}.rows() == {} && {}.cols() == {}", sizes.empty() ? "" : " && ",
                           cpp_array_name(f.writes[k]), f.shapes[k].rows, cpp_array_name(f.writes[k]), f.shapes[k].cols);
  if (!sizes.empty()) s += fmt::format("{}eigen_assert({});\n", indent, sizes);
  return s;
}

// `using std::sin; ...` for the calls a program makes, six to a line, so that unqualified calls
// find the <cmath> overloads, and argument-dependent lookup those of a user's scalar type
std::string math_using_declarations(std::initializer_list<const ir::Program*> programs, const std::string& indent) {
  std::set<ir::Op> used;
  for (const ir::Program* program : programs)
    for (const ir::Instruction& in : program->instructions)
      if (ir::is_call(in.op)) used.insert(in.op);
  std::vector<const char*> names;
  for (const ir::CallOp& call : ir::call_ops)
    if (used.count(call.op)) names.push_back(call.cpp_name);
  std::string s;
  for (std::size_t i = 0; i < names.size(); ++i)
    s += fmt::format("{}using std::{};{}", i % 6 == 0 ? indent : " ", names[i],
                     i % 6 == 5 || i + 1 == names.size() ? "\n" : "");
  return s;
}

// what an overload passes on: its inputs, the parameters spelt `parameters`
std::string forwarded_inputs(const FunctionSpec& f, const std::string& parameters) {
  std::string arguments;
  for (VariableKind kind : f.reads)
    arguments += std::string(arguments.empty() ? "" : ", ") +
                 (kind == VariableKind::parameter ? parameters : std::string(cpp_argument_name(kind)));
  return arguments;
}

// ... and its outputs, each after a comma
std::string forwarded_outputs(const FunctionSpec& f) {
  std::string arguments;
  for (std::size_t k = 0; k < f.writes.size(); ++k)
    arguments += fmt::format(", std::forward<{}>({})", output_parameter(k), cpp_array_name(f.writes[k]));
  return arguments;
}

// the overload taking Parameters: it builds their Constants for this one call
std::string forwarding_source(const FunctionSpec& f, const Arguments& a, const CppPrintOptions& print) {
  const bool scalar = returns_scalar(f), returns = scalar || f.returns_regularity;
  const std::string arguments = forwarded_inputs(f, fmt::format("Constants<{}>(p)", scalar_type(a))) +
                                (scalar ? std::string() : forwarded_outputs(f));
  return fmt::format(
      "\n  /// {}\n  /// From the parameters: computes their Constants for this call alone (to evaluate\n"
      "  /// repeatedly, build the Constants once and call the overload above).\n{}"
      "  static {} {}({}) noexcept {{\n{}{}{}({});\n  }}\n",
      f.doc, template_header(f, a), scalar ? scalar_type(a) : f.returns_regularity ? "bool" : "void", f.name,
      signature(f, a, VariableKind::parameter, false), print.indent, returns ? "return " : "", f.name, arguments);
}

// With first_output_optional: the overloads without the first output (taking Constants, then
// Parameters), each computing it into a local and forwarding to the one above it that takes it
std::string optional_output_source(const FunctionSpec& f, const Arguments& a, const CppPrintOptions& print) {
  const FunctionSpec without = without_first_output(f);
  const std::string local = cpp_array_name(f.writes.front());
  std::string code;
  for (const VariableKind parameters : {VariableKind::constant, VariableKind::parameter}) {
    const std::string arguments =
        forwarded_inputs(f, cpp_argument_name(parameters)) + ", " + local + forwarded_outputs(without);
    code += fmt::format(
        "\n  /// {}: the overload above without {} (computed all the same).\n{}"
        "  static {} {}({}) noexcept {{\n{}Eigen::Matrix<{}, {}, {}> {};\n{}{}{}({});\n  }}\n",
        f.name, local, template_header(without, a), f.returns_regularity ? "bool" : "void", f.name,
        signature(without, a, parameters, false), print.indent, scalar_type(a), f.shapes.front().rows,
        f.shapes.front().cols, local, print.indent, f.returns_regularity ? "return " : "", f.name, arguments);
  }
  return code;
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
  // a matrix entry by entry: the output may be a block, which has no linear access
  for (Array array : f.writes)
    s += ir::rank(array) == 2
             ? fmt::format("{0}for (int j = 0; j < {1}.cols(); ++j)\n{0}  for (int i = 0; i < {1}.rows(); ++i) "
                           "regular = regular && isfinite({1}(i, j));\n",
                           indent, cpp_array_name(array))
             : fmt::format("{}for (int k = 0; k < {}.size(); ++k) regular = regular && isfinite({}(k));\n", indent,
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
    s += "\n" + math_using_declarations({&derived_parameters, &constants}, body.indent);
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

// With constraints: tau = M qdd - F (the targets) is split into Xi^T lambda and the rest, the
// least tau, by lambda = (Xi Xi^T)^-1 Xi tau; a redundant set gives a lambda of the LDL^T solve
std::string constraint_force_split(const std::string& indent) {
  return fmt::format(
      "{0}const Eigen::Matrix<Scalar, nq, 1> total = tau;\n"
      "{0}lambda = (Xi * Xi.transpose()).ldlt().solve(Xi * total);\n"
      "{0}tau = total - Xi.transpose() * lambda;\n",
      indent);
}

std::string function_source(const FunctionSpec& f, const ir::Program& program, const CppPrintOptions& print) {
  const bool scalar = returns_scalar(f);
  const Arguments arguments = arguments_of(f, program);
  const std::string result = scalar ? cpp_target(f.targets.front().target) : std::string();
  const std::string doc = f.first_output_optional
                              ? fmt::format("{}. With {} first: the overload below leaves it out", f.doc,
                                            cpp_array_name(f.writes.front()))
                              : f.doc;
  std::string code = fmt::format("\n  /// {}\n{}  static {} {}({}) noexcept {{\n", doc, template_header(f, arguments),
                                 scalar ? scalar_type(arguments) : f.returns_regularity ? "bool" : "void", f.name,
                                 signature(f, arguments, VariableKind::constant, true));
  const std::size_t checks = code.size();
  code += math_using_declarations({&program}, print.indent);
  if (scalar) code += fmt::format("{}Scalar {} = Scalar(0);\n", print.indent, result);
  const std::size_t pivots = pivot_count(f);
  if (pivots > 0) code += fmt::format("{}Eigen::Matrix<Scalar, {}, 1> pivot;\n", print.indent, pivots);
  if (f.splits_constraint_forces) code += fmt::format("{}Eigen::Matrix<Scalar, nc, nq> Xi;\n", print.indent);
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
  if (f.splits_constraint_forces) code += constraint_force_split(print.indent);
  if (scalar) code += fmt::format("{}return {};\n", print.indent, result);
  if (f.returns_regularity) code += regularity_check(f, pivots, print.indent);
  // `using Scalar` only where the statements name it: an unused alias is a warning
  const bool names_scalar = code.find("Scalar", checks) != std::string::npos;
  code.insert(checks, argument_checks(f, arguments, names_scalar, print.indent));
  code += "  }\n" + forwarding_source(f, arguments, print);
  if (f.first_output_optional) code += optional_output_source(f, arguments, print);
  return code;
}

EmittedFunctions emit_functions(const std::vector<FunctionSpec>& table,
                                const std::vector<LoweringTarget>& derived_parameters,
                                const std::vector<const Subexpressions*>& intermediates,
                                const VariableNames& variables, const CppPrintOptions& print) {
  std::vector<std::vector<LoweringTarget>> targets;
  for (const FunctionSpec& f : table) targets.push_back(f.targets);
  const std::vector<ir::Program> programs = lower_functions(targets, intermediates, variables);
  const ir::Program derived = lower(derived_parameters, Subexpressions(), variables);
  // the baseline without sharing keeps every value where it is used, and every call
  std::vector<ir::Program> optimized;
  if (print.share_subexpressions)
    for (const ir::Program& p : programs) optimized.push_back(expand_angle_sums(p));
  const ConstantSplit split = print.share_subexpressions ? split_constants(optimized) : ConstantSplit{{}, programs};
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
