// The eomgen command: runs the subcommand the command line chose (its options are in
// command_line.cpp), loads the model, calls the library and prints. No algebra lives here.
//
// Exit status: 0 success; 1 an error in the model or at the requested state (eomgen::Error;
// a model file error reads "file:line:col: error: ..."); 2 a malformed command line; 3 the data
// (simulate's CSV, a sweep's table) was written in full but its plot was not. Interrupted
// (SIGINT, SIGTERM, SIGHUP), it removes its temporary files and dies by the signal
// (interruption.hpp).
#include <CLI/CLI.hpp>
#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstring>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "eomgen/codegen/emit_model.hpp"
#include "eomgen/report/equation_printer.hpp"
#include "eomgen/derivation/dimension_check.hpp"
#include "eomgen/derivation/equations_of_motion.hpp"
#include "eomgen/base/error.hpp"
#include "eomgen/derivation/linearization.hpp"
#include "eomgen/derivation/model_equations.hpp"
#include "eomgen/language/model_file.hpp"
#include "eomgen/derivation/header_functions.hpp"
#include "eomgen/derivation/numeric_evaluation.hpp"
#include "eomgen/derivation/operating_point.hpp"
#include "eomgen/base/version.hpp"
#include "eomgen/symbolic/double_evaluator.hpp"
#include "eomgen/urdf/urdf_import.hpp"
#include "eomgen/symbolic/ordered_text.hpp"
#include "command_line.hpp"
#include "command_values.hpp"
#include "linearize_command.hpp"
#include "model_loading.hpp"
#include "file_output.hpp"
#include "interruption.hpp"
#include "simulate_command.hpp"

namespace {

using eomgen::tools::join;
using eomgen::tools::json_document;
using eomgen::tools::json_rows;
using eomgen::tools::matrix_text;
using eomgen::tools::number;
using eomgen::tools::Options;
using eomgen::tools::parse_assignments;
using eomgen::tools::state_and_parameters;
using eomgen::tools::UsageError;

eomgen::Model load(const Options& o) { return eomgen::tools::load_command_model(o); }

// ---- import ----

void run_import(const Options& o) {
  eomgen::tools::check_output_files({{"-o", o.output_path}}, o.model_path);
  eomgen::urdf::ImportOptions options = eomgen::tools::import_options(o);
  // mesh files named relative to the URDF are named relative to the written model (standard
  // output: the current directory, where `> robot.eom` puts it)
  options.model_directory = o.output_path.empty() ? std::string(".")
                                                  : std::filesystem::absolute(o.output_path).parent_path().string();
  const eomgen::urdf::ImportResult imported = eomgen::urdf::import_urdf(o.model_path, options);
  // the text must read as the model it stands for before it is written anywhere
  eomgen::tools::print_notes(eomgen::parse_model(imported.text, o.model_path + " (as imported)"));
  for (const std::string& repair : imported.repairs) std::cerr << "eomgen: --repair-inertia: " << repair << "\n";
  for (const std::string& lock : imported.locked) std::cerr << "eomgen: --fix-massless-joints: " << lock << "\n";
  if (o.output_path.empty())
    std::cout << imported.text << std::flush;
  else
    eomgen::tools::write_atomically(o.output_path, imported.text);
}

void run_check(const Options& o) {
  const eomgen::Model model = load(o);
  const eomgen::MechanicalSystem& s = model.system;
  const eomgen::Variables& v = s.variables();
  // deriving is cheap (linear in the model) and catches what only the derivation can see
  const eomgen::EquationsOfMotion eom = eomgen::derive_equations(s);
  eomgen::check_dimensions(eom, v, model.dimensions);
  std::vector<std::string> coordinates, holonomic, nonholonomic, bodies, particles, inputs, outputs;
  for (const auto& c : v.coordinates()) coordinates.push_back(c.name);
  for (const auto& c : s.constraints())
    (c.kind == eomgen::Constraint::Kind::holonomic ? holonomic : nonholonomic).push_back(c.name);
  for (const auto& b : s.rigid_bodies()) bodies.push_back(b.name);
  for (const auto& p : s.particles()) particles.push_back(p.name);
  for (const auto& u : v.inputs()) inputs.push_back(u.name);
  for (const auto& out : model.outputs)
    outputs.push_back(out.components.size() == 1 ? out.name : fmt::format("{} ({} components)", out.name, out.components.size()));
  const std::size_t n = coordinates.size(), m = s.constraints().size();
  std::cout << "Model: " << model.name << "\n";
  if (!model.description.empty()) std::cout << "Description: " << model.description << "\n";
  std::cout << fmt::format("Coordinates (n = {}): {}\n", n, join(coordinates));
  std::cout << fmt::format("Constraints (m = {}):\n  holonomic ({}): {}\n  nonholonomic ({}): {}\n", m,
                           holonomic.size(), join(holonomic), nonholonomic.size(), join(nonholonomic));
  std::cout << fmt::format("Degrees of freedom (n - m): {}\n", static_cast<long long>(n) - static_cast<long long>(m));
  if (!model.independent_speeds.empty()) {
    std::vector<std::string> independent;
    for (std::size_t k : model.independent_speeds) independent.push_back(coordinates[k] + "_dot");
    std::cout << fmt::format("Independent speeds ({}): {}\n", independent.size(), join(independent));
  }
  std::cout << fmt::format("Bodies ({}): {}\nParticles ({}): {}\n", bodies.size(), join(bodies), particles.size(),
                           join(particles));
  std::cout << fmt::format("Parameters ({}):", v.parameters().size()) << (v.parameters().empty() ? " none" : "") << "\n";
  for (const auto& p : v.parameters())
    std::cout << fmt::format("  {} = {}", p.name, p.default_value) << (p.unit.empty() ? "" : " [" + p.unit + "]") << "\n";
  if (!v.derived_parameters().empty())
    std::cout << fmt::format("Derived parameters ({}):\n", v.derived_parameters().size());
  for (const eomgen::DerivedParameter& d : v.derived_parameters())
    std::cout << fmt::format("  {} = {} = {}", d.name, eomgen::ordered_text(d.definition), d.default_value)
              << (d.unit.empty() ? "" : " [" + d.unit + "]") << "\n";
  if (!model.constants.empty()) {
    std::vector<std::string> constants;
    for (const auto& [name, value] : model.constants) constants.push_back(fmt::format("{} = {}", name, value));
    std::cout << fmt::format("Constants ({}): {}\n", constants.size(), join(constants));
  }
  std::cout << fmt::format("Inputs ({}): {}\nOutputs ({}): {}\n", inputs.size(), join(inputs), outputs.size(),
                           join(outputs));
  std::cout << fmt::format("Derivation: ok ({} shared intermediates)\n", eom.subexpressions.size());
  if (!model.dimensions.empty()) std::cout << "Units: consistent (the model, then the derived equations)\n";
}

void run_derive(const Options& o) {
  eomgen::PrintOptions print;
  static const std::map<std::string, eomgen::EquationFormat> formats = {
      {"text", eomgen::EquationFormat::text},
      {"latex", eomgen::EquationFormat::latex},
      {"markdown", eomgen::EquationFormat::markdown}};
  print.format = formats.at(o.format);  // CLI11 checked membership
  if (!o.only.empty()) {
    try {
      print.parts = eomgen::parse_equation_parts(o.only);
    } catch (const eomgen::Error& e) {
      throw UsageError(fmt::format("--only: {}", e.what()));
    }
  }
  eomgen::tools::check_output_files({{"-o", o.output_path}}, o.model_path);
  if (o.shared) print.intermediates = eomgen::IntermediateForm::shared;
  if (o.expand) print.intermediates = eomgen::IntermediateForm::written_out;
  print.expand_derived_parameters = o.expand_parameters;
  const eomgen::Model model = load(o);
  const eomgen::ModelEquations eom = eomgen::derive_equations(model);
  // render completely before writing anything, so an error leaves no output behind
  std::optional<eomgen::HeaderFunctions> functions;
  if (print.parts.needs_header_functions()) {
    eomgen::HeaderOptions header;
    header.base_regressor = o.regressor == "base";
    functions = eomgen::derive_header_functions(model, eom, nullptr, header);
  }
  const std::string text = eomgen::format_equations(model, eom, print, functions ? &*functions : nullptr);
  if (o.output_path.empty())
    std::cout << text << std::flush;
  else
    eomgen::tools::write_atomically(o.output_path, text);
}

// ---- generate ----

std::string statistics_table(const std::vector<eomgen::FunctionStatistics>& statistics) {
  std::string out = fmt::format("{:<30} {:>12} {:>12} {:>8} {:>8} {:>8} {:>8}\n", "function", "unoptimized",
                                "optimized", "adds", "muls", "divs", "calls");
  // the unoptimized count of a deep tree passes 2^64 and stays at the largest count (ir.cpp)
  const auto count = [](std::uint64_t n) {
    return n == std::numeric_limits<std::uint64_t>::max() ? std::string(">1.8e19") : std::to_string(n);
  };
  for (const auto& s : statistics)
    out += fmt::format("{:<30} {:>12} {:>12} {:>8} {:>8} {:>8} {:>8}\n", s.function, count(s.unoptimized.total()),
                       s.optimized.total(), s.optimized.additions, s.optimized.multiplications,
                       s.optimized.divisions, s.optimized.calls);
  return out;
}

std::string estimate_or_not_tried(double estimate) {
  // NaN: not derived, or given up once larger than another form could be
  return std::isnan(estimate) ? std::string("not derived") : fmt::format("{:.0f}", estimate);
}

// which of the derivations of M and F was emitted, and the estimates of all three
// (KinematicsResolution, composite_body.hpp)
std::string resolution_line(const eomgen::EquationsOfMotion& eom, const eomgen::EmittedModel& emitted) {
  const bool local = eom.resolution == eomgen::KinematicsResolution::local;
  const std::string kept = emitted.mass_matrix_from_recursions ? "composite body and Newton-Euler"
                           : local                             ? "local frames"
                                                               : "inertial";
  return fmt::format("M and F: {} (estimated operations: local frames {}, inertial {}, composite body and "
                     "Newton-Euler {})\n",
                     kept, estimate_or_not_tried(eom.estimated_operations_local),
                     estimate_or_not_tried(eom.estimated_operations_inertial),
                     estimate_or_not_tried(emitted.estimated_operations_recursions));
}

// why there is no forward_dynamics(), or how it compares with M, F and the Cholesky solve
std::string forward_dynamics_line(const eomgen::EmittedModel& emitted) {
  if (!emitted.no_forward_dynamics.empty()) return "no forward_dynamics: " + emitted.no_forward_dynamics + "\n";
  return fmt::format("forward_dynamics: {:.0f} operations per call against {:.0f} for M, F and their Cholesky solve: "
                     "the runtime takes {}\n",
                     emitted.forward_dynamics_operations, emitted.mass_matrix_path_operations,
                     emitted.prefers_forward_dynamics ? "forward_dynamics" : "M and F");
}

// with a linearization: which form forward_dynamics_derivatives() took, or why there is none
std::string forward_dynamics_derivatives_line(const eomgen::EmittedModel& emitted) {
  if (!emitted.no_forward_dynamics_derivatives.empty())
    return "forward_dynamics_derivatives not derived symbolically: " + emitted.no_forward_dynamics_derivatives + "\n";
  if (!emitted.forward_dynamics_derivatives) return {};
  std::string estimates;
  for (const auto& [form, operations] : emitted.forward_dynamics_derivatives_estimates)
    estimates += fmt::format("{}{} {:.0f}", estimates.empty() ? "" : ", ", eomgen::to_string(form), operations);
  return fmt::format("forward_dynamics_derivatives: {} (estimated operations: {})\n",
                     eomgen::to_string(*emitted.forward_dynamics_derivatives), estimates);
}

void run_generate(const Options& o) {
  eomgen::tools::check_output_files({{"-o", o.output_path}}, o.model_path);
  using clock = std::chrono::steady_clock;
  const auto milliseconds = [](clock::duration d) { return std::chrono::duration<double, std::milli>(d).count(); };
  const auto start = clock::now();
  const eomgen::Model model = load(o);
  const auto loaded = clock::now();
  const eomgen::ModelEquations eom = eomgen::derive_equations(model);
  const auto derived = clock::now();
  eomgen::EmitOptions emit;
  emit.outer_namespace = o.outer_namespace;
  emit.share_subexpressions = !o.no_cse;
  // the file name only: a path would make the header differ between checkouts
  emit.source_name = std::filesystem::path(o.model_path).filename().string();
  std::optional<eomgen::SymbolicLinearization> linearization;
  if (o.emit_linearization) linearization = eomgen::linearize_symbolic(model, eom);
  eomgen::HeaderOptions header;
  header.base_regressor = o.regressor == "base";
  const eomgen::EmittedModel emitted = eomgen::emit_model(
      model, eomgen::derive_header_functions(model, eom, linearization ? &*linearization : nullptr, header), emit);
  // wall times inside the process (what a build step or a benchmark against an in-process
  // peer should compare), not the program's start-up
  const std::string stats =
      o.stats ? statistics_table(emitted.statistics) + resolution_line(eom, emitted) +
                    forward_dynamics_line(emitted) + forward_dynamics_derivatives_line(emitted) +
                    fmt::format("time [ms]: parse {:.3f}, derive {:.3f}, emit {:.3f}\n", milliseconds(loaded - start),
                                milliseconds(derived - loaded), milliseconds(clock::now() - derived))
              : std::string();
  if (o.output_path.empty()) {
    std::cout << emitted.header << std::flush;
    std::cerr << stats;
  } else {
    eomgen::tools::write_atomically(o.output_path, emitted.header);
    std::cout << stats;
  }
}

// ---- eval ----

void print_matrix(const std::string& title, const Eigen::MatrixXd& a) { std::cout << matrix_text(title, a); }

void print_named(const std::string& title, const std::vector<std::pair<std::string, double>>& values) {
  std::cout << title << ":" << (values.empty() ? " none" : "") << "\n";
  for (const auto& [name, value] : values) std::cout << "  " << name << " = " << number(value) << "\n";
}

/// eval evaluates where it is told, on the constraints or not; where not, it says which
/// constraint the state violates and by how much (relative to the size of the row's terms, as
/// assembly measures it), since M, F and qdd there belong to no motion of the model.
void warn_of_violated_constraints(const eomgen::Model& model, const eomgen::NumericEquations& eq,
                                  const eomgen::NamedValues& values) {
  const auto& constraints = model.system.constraints();
  const auto& coordinates = model.system.variables().coordinates();
  Eigen::VectorXd q(static_cast<Eigen::Index>(coordinates.size())), qd(q.size());
  for (std::size_t j = 0; j < coordinates.size(); ++j) {
    const auto at = [&](const std::string& name) {
      const auto it = values.find(name);
      return it == values.end() ? 0.0 : it->second;
    };
    q(static_cast<Eigen::Index>(j)) = at(coordinates[j].name);
    qd(static_cast<Eigen::Index>(j)) = at(coordinates[j].name + "_dot");
  }
  Eigen::Index h = 0;
  for (std::size_t r = 0; r < constraints.size(); ++r) {
    const auto row = static_cast<Eigen::Index>(r);
    const Eigen::RowVectorXd xi = eq.constraint_jacobian.row(row);
    if (constraints[r].kind == eomgen::Constraint::Kind::holonomic) {
      const double phi = eq.holonomic_residuals(h++);
      if (std::abs(phi) > eomgen::operating_point_tolerance * (1 + xi.cwiseAbs().dot((q.cwiseAbs().array() + 1).matrix())))
        std::cerr << fmt::format("eomgen: warning: the state violates the constraint '{}': phi = {:.3g}; the values "
                                 "below belong to no motion of {} (linearize and simulate bring a state onto the "
                                 "constraints first)\n",
                                 constraints[r].name, phi, model.name);
    }
    const double rate = xi.dot(qd) + eq.constraint_rate_term(row);
    if (std::abs(rate) > eomgen::operating_point_tolerance *
                             (1 + xi.cwiseAbs().dot(qd.cwiseAbs()) + std::abs(eq.constraint_rate_term(row))))
      std::cerr << fmt::format("eomgen: warning: the state violates the constraint '{}': Xi qd + Xi_t = {:.3g}; the "
                               "values below belong to no motion of {} (linearize and simulate bring a state onto the "
                               "constraints first)\n",
                               constraints[r].name, rate, model.name);
  }
}

void run_eval(const Options& o) {
  if (o.format != "text" && o.format != "json") throw UsageError("--format: eval prints 'text' or 'json'");
  const eomgen::Model model = load(o);
  const eomgen::NamedValues values = state_and_parameters(o.at, o.set, model);
  const eomgen::Variables& v = model.system.variables();
  const eomgen::ModelEquations eom = eomgen::derive_equations(model);
  const eomgen::NumericEquations eq = eomgen::evaluate_equations(model, eom, values);
  warn_of_violated_constraints(model, eq, values);
  eomgen::AccelerationSolution sol;
  try {
    sol = eomgen::solve_accelerations(eq);
  } catch (const eomgen::Error& e) {
    if (model.system.constraints().empty())
      throw eomgen::Error("solving M qdd = F: " + eomgen::explain_singular_mass_matrix(model, eom, values, eq.mass_matrix));
    // the usual cause is a state off the constraints (the all-zero default for a quaternion)
    if (eq.holonomic_residuals.size() == 0 || eq.holonomic_residuals.norm() < 1e-9) throw;
    throw eomgen::Error(fmt::format("{}; note that the state violates the holonomic constraints: "
                                    "|phi| = {:.3g}", e.what(), eq.holonomic_residuals.norm()));
  }

  // the state and parameters actually used, in declaration order
  auto value_of = [&](const std::string& name, double fallback) {
    const auto it = values.find(name);
    return it == values.end() ? fallback : it->second;
  };
  std::vector<std::pair<std::string, double>> state{{"t", value_of("t", 0.0)}}, parameters, qdd, lambda;
  std::vector<std::string> coordinates, constraints;
  for (const auto& c : v.coordinates()) {
    coordinates.push_back(c.name);
    state.emplace_back(c.name, value_of(c.name, 0.0));
    state.emplace_back(c.qd.get_name(), value_of(c.qd.get_name(), 0.0));
    qdd.emplace_back(c.qdd.get_name(), sol.qdd(static_cast<Eigen::Index>(qdd.size())));
  }
  for (const auto& u : v.inputs()) state.emplace_back(u.name, value_of(u.name, 0.0));
  for (const auto& p : v.parameters()) parameters.emplace_back(p.name, value_of(p.name, p.default_value));
  // what the derived parameters came to with these parameters
  std::vector<std::pair<std::string, double>> derived;
  eomgen::DoubleEvaluator at_parameters;
  for (const auto& p : v.parameters()) at_parameters.set(p.symbol, value_of(p.name, p.default_value));
  v.evaluate_derived_parameters(at_parameters);
  for (const eomgen::DerivedParameter& d : v.derived_parameters())
    derived.emplace_back(d.name, at_parameters.value(d.symbol, "derived parameter '" + d.name + "'"));
  for (const auto& c : model.system.constraints()) {
    constraints.push_back(c.name);
    lambda.emplace_back(c.name, sol.lambda(static_cast<Eigen::Index>(lambda.size())));
  }
  // the functions for controllers at this state, the regressor at the accelerations above
  const eomgen::HeaderFunctions functions = eomgen::derive_header_functions(model, eom);
  const eomgen::NumericControllerFunctions controller =
      eomgen::evaluate_controller_functions(model, eom, functions, values, sol.qdd);

  if (o.format == "json") {
    using json = nlohmann::ordered_json;  // keys in a fixed, readable order
    auto column = [](const Eigen::VectorXd& x) { return json(std::vector<double>(x.data(), x.data() + x.size())); };
    auto object = [](const std::vector<std::pair<std::string, double>>& values) {
      json out = json::object();
      for (const auto& [name, value] : values) out[name] = value;
      return out;
    };
    json j;
    j["model"] = model.name;
    j["coordinates"] = coordinates;
    j["constraints"] = constraints;
    j["state"] = object(state);
    j["parameters"] = object(parameters);
    if (!derived.empty()) j["derived_parameters"] = object(derived);
    j["M"] = json_rows(eq.mass_matrix);
    j["F"] = column(eq.forcing);
    j["Xi"] = json_rows(eq.constraint_jacobian);
    j["Xi_t"] = column(eq.constraint_rate_term);
    j["b"] = column(eq.constraint_acceleration_term);
    j["phi"] = column(eq.holonomic_residuals);
    j["T"] = eq.kinetic_energy;
    j["V"] = eq.potential_energy;
    j["qdd"] = column(sol.qdd);
    j["lambda"] = column(sol.lambda);
    j["outputs"] = object(eq.outputs);
    if (controller.gravity_forces.size() > 0) {
      j["G"] = column(controller.gravity_forces);
      j["C"] = json_rows(controller.coriolis_matrix);
    }
    json jacobians = json::object();
    for (const auto& jac : controller.output_jacobians)
      jacobians[jac.output] = json{{"J", json_rows(jac.jacobian)}, {"Jdot_qd", column(jac.bias)}};
    j["output_jacobians"] = jacobians;
    if (controller.regressor.size() > 0) {
      j["Y"] = json_rows(controller.regressor);
      json pi = json::object();
      for (std::size_t k = 0; k < functions.inertial_parameter_names.size(); ++k)
        pi[functions.inertial_parameter_names[k]] = controller.inertial_parameters(static_cast<Eigen::Index>(k));
      j["pi"] = pi;
    }
    std::cout << json_document(j);
    return;
  }
  std::cout << "Model " << model.name << "\n";
  print_named("State", state);
  print_named("Parameters", parameters);
  if (!derived.empty()) print_named("Derived parameters", derived);
  print_matrix("M", eq.mass_matrix);
  print_matrix("F", eq.forcing);
  if (!constraints.empty()) {
    std::cout << "Constraints: " << join(constraints) << "\n";
    print_matrix("Xi", eq.constraint_jacobian);
    print_matrix("Xi_t", eq.constraint_rate_term);
    print_matrix("b = dXi/dt qd + dXi_t/dt", eq.constraint_acceleration_term);
    print_matrix("phi", eq.holonomic_residuals);
  }
  std::cout << "T = " << number(eq.kinetic_energy) << "\nV = " << number(eq.potential_energy) << "\n";
  print_named("Outputs", eq.outputs);
  print_named("Accelerations qdd", qdd);
  if (!constraints.empty()) print_named("Multipliers lambda", lambda);
  if (controller.gravity_forces.size() > 0) {
    print_matrix("G = dV/dq", controller.gravity_forces);
    print_matrix("C (Coriolis matrix)", controller.coriolis_matrix);
  }
  for (const auto& jac : controller.output_jacobians) {
    print_matrix("J of " + jac.output, jac.jacobian);
    print_matrix("Jdot qd of " + jac.output, jac.bias);
  }
  if (controller.regressor.size() > 0) {
    print_matrix("Y (regressor, at qdd above)", controller.regressor);
    std::vector<std::pair<std::string, double>> pi;
    for (std::size_t k = 0; k < functions.inertial_parameter_names.size(); ++k)
      pi.emplace_back(functions.inertial_parameter_names[k], controller.inertial_parameters(static_cast<Eigen::Index>(k)));
    print_named("Inertial parameters pi", pi);
  }
}

// ---- simulate ----

int run_simulate(Options& o) {
  const eomgen::Model model = load(o);
  eomgen::tools::SimulateRequest& r = o.simulate;
  r.model_path = o.model_path;
  r.parameters = parse_assignments(o.set, "--set");
  r.initial = parse_assignments(o.init, "--init");
  r.guesses = eomgen::tools::state_guesses(o.guesses, r.initial, "--init", model);
  r.inputs = parse_assignments(o.inputs, "--input");
  r.plot = !o.no_plot;
  return eomgen::tools::run_simulate(model, r);
}

// ---- python ----

int run_python(Options& o) {
  const eomgen::Model model = load(o);
  o.python.model_path = o.model_path;
  return eomgen::tools::run_python(model, o.python);
}

// runs the parsed subcommand and maps its errors to exit statuses (see the file comment)
int run_command(const std::vector<std::pair<CLI::App*, int (*)(Options&)>>& commands, Options& o) {
  try {
    for (const auto& [command, run] : commands)
      if (command->parsed()) return run(o);
  } catch (const UsageError& e) {
    std::cerr << "eomgen: error: " << e.what() << "\n";
    return 2;
  } catch (const eomgen::SourceError& e) {
    std::cerr << e.what() << "\n";  // already "file:line:col: error: ..."
    return 1;
  } catch (const eomgen::Error& e) {
    std::cerr << "eomgen: error: " << e.what() << "\n";
    return 1;
  } catch (const eomgen::InternalError& e) {  // an invariant of the generator: says where the bug is
    std::cerr << "eomgen: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {  // GiNaC or the system: not the user's fault, but still fatal
    std::cerr << "eomgen: internal error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

// a subcommand that prints and succeeds, as a command of run_command
template <void (*run)(const Options&)>
int succeeds(Options& o) {
  run(o);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  eomgen::tools::interruption::install();  // first: before any thread, child or temporary file
  CLI::App app{"eomgen: equations of motion M(q) qdd = F(q, qd, t, u) + Xi^T lambda from a model file", "eomgen"};
  app.set_version_flag("--version", std::string("eomgen ") + eomgen::version);
  app.require_subcommand(1);
  app.footer(
      "Exit status: 0 success, 1 error in the model or at the state, 2 usage error, 3 the data (CSV, table) was written "
      "in full but its plot was not; on SIGINT or SIGTERM eomgen removes its temporary files and dies by the signal.");
  Options o;
  namespace tools = eomgen::tools;
  const std::vector<std::pair<CLI::App*, int (*)(Options&)>> commands = {
      {tools::add_import_command(app, o), succeeds<run_import>},
      {tools::add_check_command(app, o), succeeds<run_check>},
      {tools::add_derive_command(app, o), succeeds<run_derive>},
      {tools::add_eval_command(app, o), succeeds<run_eval>},
      {tools::add_generate_command(app, o), succeeds<run_generate>},
      {tools::add_linearize_command(app, o), [](Options& opts) { return eomgen::tools::run_linearize(opts); }},
      {tools::add_simulate_command(app, o), run_simulate},
      {tools::add_python_command(app, o), run_python},
  };
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version: printed to stdout
    std::cerr << "eomgen: error: " << e.what() << "\nRun with --help for more information.\n";
    return 2;
  }
  return run_command(commands, o);
}
