#include "model_metadata.hpp"

#include <fmt/format.h>

#include <vector>

#include "eomgen/base/version.hpp"
#include "eomgen/codegen/cpp_identifier.hpp"
#include "eomgen/codegen/cpp_printer.hpp"
#include "eomgen/symbolic/ordered_text.hpp"

namespace eomgen {
namespace {

// "a", "b" as the initializer of a std::array of string literals
std::string name_list(const std::vector<std::string>& items) {
  std::string s;
  for (std::size_t i = 0; i < items.size(); ++i) s += fmt::format("{}\"{}\"", i ? ", " : "", cpp_string_contents(items[i]));
  return s;
}

std::string comma_list(const std::vector<std::size_t>& items) {
  std::string s;
  for (std::size_t i = 0; i < items.size(); ++i) s += fmt::format("{}{}", i ? ", " : "", items[i]);
  return s;
}

// the names of every coordinate, input, parameter, constraint and output component
struct Names {
  std::vector<std::string> coordinates, inputs, parameters, constraints, outputs;
};

Names names_of(const Model& model) {
  const Variables& vars = model.system.variables();
  Names names;
  for (const Coordinate& c : vars.coordinates()) names.coordinates.push_back(c.name);
  for (const Input& u : vars.inputs()) names.inputs.push_back(u.name);
  for (const Parameter& p : vars.parameters()) names.parameters.push_back(p.name);
  for (const Constraint& c : model.system.constraints()) names.constraints.push_back(c.name);
  for (const Output& o : model.outputs) names.outputs.insert(names.outputs.end(), o.labels.begin(), o.labels.end());
  return names;
}

// phi holds the holonomic rows of Xi in model order; the runtime stabilizes and projects them
std::vector<std::size_t> holonomic_rows(const Model& model) {
  std::vector<std::size_t> rows;
  for (std::size_t i = 0; i < model.system.constraints().size(); ++i)
    if (model.system.constraints()[i].kind == Constraint::Kind::holonomic) rows.push_back(i);
  return rows;
}

std::string sizes_source(const Model& model, const ModelEquations& eom, const Names& names) {
  std::string s;
  s += fmt::format("  static constexpr int nq = {};  // coordinates (and rates)\n", names.coordinates.size());
  s += fmt::format("  static constexpr int nu = {};  // inputs\n", names.inputs.size());
  s += fmt::format("  static constexpr int nc = {};  // constraints (rows of Xi)\n", eom.constraint_count);
  s += fmt::format("  static constexpr int nh = {};  // holonomic constraints (rows of phi)\n",
                   eom.holonomic_residuals.rows());
  s += fmt::format("  static constexpr int np = {};  // parameters\n", names.parameters.size());
  std::size_t ny = 0;
  for (const Output& o : model.outputs) ny += o.components.size();
  s += fmt::format("  static constexpr int ny = {};  // output components\n", ny);
  s += fmt::format("  static constexpr int ni = {};  // independent speeds declared in the model (0: none, null space "
                   "from QR of Xi)\n", model.independent_speeds.size());
  return s;
}

}  // namespace

std::string independent_speed_list(const Model& model) { return comma_list(model.independent_speeds); }

std::string metadata_source(const Model& model, const HeaderFunctions& functions, std::uint64_t model_hash) {
  const ModelEquations& eom = *functions.equations;
  const Names names = names_of(model);
  std::string defaults;
  for (const Parameter& p : model.system.variables().parameters())
    defaults += fmt::format("{}{}", defaults.empty() ? "" : ", ", cpp_number(p.default_value, "double"));
  std::string s = sizes_source(model, eom, names);
  s += fmt::format("  static constexpr const char* name = \"{}\";\n", cpp_string_contents(model.name));
  s += fmt::format("  static constexpr const char* description = \"{}\";\n", cpp_string_contents(model.description));
  s += fmt::format("  static constexpr const char* generator_version = \"{}\";\n", version);
  s += fmt::format("  static constexpr const char* model_hash = \"{:016x}\";\n", model_hash);
  s += fmt::format("  static constexpr std::array<const char*, nq> coordinate_names{{{{{}}}}};\n", name_list(names.coordinates));
  s += fmt::format("  static constexpr std::array<const char*, nu> input_names{{{{{}}}}};\n", name_list(names.inputs));
  s += fmt::format("  static constexpr std::array<const char*, np> parameter_names{{{{{}}}}};\n", name_list(names.parameters));
  s += fmt::format("  static constexpr std::array<double, np> parameter_defaults{{{{{}}}}};\n", defaults);
  s += fmt::format("  static constexpr std::array<const char*, nc> constraint_names{{{{{}}}}};\n", name_list(names.constraints));
  s += fmt::format("  static constexpr std::array<int, nh> holonomic_rows{{{{{}}}}};  // row of Xi of each entry of phi\n",
                   comma_list(holonomic_rows(model)));
  s += fmt::format("  static constexpr std::array<int, ni> independent_speeds{{{{{}}}}};  // their coordinate indices\n",
                   independent_speed_list(model));
  s += fmt::format("  static constexpr std::array<const char*, ny> output_names{{{{{}}}}};\n", name_list(names.outputs));
  if (functions.regressor && functions.base_parameters) {
    s += fmt::format("  static constexpr int npi = {};  // identifiable base parameters (regressor)\n",
                     functions.base_parameters->names.size());
    s += fmt::format("  static constexpr std::array<const char*, npi> inertial_parameter_names{{{{{}}}}};\n",
                     name_list(functions.base_parameters->names));
  } else if (functions.regressor) {
    s += fmt::format("  static constexpr int npi = {};  // inertial parameters: 10 per body (regressor)\n",
                     functions.inertial_parameter_names.size());
    s += fmt::format("  static constexpr std::array<const char*, npi> inertial_parameter_names{{{{{}}}}};\n",
                     name_list(functions.inertial_parameter_names));
  }
  return s;
}

std::string parameters_source(const Model& model) {
  std::string fields, pointers;
  bool renamed = false;
  for (const Parameter& p : model.system.variables().parameters()) {
    const std::string field = cpp_identifier(p.name);
    const std::string unit = p.unit.empty() ? "" : "[" + cpp_comment_text(p.unit) + "]";
    // a renamed field says whose it is
    const std::string comment = field == p.name ? unit : fmt::format("'{}'{}{}", cpp_comment_text(p.name),
                                                                     unit.empty() ? "" : " ", unit);
    renamed = renamed || field != p.name;
    pointers += fmt::format("{}&{}", pointers.empty() ? "" : ", ", field);
    fields += fmt::format("    Scalar {} = {};{}\n", field, cpp_number(p.default_value, "Scalar"),
                          comment.empty() ? "" : " // " + comment);
  }
  std::string s = "  /// Parameters, defaulted to the model's values.\n";
  if (renamed)
    s += "  /// A field has its parameter's name, unless that name is a C++ keyword, a name of this\n"
         "  /// header or a macro of the standard headers, or begins, ends or doubles '_': then the\n"
         "  /// field ends in '_' and its comment gives the parameter (eomgen's docs/model-language.md).\n";
  s += "  template <class Scalar>\n  struct Parameters {\n";
  s += fields;
  if (!model.system.variables().derived_parameters().empty())
    s += "    // The model's derived parameters are no fields: the Constants compute them (DerivedParameters).\n";
  s += "    /// The fields in the order of parameter_names, to set parameters by index or name.\n";
  s += fmt::format("    std::array<Scalar*, np> fields() noexcept {{ return {{{{{}}}}}; }}\n", pointers);
  return s + "  };\n" + derived_parameters_source(model);
}

std::string derived_parameters_source(const Model& model) {
  const std::vector<DerivedParameter>& derived = model.system.variables().derived_parameters();
  if (derived.empty()) return "";
  std::string s = "\n  /// The derived parameters, each defined from the parameters and those before it: computed by\n"
                  "  /// the Constants (Constants::derived_parameters()) whenever the parameters are given.\n"
                  "  template <class Scalar>\n  struct DerivedParameters {\n";
  for (const DerivedParameter& d : derived) {
    const std::string field = cpp_identifier(d.name);
    // a renamed field says whose it is, as in the Parameters
    s += fmt::format("    Scalar {} = Scalar(0);  // {}= {}{}\n", field,
                     field == d.name ? "" : "'" + cpp_comment_text(d.name) + "' ",
                     cpp_comment_text(ordered_text(d.definition)),
                     d.unit.empty() ? "" : " [" + cpp_comment_text(d.unit) + "]");
  }
  return s + "  };\n";
}

}  // namespace eomgen
