#include "eomgen/codegen/emit_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>
#include <optional>
#include <set>

#include "eomgen/base/content_hash.hpp"
#include "eomgen/codegen/cpp_printer.hpp"
#include "eomgen/base/error.hpp"
#include "eomgen/derivation/linearization.hpp"
#include "eomgen/codegen/lower.hpp"
#include "eomgen/base/version.hpp"
#include "linearization_source.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;

// `using std::sin; ...` for every call op, six to a line, so unqualified calls find the
// overloads of any scalar type (ADL finds those outside std)
std::string math_using_declarations() {
  std::string s;
  const std::size_t count = std::size(ir::call_ops);
  for (std::size_t i = 0; i < count; ++i)
    s += fmt::format("{}using std::{};{}", i % 6 == 0 ? "    " : " ", ir::call_ops[i].cpp_name,
                     i % 6 == 5 || i + 1 == count ? "\n" : "");
  return s;
}

// one generated function: its signature pieces and its lowered body
struct FunctionSpec {
  FunctionSpec(std::string n, std::string d, std::string r, std::string a)
      : name(std::move(n)), doc(std::move(d)), returns(std::move(r)), arguments(std::move(a)) {}
  std::string name;
  std::string doc;
  std::string returns;    // "void" or "Scalar"
  std::string arguments;  // after the common (t, q[, qd][, u], p)
  bool needs_qd = false;
  bool needs_u = false;
  std::vector<LoweringTarget> targets;
  std::vector<std::pair<ir::Target, ir::Target>> mirrors;  // target = source after the body
  std::string scalar_result;  // name of the scalar result variable, if returns Scalar
};

}  // namespace

EmittedModel emit_model(const Model& model, const ModelEquations& eom, const EmitOptions& options) {
  const Variables& vars = model.system.variables();
  const std::size_t n = vars.coordinate_count(), m = eom.constraint_count;
  const std::size_t nh = eom.holonomic_residuals.rows();
  std::size_t ny = 0;
  for (const Output& o : model.outputs) ny += o.components.size();
  // a Model assembled through the API skips the parser's checks of the `independent` statement
  const std::vector<std::size_t>& independent = model.independent_speeds;
  if (!independent.empty()) {
    if (independent.size() + m != n)
      throw EmitError(fmt::format("emitting '{}': expected nq - nc = {} independent speeds, got {}", model.name,
                                  static_cast<long>(n) - static_cast<long>(m), independent.size()));
    std::set<std::size_t> seen;
    for (std::size_t i = 0; i < independent.size(); ++i)
      if (independent[i] >= n || !seen.insert(independent[i]).second)
        throw EmitError(fmt::format("emitting '{}': independent speed {} is coordinate index {}: expected distinct "
                                    "indices below nq = {}", model.name, i, independent[i], n));
  }

  CppPrintOptions print_options;
  print_options.share_subexpressions = options.share_subexpressions;
  for (const Parameter& p : vars.parameters()) print_options.parameter_names.push_back(p.name);
  // which input each model symbol is; named by its spelling, which has fixed the order of
  // operands since the first version
  VariableNames names;
  auto bind = [&](const ex& symbol, ir::VariableKind kind, std::size_t index) {
    const ir::Variable variable{kind, index};
    names[symbol] = NamedVariable{variable, cpp_variable(variable, print_options)};
  };
  bind(vars.time(), ir::VariableKind::time, 0);
  for (std::size_t k = 0; k < n; ++k) {
    bind(vars.coordinates()[k].q, ir::VariableKind::coordinate, k);
    bind(vars.coordinates()[k].qd, ir::VariableKind::rate, k);
  }
  for (std::size_t k = 0; k < vars.inputs().size(); ++k) bind(vars.inputs()[k].symbol, ir::VariableKind::input, k);
  for (std::size_t k = 0; k < vars.parameters().size(); ++k)
    bind(vars.parameters()[k].symbol, ir::VariableKind::parameter, k);
  // the linearization's derivatives are taken at given accelerations and multipliers
  std::optional<SymbolicLinearization> linearization;
  if (options.linearization) {
    linearization = linearize_symbolic(model, eom);
    for (std::size_t k = 0; k < n; ++k) bind(vars.coordinates()[k].qdd, ir::VariableKind::acceleration, k);
    for (std::size_t r = 0; r < m; ++r) bind(linearization->lambda[r], ir::VariableKind::multiplier, r);
  }

  std::vector<FunctionSpec> functions;
  auto mass_targets = [&](FunctionSpec& f) {
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i; j < n; ++j) f.targets.push_back({{ir::Array::mass_matrix, i, j}, eom.mass_matrix(i, j)});
  };
  auto mirror_mass = [&](FunctionSpec& f) {
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        f.mirrors.push_back({{ir::Array::mass_matrix, j, i}, {ir::Array::mass_matrix, i, j}});
  };
  auto vector_targets = [&](FunctionSpec& f, ir::Array array, const GiNaC::matrix& v) {
    for (unsigned i = 0; i < v.rows(); ++i) f.targets.push_back({{array, i, 0}, v(i, 0)});
  };
  {
    FunctionSpec f{"mass_matrix", "M(q, t), symmetric positive (semi)definite", "void", "MassMatrix<Scalar>& M"};
    mass_targets(f);
    mirror_mass(f);
    functions.push_back(f);
  }
  {
    FunctionSpec f{"forcing", "F(q, qd, t, u): everything of Lagrange's equations except M qdd", "void", "Vector<Scalar>& F"};
    f.needs_qd = f.needs_u = true;
    vector_targets(f, ir::Array::forcing, eom.forcing);
    functions.push_back(f);
  }
  {
    FunctionSpec f{"mass_matrix_and_forcing", "M and F together, sharing their common subexpressions", "void",
                   "MassMatrix<Scalar>& M, Vector<Scalar>& F"};
    f.needs_qd = f.needs_u = true;
    mass_targets(f);
    vector_targets(f, ir::Array::forcing, eom.forcing);
    mirror_mass(f);
    functions.push_back(f);
  }
  {
    FunctionSpec f{"constraint_jacobian", "Xi(q, t) of the Pfaffian constraints Xi qd + Xi_t = 0", "void",
                   "ConstraintJacobian<Scalar>& Xi"};
    for (std::size_t i = 0; i < m; ++i)
      for (std::size_t j = 0; j < n; ++j) f.targets.push_back({{ir::Array::constraint_jacobian, i, j}, eom.constraint_jacobian(i, j)});
    functions.push_back(f);
  }
  {
    FunctionSpec f{"constraint_rate_term", "Xi_t(q, t)", "void", "ConstraintVector<Scalar>& Xi_t"};
    vector_targets(f, ir::Array::constraint_rate_term, eom.constraint_rate_term);
    functions.push_back(f);
  }
  {
    FunctionSpec f{"constraint_acceleration_term", "dXi/dt qd + dXi_t/dt, so that Xi qdd + b = 0", "void",
                   "ConstraintVector<Scalar>& b"};
    f.needs_qd = true;
    vector_targets(f, ir::Array::constraint_acceleration_term, eom.constraint_acceleration_term);
    functions.push_back(f);
  }
  {
    FunctionSpec f{"holonomic_residuals", "phi(q, t) of the holonomic constraints", "void", "HolonomicVector<Scalar>& phi"};
    vector_targets(f, ir::Array::holonomic_residuals, eom.holonomic_residuals);
    functions.push_back(f);
  }
  {
    FunctionSpec f{"kinetic_energy", "T(q, qd, t)", "Scalar", ""};
    f.needs_qd = true;
    f.scalar_result = "T";
    f.targets.push_back({{ir::Array::kinetic_energy, 0, 0}, eom.kinetic_energy});
    functions.push_back(f);
  }
  {
    FunctionSpec f{"potential_energy", "V(q, t)", "Scalar", ""};
    f.scalar_result = "V";
    f.targets.push_back({{ir::Array::potential_energy, 0, 0}, eom.potential_energy});
    functions.push_back(f);
  }
  {
    FunctionSpec f{"outputs", "the model's named outputs, in the order of output_names", "void", "OutputVector<Scalar>& y"};
    f.needs_qd = f.needs_u = true;
    for (std::size_t k = 0; k < ny; ++k) f.targets.push_back({{ir::Array::outputs, k, 0}, eom.output_component(k)});
    functions.push_back(f);
  }
  if (linearization) {
    const bool constrained = m > 0;
    FunctionSpec f{"linearization_terms",
                   constrained ? "K = dR/dq, D = dR/dqd, B_u = dF/du of R = M qdd - F - Xi^T lambda, and S_q, S_qd of "
                                 "S = Xi qdd + b, at the given qdd and lambda"
                               : "K = dR/dq, D = dR/dqd, B_u = dF/du of R = M qdd - F, at the given qdd",
                   "void",
                   constrained ? "const Vector<Scalar>& qdd, const ConstraintVector<Scalar>& lambda, MassMatrix<Scalar>& K, "
                                 "MassMatrix<Scalar>& D, InputMatrix<Scalar>& B_u, ConstraintJacobian<Scalar>& S_q, "
                                 "ConstraintJacobian<Scalar>& S_qd"
                               : "const Vector<Scalar>& qdd, MassMatrix<Scalar>& K, MassMatrix<Scalar>& D, "
                                 "InputMatrix<Scalar>& B_u"};
    f.needs_qd = f.needs_u = true;
    auto matrix_targets = [&](ir::Array array, const GiNaC::matrix& a) {
      for (unsigned i = 0; i < a.rows(); ++i)
        for (unsigned j = 0; j < a.cols(); ++j) f.targets.push_back({{array, i, j}, a(i, j)});
    };
    matrix_targets(ir::Array::stiffness, linearization->K);
    matrix_targets(ir::Array::damping, linearization->D);
    matrix_targets(ir::Array::input_matrix, linearization->B_u);
    if (constrained) {
      matrix_targets(ir::Array::acceleration_constraint_by_q, linearization->S_q);
      matrix_targets(ir::Array::acceleration_constraint_by_qd, linearization->S_qd);
    }
    functions.push_back(f);
  }

  EmittedModel result;
  std::string body;
  std::vector<const Subexpressions*> intermediates{&eom.subexpressions};
  if (linearization) intermediates.push_back(&linearization->derivatives);
  std::vector<std::vector<LoweringTarget>> all_targets;
  for (const FunctionSpec& f : functions) all_targets.push_back(f.targets);
  const std::vector<ir::Program> programs = lower_functions(all_targets, intermediates, names);
  for (std::size_t index = 0; index < functions.size(); ++index) {
    const FunctionSpec& f = functions[index];
    const ir::Program& program = programs[index];
    result.statistics.push_back({f.name, ir::count_operations_without_sharing(program), ir::count_operations(program)});
    std::string code;
    if (!f.scalar_result.empty()) code += fmt::format("    Scalar {} = Scalar(0);\n", f.scalar_result);
    code += print_cpp(program, print_options);
    // structural zeros are written as zeros, not computed
    std::set<ir::Target> computed;
    for (const ir::Assignment& a : program.outputs) computed.insert(a.target);
    for (const LoweringTarget& target : f.targets)
      if (!computed.count(target.target) && f.scalar_result.empty())
        code += fmt::format("    {} = Scalar(0);\n", cpp_target(target.target));
    for (const auto& [target, source] : f.mirrors)
      code += fmt::format("    {} = {};\n", cpp_target(target), computed.count(source) ? cpp_target(source) : "Scalar(0)");
    if (!f.scalar_result.empty()) code += fmt::format("    return {};\n", f.scalar_result);
    std::string signature = "const Scalar& t, const Vector<Scalar>& q";
    if (f.needs_qd) signature += ", const Vector<Scalar>& qd";
    if (f.needs_u) signature += ", const Inputs<Scalar>& u";
    signature += ", const Parameters<Scalar>& p";
    if (!f.arguments.empty()) signature += ", " + f.arguments;
    // every argument may go unused in a particular model (M of a pendulum ignores t)
    std::string marked;
    std::size_t start = 0;
    while (start < signature.size()) {
      std::size_t comma = signature.find(", ", start);
      if (comma == std::string::npos) comma = signature.size();
      marked += (start ? ", " : "") + std::string("[[maybe_unused]] ") + signature.substr(start, comma - start);
      start = comma + 2;
    }
    body += fmt::format("\n  /// {}\n  template <class Scalar>\n  static {} {}({}) noexcept {{\n", f.doc, f.returns, f.name, marked);
    body += math_using_declarations();
    body += code + "  }\n";
  }
  if (linearization) body += linearization_source(m > 0);

  // metadata
  auto name_list = [](const std::vector<std::string>& items) {
    std::string s;
    for (std::size_t i = 0; i < items.size(); ++i) s += fmt::format("{}\"{}\"", i ? ", " : "", cpp_string_contents(items[i]));
    return s;
  };
  std::vector<std::string> coordinate_names, input_names, parameter_names, constraint_names, output_names;
  std::string parameter_defaults, parameter_fields, field_pointers;
  for (const Coordinate& c : vars.coordinates()) coordinate_names.push_back(c.name);
  for (const Input& u : vars.inputs()) input_names.push_back(u.name);
  for (const Parameter& p : vars.parameters()) {
    parameter_names.push_back(p.name);
    parameter_defaults += fmt::format("{}{}", parameter_defaults.empty() ? "" : ", ", cpp_number(p.default_value, "double"));
    field_pointers += fmt::format("{}&{}", field_pointers.empty() ? "" : ", ", cpp_identifier(p.name));
    parameter_fields += fmt::format("    Scalar {} = {};{}\n", cpp_identifier(p.name), cpp_number(p.default_value, "Scalar"),
                                    p.unit.empty() ? "" : " // [" + cpp_comment_text(p.unit) + "]");
  }
  for (const Constraint& c : model.system.constraints()) constraint_names.push_back(c.name);
  // phi holds the holonomic rows of Xi in model order; the runtime stabilizes and projects them
  std::string holonomic_rows, independent_speeds;
  for (std::size_t i = 0; i < m; ++i)
    if (model.system.constraints()[i].kind == Constraint::Kind::holonomic)
      holonomic_rows += fmt::format("{}{}", holonomic_rows.empty() ? "" : ", ", i);
  for (std::size_t k : model.independent_speeds)
    independent_speeds += fmt::format("{}{}", independent_speeds.empty() ? "" : ", ", k);
  for (const Output& o : model.outputs) output_names.insert(output_names.end(), o.labels.begin(), o.labels.end());

  std::string fingerprint;  // content of the equations, printed: a stable hash of the model
  for (const auto& t : functions)
    for (const auto& target : t.targets) fingerprint += cpp_target(target.target);
  fingerprint += body;
  // the declared split changes how the runtime solves the model, not the equations; appended only
  // when there is one, so models without it keep their hash
  if (!model.independent_speeds.empty()) fingerprint += "independent_speeds " + independent_speeds;
  const std::string model_name = cpp_identifier(model.name);
  std::string h;
  h += fmt::format("// Generated by eomgen {} from {}. Do not edit: regenerate from the model.\n",
                   version, cpp_comment_text(options.source_name.empty() ? model.name : options.source_name));
  h += "// Needs only Eigen. Every function is templated on the scalar type, allocates nothing and\n"
       "// does not throw: safe to call from a real-time loop.\n";
  // linearization() factors M (Cholesky) and the KKT matrix (LU)
  h += "#pragma once\n\n";
  h += linearization ? "#include <Eigen/Cholesky>\n#include <Eigen/Core>\n#include <Eigen/LU>\n" : "#include <Eigen/Core>\n";
  h += "\n#include <array>\n#include <cmath>\n\n";
  h += fmt::format("namespace {} {{\nnamespace {} {{\n\n", cpp_identifier(options.outer_namespace), model_name);
  h += "struct Model {\n";
  h += fmt::format("  static constexpr int nq = {};  // coordinates (and rates)\n", n);
  h += fmt::format("  static constexpr int nu = {};  // inputs\n", vars.inputs().size());
  h += fmt::format("  static constexpr int nc = {};  // constraints (rows of Xi)\n", m);
  h += fmt::format("  static constexpr int nh = {};  // holonomic constraints (rows of phi)\n", nh);
  h += fmt::format("  static constexpr int np = {};  // parameters\n", vars.parameters().size());
  h += fmt::format("  static constexpr int ny = {};  // output components\n", ny);
  h += fmt::format("  static constexpr int ni = {};  // independent speeds declared in the model (0: none, null space "
                   "from QR of Xi)\n", model.independent_speeds.size());
  h += fmt::format("  static constexpr const char* name = \"{}\";\n", cpp_string_contents(model.name));
  h += fmt::format("  static constexpr const char* description = \"{}\";\n", cpp_string_contents(model.description));
  h += fmt::format("  static constexpr const char* generator_version = \"{}\";\n", version);
  h += fmt::format("  static constexpr const char* model_hash = \"{:016x}\";\n", content_hash(fingerprint));
  h += fmt::format("  static constexpr std::array<const char*, nq> coordinate_names{{{{{}}}}};\n", name_list(coordinate_names));
  h += fmt::format("  static constexpr std::array<const char*, nu> input_names{{{{{}}}}};\n", name_list(input_names));
  h += fmt::format("  static constexpr std::array<const char*, np> parameter_names{{{{{}}}}};\n", name_list(parameter_names));
  h += fmt::format("  static constexpr std::array<double, np> parameter_defaults{{{{{}}}}};\n", parameter_defaults);
  h += fmt::format("  static constexpr std::array<const char*, nc> constraint_names{{{{{}}}}};\n", name_list(constraint_names));
  h += fmt::format("  static constexpr std::array<int, nh> holonomic_rows{{{{{}}}}};  // row of Xi of each entry of phi\n",
                   holonomic_rows);
  h += fmt::format("  static constexpr std::array<int, ni> independent_speeds{{{{{}}}}};  // their coordinate indices\n",
                   independent_speeds);
  h += fmt::format("  static constexpr std::array<const char*, ny> output_names{{{{{}}}}};\n\n", name_list(output_names));
  h += "  template <class Scalar> using Vector = Eigen::Matrix<Scalar, nq, 1>;\n"
       "  template <class Scalar> using Inputs = Eigen::Matrix<Scalar, nu, 1>;\n"
       "  template <class Scalar> using MassMatrix = Eigen::Matrix<Scalar, nq, nq>;\n"
       "  template <class Scalar> using ConstraintJacobian = Eigen::Matrix<Scalar, nc, nq>;\n"
       "  template <class Scalar> using ConstraintVector = Eigen::Matrix<Scalar, nc, 1>;\n"
       "  template <class Scalar> using HolonomicVector = Eigen::Matrix<Scalar, nh, 1>;\n"
       "  template <class Scalar> using OutputVector = Eigen::Matrix<Scalar, ny, 1>;\n";
  if (linearization)
    h += "  template <class Scalar> using InputMatrix = Eigen::Matrix<Scalar, nq, nu>;\n"
         "  template <class Scalar> using StateMatrix = Eigen::Matrix<Scalar, 2 * nq, 2 * nq>;\n"
         "  template <class Scalar> using StateInputMatrix = Eigen::Matrix<Scalar, 2 * nq, nu>;\n";
  h += "\n";
  h += "  /// Parameters, defaulted to the model's values.\n  template <class Scalar>\n  struct Parameters {\n";
  h += parameter_fields;
  h += "    /// The fields in the order of parameter_names, to set parameters by index or name.\n";
  h += fmt::format("    std::array<Scalar*, np> fields() noexcept {{ return {{{{{}}}}}; }}\n", field_pointers);
  h += "  };\n";
  h += body;
  h += "};\n\n";
  h += fmt::format("}}  // namespace {}\n}}  // namespace {}\n", model_name, cpp_identifier(options.outer_namespace));
  result.header = h;
  return result;
}

}  // namespace eomgen
