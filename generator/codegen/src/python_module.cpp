#include "eomgen/codegen/python_module.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <string_view>
#include <vector>

#include "eomgen/base/error.hpp"
#include "eomgen/codegen/cpp_identifier.hpp"
#include "function_table.hpp"

namespace eomgen {
namespace {

using ir::VariableKind;

// Python's keywords (3.11), which cannot name a module or an attribute
constexpr std::array<std::string_view, 35> python_keywords{
    "False", "None",   "True",    "and",      "as",   "assert", "async",  "await",    "break",
    "class", "continue", "def",   "del",      "elif", "else",   "except", "finally",  "for",
    "from",  "global", "if",      "import",   "in",   "is",     "lambda", "nonlocal", "not",
    "or",    "pass",   "raise",   "return",   "try",  "while",  "with",   "yield"};

// the argument of eompy::Reads, and the member of eompy::Point the call passes, of an input
struct ReadSpelling {
  const char* arg;
  const char* member;
};

ReadSpelling spelling(VariableKind kind) {
  switch (kind) {
    case VariableKind::time: return {"t", "x.t"};
    case VariableKind::coordinate: return {"q", "x.q"};
    case VariableKind::rate: return {"qd", "x.qd"};
    case VariableKind::acceleration: return {"qdd", "x.qdd"};
    case VariableKind::input: return {"u", "x.u"};
    case VariableKind::multiplier: return {"lambda", "x.lambda"};
    case VariableKind::parameter: return {"p", "*x.c"};
    case VariableKind::constant:
    case VariableKind::derived_parameter:
      EOMGEN_UNREACHABLE("the Constants and derived parameters are read through the parameters, never an argument");
  }
  EOMGEN_UNREACHABLE("an ir::VariableKind value that is not an enumerator");
}

std::string quoted(const std::string& text) { return "\"" + cpp_string_contents(text) + "\""; }

template <class Names>
std::string literal_list(const Names& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + quoted(n);
  return "{{" + s + "}}";
}

// "mass_matrix(t, q, p=None) -> (nq, nq)": the first line of a function's docstring
std::string python_signature(const FunctionSpec& f) {
  std::string args;
  for (VariableKind kind : f.reads) {
    const char* name = spelling(kind).arg;
    std::string a = std::string_view(name) == "lambda" ? "lambda_" : name;
    if (kind == VariableKind::input || kind == VariableKind::parameter) a += "=None";
    args += (args.empty() ? "" : ", ") + a;
  }
  std::string results;
  if (returns_scalar(f)) {
    results = "float";
  } else {
    for (const ArgumentShape& s : f.shapes)
      results += (results.empty() ? "" : ", ") +
                 (s.cols == "1" ? fmt::format("({},)", s.rows) : fmt::format("({}, {})", s.rows, s.cols));
    if (f.shapes.size() > 1) results = "(" + results + ")";
  }
  return fmt::format("{}({}) -> {}", f.name, args, results);
}

// one eompy::FunctionDefinition: the call of the header's function per state
std::string definition(const FunctionSpec& f) {
  std::string reads, call_arguments;
  for (VariableKind kind : f.reads) {
    reads += fmt::format(", eompy::Arg::{}", spelling(kind).arg);
    call_arguments += (call_arguments.empty() ? "" : ", ") + std::string(spelling(kind).member);
  }
  std::string outs, out_parameters;
  const char* returns = "nothing";
  if (returns_scalar(f)) {
    returns = "scalar";
  } else {
    for (std::size_t k = 0; k < f.shapes.size(); ++k) {
      outs += fmt::format(", eompy::Out<{}, {}, {}>", f.shapes[k].rows, f.shapes[k].cols,
                          f.shapes[k].cols == "1" ? "true" : "false");
      out_parameters += fmt::format(", auto&& o{}", k);
      call_arguments += fmt::format(", o{}", k);
    }
  }
  if (f.returns_regularity) returns = "status";
  const std::string doc =
      python_signature(f) + "\n\n" + f.doc +
      ". Each state argument may be one value or a batch of N (an array with a first dimension N); u=None is zero "
      "inputs and p=None the default parameters.";
  std::string body;
  if (f.returns_regularity)
    body = fmt::format("return Model::{}({}) ? nullptr : \"M is not positive definite (a pivot is not positive), or "
                       "the result is not finite\";",
                       f.name, call_arguments);
  else if (returns_scalar(f))
    body = fmt::format("return Model::{}({});", f.name, call_arguments);
  else
    body = fmt::format("Model::{}({});", f.name, call_arguments);
  return fmt::format(
      "    eompy::FunctionDefinition<Model, eompy::Returns::{}, eompy::Reads<{}>{}>::define(\n"
      "        m, {}, {}, defaults,\n"
      "        []([[maybe_unused]] const eompy::Point<Model>& x{}) {{ {} }});\n",
      returns, reads.substr(2), outs, quoted(f.name), quoted(doc), out_parameters, body);
}

}  // namespace

std::string python_identifier(const std::string& name) {
  return std::find(python_keywords.begin(), python_keywords.end(), name) != python_keywords.end() ? name + "_" : name;
}

std::string python_module_name(const Model& model) { return python_identifier(cpp_identifier(model.name)); }

std::string python_module_source(const Model& model, const HeaderFunctions& functions, const std::string& module_name) {
  EOMGEN_DEMAND(functions.linearization != nullptr,
                "a Python module's header holds linearization_terms: derive its functions with a linearization");
  const Variables& vars = model.system.variables();
  std::vector<std::string> attributes, parameter_units, coordinate_units, input_units;
  for (const Parameter& p : vars.parameters()) {
    attributes.push_back(python_identifier(cpp_identifier(p.name)));
    parameter_units.push_back(p.unit);
  }
  for (const Coordinate& c : vars.coordinates()) coordinate_units.push_back(c.unit);
  for (const Input& u : vars.inputs()) input_units.push_back(u.unit);

  std::string definitions;
  // a function with an optional first output is bound without it, as its own outputs alone
  for (const FunctionSpec& f : function_table(model, functions))
    definitions += definition(f.first_output_optional ? without_first_output(f) : f);

  return fmt::format(
      "// The Python module of model '{model}', written by eomgen (docs/python.md).\n"
      "#include \"model.hpp\"\n"
      "#include \"eompy/module.hpp\"\n\n"
      "namespace {{\n\n"
      "// a scope where the header's sizes (nq, nu, ny, ...) are names, as its function table writes them\n"
      "struct Definitions : eomgen_models::{ns}::Model {{\n"
      "  using Model = eomgen_models::{ns}::Model;\n"
      "  static void define(pybind11::module_& m) {{\n"
      "    pybind11::options options;  // each docstring begins with its Python signature\n"
      "    options.disable_function_signatures();\n"
      "    const eompy::ModelText<Model> text{{{{{attributes}, {parameter_units}}}, {coordinate_units}, "
      "{input_units}}};\n"
      "    const eompy::ParameterSet<Model>& defaults = eompy::define_model<Model>(m, text);\n"
      "{definitions}"
      "  }}\n"
      "}};\n\n"
      "}}  // namespace\n\n"
      "PYBIND11_MODULE({module}, m) {{ Definitions::define(m); }}\n",
      fmt::arg("model", cpp_string_contents(model.name)), fmt::arg("ns", cpp_identifier(model.name)),
      fmt::arg("attributes", literal_list(attributes)), fmt::arg("parameter_units", literal_list(parameter_units)),
      fmt::arg("coordinate_units", literal_list(coordinate_units)), fmt::arg("input_units", literal_list(input_units)),
      fmt::arg("definitions", definitions), fmt::arg("module", module_name));
}

}  // namespace eomgen
