#include "command_line.hpp"

#include <fmt/format.h>

#include <cmath>

#include "eomgen/codegen/cpp_identifier.hpp"

namespace eomgen::tools {

namespace {

// A time, a step or a tolerance: a finite number above zero ("nan" and "inf" parse as doubles,
// and CLI11's PositiveNumber lets them through)
const CLI::Validator positive_finite(
    [](std::string& text) {
      double value = 0;
      if (!CLI::detail::lexical_cast(text, value)) return "expected a number, got '" + text + "'";
      if (!std::isfinite(value) || !(value > 0)) return "expected a finite number above 0, got " + text;
      return std::string();
    },
    "POSITIVE");

// the generated code's outer namespace is written as given, so it must be a name the mapping of
// model names leaves alone (docs/model-language.md, "Names in generated code")
const CLI::Validator cpp_namespace(
    [](std::string& text) {
      if (eomgen::cpp_identifier(text) == text) return std::string();
      return "expected a C++ identifier (a letter, then letters, digits and single _, not a keyword, a macro or a "
             "name the generated header uses), got '" + text + "'";
    },
    "IDENTIFIER");

// the options every subcommand has: the model file and --define
// how a URDF file becomes a model (urdf_import.hpp)
void add_import_flags(CLI::App* sub, Options& o) {
  sub->add_flag("--repair-inertia", o.repair_inertia,
                "URDF: replace an inertia no body has by one that is (each listed) instead of refusing it");
  sub->add_flag("--floating-base", o.floating_base,
                "URDF: the root link flies free (x, y, z and 3-2-1 Euler angles) instead of being fixed to the ground");
  sub->add_flag("--fix-massless-joints", o.fix_massless_joints,
                "URDF: make fixed the moving joints that move only links without mass, instead of refusing them");
}

void add_model_options(CLI::App* sub, Options& o) {
  sub->add_option("MODEL", o.model_path, "Model file (.eom), or a robot's URDF file (.urdf)")
      ->required()
      ->check(CLI::ExistingFile);
  add_import_flags(sub, o);
  sub->add_option("-D,--define", o.defines, "Override a 'const' of the model: NAME=VALUE (repeatable)")
      ->delimiter(',')
      ->type_name("NAME=VALUE");
}

// simulate and python share one cache of compiled programs (cached_build.hpp)
void add_cache_option(CLI::App* sub, std::string& dir, const std::string& what) {
  sub->add_option("--cache-dir", dir,
                  "Where compiled " + what + " are kept (default: $EOMGEN_CACHE_DIR, else ~/.cache/eomgen)")
      ->type_name("DIR");
}

// --set NAME=VALUE, repeatable; `help` says what it sets
void add_parameter_option(CLI::App* sub, std::vector<std::string>& set, const std::string& help) {
  sub->add_option("--set", set, help)->delimiter(',')->type_name("NAME=VALUE");
}

// the integrator options take their names and help from the integrator registry
void add_integrator_options(CLI::App* simulate, SimulateRequest& r) {
  const std::string fixed_step = integrator_names(false, "/"), adaptive = integrator_names(true, "/");
  simulate->add_option("--method", r.method, method_help())->check(CLI::IsMember(integrator_names()));
  simulate->add_option("--dt", r.step, fmt::format("Step of {} [s] (default 1e-3)", fixed_step))
      ->check(positive_finite);
  simulate->add_option("--rtol", r.rtol, fmt::format("Relative tolerance of {} (default 1e-8)", adaptive))
      ->check(positive_finite);
  simulate->add_option("--atol", r.atol, fmt::format("Absolute tolerance of {} (default 1e-10)", adaptive))
      ->check(positive_finite);
}

}  // namespace

urdf::ImportOptions import_options(const Options& o) {
  if ((o.repair_inertia || o.floating_base || o.fix_massless_joints) && !urdf::is_urdf_path(o.model_path))
    throw UsageError(fmt::format("{}: applies to a robot's URDF file (.urdf), and '{}' is a model file",
                                 o.repair_inertia  ? "--repair-inertia"
                                 : o.floating_base ? "--floating-base"
                                                   : "--fix-massless-joints",
                                 o.model_path));
  urdf::ImportOptions options;
  options.repair_inertia = o.repair_inertia;
  options.floating_base = o.floating_base;
  options.fix_massless_joints = o.fix_massless_joints;
  return options;
}

CLI::App* add_import_command(CLI::App& app, Options& o) {
  CLI::App* import = app.add_subcommand("import", "Write a robot's URDF file as a model (.eom) to read and edit");
  import->add_option("ROBOT", o.model_path, "URDF file")->required()->check(CLI::ExistingFile);
  import->add_option("-o,--output", o.output_path, "Write to FILE instead of standard output (atomically)")
      ->type_name("FILE");
  add_import_flags(import, o);
  return import;
}

CLI::App* add_check_command(CLI::App& app, Options& o) {
  CLI::App* check = app.add_subcommand("check", "Check a model and summarize it");
  add_model_options(check, o);
  return check;
}

CLI::App* add_derive_command(CLI::App& app, Options& o) {
  CLI::App* derive = app.add_subcommand("derive", "Derive and print the equations of motion");
  derive->alias("show");
  add_model_options(derive, o);
  derive->add_option("-f,--format", o.format, "Output format")
      ->check(CLI::IsMember({"text", "latex", "markdown"}))
      ->capture_default_str();
  derive->add_option("--only", o.only, "Parts to print, comma-separated: M,F,Xi,Xi_t,b,phi,T,V,outputs; for "
                     "controllers (only when named) tau,g,C,J,regressor")
      ->type_name("PARTS");
  derive->add_option("--regressor", o.regressor, "With --only regressor: full, or base (the identifiable base "
                     "parameters and their combinations)")
      ->check(CLI::IsMember({"full", "base"}))
      ->capture_default_str();
  CLI::Option* shared = derive->add_flag("--intermediates", o.shared,
                                         "Print in terms of shared intermediates, then their definitions");
  derive->add_flag("--expand", o.expand, "Write intermediates out even for a large system (may be slow)")
      ->excludes(shared);
  derive->add_flag("--expand-parameters", o.expand_parameters,
                   "Write derived parameters out in the parameters they are defined from (may be large)");
  derive->add_option("-o,--output", o.output_path, "Write to FILE instead of standard output (atomically)")
      ->type_name("FILE");
  return derive;
}

CLI::App* add_eval_command(CLI::App& app, Options& o) {
  CLI::App* eval = app.add_subcommand("eval", "Evaluate the equations numerically and solve for qdd, lambda");
  add_model_options(eval, o);
  eval->add_option("--at", o.at, "State: q1=0.1,q1_dot=0.3,u=1,t=0 (others are 0)")
      ->delimiter(',')
      ->type_name("NAME=VALUE,...");
  add_parameter_option(eval, o.set, "Override a parameter's default: NAME=VALUE (repeatable)");
  eval->add_option("-f,--format", o.format, "Output format")->check(CLI::IsMember({"text", "json"}))->capture_default_str();
  return eval;
}

CLI::App* add_generate_command(CLI::App& app, Options& o) {
  CLI::App* generate = app.add_subcommand("generate", "Emit an optimized C++ header (Eigen only) for the model");
  add_model_options(generate, o);
  generate->add_option("-o,--output", o.output_path, "Write to FILE instead of standard output (atomically)")
      ->type_name("FILE");
  generate->add_option("--namespace", o.outer_namespace, "Outer namespace of the generated code")
      ->check(cpp_namespace)
      ->capture_default_str();
  generate->add_flag("--no-cse", o.no_cse,
                     "Write every output as its own expression tree, without shared temporaries (for comparison)");
  generate->add_flag("--stats", o.stats,
                     "Print operation counts per function, without and with shared subexpressions");
  generate->add_flag("--linearization", o.emit_linearization,
                     "Also emit linearization_terms, the exact derivatives from which eomrt::linearization "
                     "gives A and B about any operating point (for gain scheduling)");
  generate->add_option("--regressor", o.regressor,
                       "full: the regressor on ten inertial parameters per body; base: on the identifiable base "
                       "parameters, their combinations found at generation (derive --only regressor prints them)")
      ->check(CLI::IsMember({"full", "base"}))
      ->capture_default_str();
  return generate;
}

CLI::App* add_linearize_command(CLI::App& app, Options& o) {
  CLI::App* linearize = app.add_subcommand(
      "linearize", "Linearize about an operating point: A, B, the second-order form, eigenvalues, stability");
  add_model_options(linearize, o);
  linearize->add_option("--at", o.at, "Operating point: q1=0.1,q1_dot=0.3,u=1,t=0 (others are 0)")
      ->delimiter(',')
      ->type_name("NAME=VALUE,...");
  add_parameter_option(linearize, o.set, "Override a parameter's default: NAME=VALUE (repeatable)");
  linearize->add_option("--guess", o.guesses,
                        "Starting values for the coordinates and rates solved from the constraints: the point is "
                        "the consistent one nearest them (which assembly of a loop)")
      ->delimiter(',')
      ->type_name("NAME=VALUE,...");
  linearize->add_flag("--equilibrium", o.find_equilibrium,
                      "Take --at as a guess: find the equilibrium (coordinates; rates held) by Newton's method first");
  linearize->add_flag("--drop-cyclic", o.drop_cyclic,
                      "Leave states nothing depends on out (cyclic coordinates; with constraints also speeds such as a "
                      "wheel's spin)");
  linearize->add_option("--sweep", o.sweep,
                        "Linearize at every NAME = FROM, FROM+STEP, ..., TO (a parameter or an --at name): eigenvalues, "
                        "verdicts and where the verdict changes")
      ->type_name("NAME=FROM:TO:STEP");
  linearize->add_option("-f,--format", o.format, "Output format (csv: with --sweep only)")
      ->check(CLI::IsMember({"text", "latex", "json", "csv"}))
      ->capture_default_str();
  linearize->add_option("-o,--output", o.output_path, "Write to FILE instead of standard output (atomically)")
      ->type_name("FILE");
  linearize->add_option("--plot", o.sweep_plot, "With --sweep: plot the eigenvalues' real and imaginary parts, .svg or .png")
      ->type_name("FILE");
  return linearize;
}

CLI::App* add_simulate_command(CLI::App& app, Options& o) {
  CLI::App* simulate = app.add_subcommand(
      "simulate", "Generate, compile (cached) and run a simulation; write a CSV and plot it with gnuplot");
  add_model_options(simulate, o);
  SimulateRequest& r = o.simulate;
  simulate->add_option("--t-end", r.t_end, "End time [s] (the run starts at t = 0)")
      ->required()
      ->check(positive_finite);
  add_integrator_options(simulate, r);
  simulate->add_option("--sample", r.sample, "Interval between CSV rows [s] (default: about 1000 rows)")
      ->check(positive_finite);
  add_parameter_option(simulate, o.set, "Override a parameter: NAME=VALUE (repeatable)");
  simulate->add_option("--init", o.init, "Initial coordinate or rate: q=VALUE, q_dot=VALUE (others 0)")
      ->delimiter(',')
      ->type_name("NAME=VALUE");
  simulate->add_option("--guess", o.guesses,
                       "Starting values for the coordinates and rates solved from the constraints (not kept: the "
                       "start is the consistent state nearest them and the --init values)")
      ->delimiter(',')
      ->type_name("NAME=VALUE");
  simulate->add_option("--input", o.inputs, "Constant input: NAME=VALUE (others 0)")
      ->delimiter(',')
      ->type_name("NAME=VALUE");
  simulate->add_option("--solver", r.solver, "Constraint forces by the KKT system or the null-space method")
      ->check(CLI::IsMember({"kkt", "null-space"}))
      ->capture_default_str();
  simulate->add_option("--stabilization", r.stabilization, "Constraint drift correction")
      ->check(CLI::IsMember({"projection", "baumgarte", "none"}))
      ->capture_default_str();
  simulate->add_option("-o,--output", r.csv_path, "CSV file (default: MODELNAME.csv)")->type_name("FILE");
  CLI::Option* plot = simulate->add_option("--plot", r.plot_path, "Plot file, .svg or .png (default: MODELNAME.svg)")
                          ->type_name("FILE");
  simulate->add_flag("--no-plot", o.no_plot, "Write the CSV only")->excludes(plot);
  simulate->add_option("--animate", r.animation_path,
                       "Also write an animated 3D view of the run: one self-contained HTML page (docs/animation.md)")
      ->type_name("FILE.html");
  add_cache_option(simulate, r.cache_dir, "simulations");
  return simulate;
}

CLI::App* add_python_command(CLI::App& app, Options& o) {
  CLI::App* python = app.add_subcommand(
      "python", "Build the model's Python module (pybind11, NumPy arrays; cached): import it as its model's name");
  add_model_options(python, o);
  PythonRequest& r = o.python;
  python->add_option("-o,--output", r.output_dir, "Directory the module is written to (made if missing)")
      ->type_name("DIR")
      ->capture_default_str();
  python->add_option("--module-name", r.module_name, "The name to import (default: the model's name)")
      ->type_name("NAME");
  add_cache_option(python, r.cache_dir, "modules");
  python->add_flag("--source-only", r.source_only,
                   "Write the header (model.hpp) and the binding source (module.cpp) to DIR instead of building "
                   "(what eomgen_add_python_module compiles)");
  return python;
}

}  // namespace eomgen::tools
