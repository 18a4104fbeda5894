#include "eomgen/codegen/cpp_identifier.hpp"

#include <fmt/format.h>

#include <set>

#include "eomgen/codegen/cpp_printer.hpp"
#include "eomgen/codegen/ir.hpp"
#include "header_macros.hpp"

namespace eomgen {
namespace {

bool is_letter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }
bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_alphanumeric(char c) { return is_letter(c) || is_digit(c); }

// C++20's keywords and alternative tokens, and the identifiers with a special meaning
std::set<std::string> keywords() {
  return {"alignas", "alignof", "and", "and_eq", "asm", "auto", "bitand", "bitor", "bool", "break", "case", "catch",
          "char", "char8_t", "char16_t", "char32_t", "class", "compl", "concept", "const", "consteval", "constexpr",
          "constinit", "const_cast", "continue", "co_await", "co_return", "co_yield", "decltype", "default",
          "delete", "do", "double", "dynamic_cast", "else", "enum", "explicit", "export", "extern", "false", "float",
          "for", "friend", "goto", "if", "inline", "int", "long", "mutable", "namespace", "new", "noexcept", "not",
          "not_eq", "nullptr", "operator", "or", "or_eq", "private", "protected", "public", "register",
          "reinterpret_cast", "requires", "return", "short", "signed", "sizeof", "static", "static_assert",
          "static_cast", "struct", "switch", "template", "this", "thread_local", "throw", "true", "try", "typedef",
          "typeid", "typename", "union", "unsigned", "using", "virtual", "void", "volatile", "wchar_t", "while",
          "xor", "xor_eq", "final", "override", "import", "module"};
}

// Every name the generated header uses unqualified (not after '.' or '::'): a model's name
// equal to one could change what the header means. The names of the IR's calls, arguments
// and arrays come from the lists the printer spells them with; the rest are written by
// header_assembly.cpp, model_metadata.cpp, function_source.cpp, parameter_constants.cpp and
// linearization_source.cpp. The numbered values (w0, w1, ... locals; k0, k1, ... members of
// the Constants) are left out: they never share a scope with a parameter (the Parameters
// hold only the fields and fields(), and every parameter is read through p. or c.p.).
// CppIdentifier.ChangesEveryNameOfTheGeneratedCode (tests/codegen/cpp_identifier_test.cpp)
// checks generated headers against this list.
std::set<std::string> generated_code_names() {
  std::set<std::string> names = {
      // namespaces: Eigen's, the standard library's, the runtime's and the simulation program's
      // (not eomgen_models, the default outer namespace: a model of that name is no clash, and
      // generate --namespace eomgen_models must give it)
      "Eigen", "std", "eomrt", "eomgen",
      // the Model struct's members
      "Model", "nq", "nu", "nc", "nh", "np", "ny", "ni", "name", "description", "generator_version", "model_hash",
      "coordinate_names", "input_names", "parameter_names", "parameter_defaults", "constraint_names",
      "holonomic_rows", "independent_speeds", "output_names", "has_forward_dynamics", "prefers_forward_dynamics",
      "Vector", "Inputs", "MassMatrix", "ConstraintJacobian", "ConstraintVector", "HolonomicVector", "OutputVector",
      "InputMatrix", "StateMatrix", "StateInputMatrix", "Parameters", "fields", "Constants", "parameters",
      "DerivedParameters", "derived_parameters",
      "mass_matrix", "forcing", "mass_matrix_and_forcing", "constraint_jacobian", "constraint_rate_term",
      "constraint_acceleration_term", "holonomic_residuals", "kinetic_energy", "potential_energy", "outputs",
      "forward_dynamics", "forward_dynamics_derivatives", "linearization_terms", "inverse_dynamics", "gravity_forces",
      "coriolis_matrix", "regressor", "kkt_derivatives", "multiplier_derivatives",
      "inertial_parameters", "npi", "inertial_parameter_names", "fits",
      // the template parameters of the functions, their locals, and the standard names they use
      "DerivedQ", "DerivedQd", "DerivedU", "DerivedQdd", "DerivedLambda", "Out0", "Out1", "Out2", "Out3", "Out4",
      "total", "decay_t", "forward", "eigen_assert", "Derived", "rows", "cols",
      // the template parameter, an attribute, the locals of forward_dynamics and its finiteness test
      "Scalar", "maybe_unused", "regular", "isfinite", "i", "j",
      // those of a constrained header's kkt_derivatives (linearization_source.cpp)
      "ParametersOrConstants", "kkt", "kkt_x", "kkt_pivot", "kkt_row", "kkt_below", "kkt_column", "kkt_solve",
      "kkt_rhs", "dlambda_dq", "dlambda_dqd", "dlambda_du",
      // macros the generated code must never meet as names, whatever the headers included
      "NDEBUG", "assert", "errno"};
  for (const ir::CallOp& call : ir::call_ops) names.insert(call.cpp_name);
  for (int kind = 0; kind <= static_cast<int>(ir::VariableKind::constant); ++kind)
    names.insert(cpp_argument_name(static_cast<ir::VariableKind>(kind)));
  for (int array = 0; array <= static_cast<int>(ir::Array::derived_parameters); ++array)
    names.insert(cpp_array_name(static_cast<ir::Array>(array)));
  return names;
}

// the prefixes of the functions named after outputs (function_table.cpp)
bool has_generated_prefix(const std::string& name) {
  return name.rfind("output_jacobian_", 0) == 0 || name.rfind("output_bias_", 0) == 0;
}

bool is_reserved(const std::string& name) {
  static const std::set<std::string> words = [] {
    std::set<std::string> all = keywords();
    all.merge(generated_code_names());
    return all;
  }();
  return words.count(name) > 0 || has_generated_prefix(name) || is_header_macro(name);
}

// A letter, then letters, digits and single '_' between them: an identifier that no rule of
// C++ reserves (no leading '_', no "__") and that does not end in '_'.
bool is_plain(const std::string& name) {
  if (name.empty() || !is_letter(name.front()) || name.back() == '_') return false;
  for (std::size_t i = 0; i < name.size(); ++i) {
    if (!is_alphanumeric(name[i]) && name[i] != '_') return false;
    if (name[i] == '_' && name[i + 1] == '_') return false;  // name.back() != '_': i + 1 < size
  }
  return true;
}

// The escape of any byte string into letters, digits and '_' followed by a letter, '0', '1'
// or '2', so it never contains "__" nor ends in '_':
//   a letter or digit       stays
//   '_' before a letter     stays
//   any other '_'           "_1"
//   any other byte          "_2" and its two hex digits (uppercase)
// and a prefix "v_0" when the name does not begin with a letter. Decoding reads it back from
// left to right ("_0" occurs only in the prefix), so different names give different escapes.
// A plain name without "_" before a digit escapes to itself.
std::string escaped(const std::string& name) {
  std::string out = name.empty() || !is_letter(name.front()) ? "v_0" : "";
  for (std::size_t i = 0; i < name.size(); ++i) {
    const char c = name[i];
    if (is_alphanumeric(c))
      out += c;
    else if (c == '_')
      out += i + 1 < name.size() && is_letter(name[i + 1]) ? "_" : "_1";
    else
      out += fmt::format("_2{:02X}", static_cast<unsigned char>(c));
  }
  return out;
}

}  // namespace

std::string cpp_identifier(const std::string& name) {
  if (is_plain(name) && !is_reserved(name)) return name;
  // every other name ends in the one '_' a plain name never has
  return escaped(name) + "_";
}

std::string cpp_string_contents(const std::string& text) {
  std::string out;
  for (unsigned char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c >= 32 && c < 127 && c != '?') {  // '?' avoids trigraph surprises in old compilers
      out += static_cast<char>(c);
    } else {
      out += fmt::format("\\{:03o}", c);
    }
  }
  return out;
}

std::string cpp_comment_text(const std::string& text) {
  std::string out;
  for (char c : text)
    if (c >= 32 && c < 127 && c != '\\') out += c;
  return out;
}

}  // namespace eomgen
