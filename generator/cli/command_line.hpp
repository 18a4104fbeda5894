#pragma once
// The eomgen command line: what each subcommand accepts (CLI11), parsed into Options. What the
// subcommands do is in eomgen_main.cpp, linearize_command.cpp, simulate_command.cpp and
// python_command.cpp.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "eomgen/urdf/urdf_import.hpp"
#include "python_command.hpp"
#include "simulate_command.hpp"

namespace eomgen::tools {

/// The command line as parsed: each subcommand fills the fields it has.
struct Options {
  std::string model_path;
  std::vector<std::string> defines;  // --define NAME=VALUE
  // derive
  std::string format = "text";
  std::string only;
  bool shared = false;
  bool expand = false;
  bool expand_parameters = false;
  std::string output_path;
  // eval
  std::vector<std::string> at, set;
  // linearize, simulate: starting values of the coordinates and rates the constraints determine
  std::vector<std::string> guesses;
  // generate
  std::string outer_namespace = "eomgen_models";
  bool stats = false;
  bool no_cse = false;
  bool emit_linearization = false;
  std::string regressor = "full";  // generate, derive: full (ten per body) or base
  // linearize
  bool drop_cyclic = false;
  bool find_equilibrium = false;
  std::string sweep;       // NAME=FROM:TO:STEP
  std::string sweep_plot;  // --plot of linearize
  // import, and every command given a URDF file
  bool repair_inertia = false;
  bool floating_base = false;
  bool fix_massless_joints = false;
  // simulate
  SimulateRequest simulate;
  std::vector<std::string> init, inputs;
  bool no_plot = false;
  // python
  PythonRequest python;
};

/// How a URDF file given to a command becomes its model.
urdf::ImportOptions import_options(const Options& o);

/// Each adds its subcommand to \p app, with options that write into \p o; \return the
/// subcommand, whose parsed() says whether it was chosen.
CLI::App* add_import_command(CLI::App& app, Options& o);
CLI::App* add_check_command(CLI::App& app, Options& o);
CLI::App* add_derive_command(CLI::App& app, Options& o);
CLI::App* add_eval_command(CLI::App& app, Options& o);
CLI::App* add_generate_command(CLI::App& app, Options& o);
CLI::App* add_linearize_command(CLI::App& app, Options& o);
CLI::App* add_simulate_command(CLI::App& app, Options& o);
CLI::App* add_python_command(CLI::App& app, Options& o);

}  // namespace eomgen::tools
