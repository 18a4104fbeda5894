#pragma once
// The settings of one run of the simulation program, read from the command line that
// `eomgen simulate` writes (generator/cli/simulate_command.cpp):
//
//   program --t-end T --method NAME --solver S --stabilization S [--dt H] [--rtol R]
//           [--atol A] [--sample S] [--set p=v]... [--init q=v | q_dot=v]...
//           [--guess q=v | q_dot=v]... [--input u=v]...
//           --csv FILE [--scene-first K [--scene FILE]] [--progress]
//
// eomgen has checked every value and name against the model and the integrator registry
// before it builds the program, and says what is wrong in the user's terms; here a malformed
// argument can only be a bug in eomgen, and is reported as such.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "eomrt/assembly.hpp"
#include "eomrt/integrators.hpp"
#include "eomrt/sampling.hpp"
#include "eomrt/simulate.hpp"

namespace eomgen::simulation_program {

/// An argument eomgen should not have written (exit status 2).
class ArgumentError : public std::runtime_error {
 public:
  explicit ArgumentError(const std::string& what)
      : std::runtime_error("malformed argument from eomgen simulate: " + what) {}
};

/// What one run simulates and where it writes.
template <class Model>
struct RunSettings {
  using Types = eomrt::ModelTypes<Model, double>;
  eomrt::SimulationOptions<double> options;
  typename Types::Parameters p;
  typename Types::State x0 = Types::State::Zero();
  /// the entries of x0 given by --init, which assembly keeps (the others, --guess or 0, it
  /// solves from the constraints)
  eomrt::HeldEntries<Model> held = eomrt::HeldEntries<Model>::Constant(false);
  /// the inputs, held constant
  typename Types::Inputs u = Types::Inputs::Zero();
  std::string csv_path;
  /// The output components from scene_first on (default: none) are the animation's recording
  /// (scene_recording.hpp), never written to the CSV; with --animate they go to scene_path, one
  /// line per sample (empty: nowhere).
  std::string scene_path;
  int scene_first = -1;
  /// draw a progress line on stderr when it is a terminal
  bool progress = false;
};

/// The model's output components: ny, or 0 for a model without outputs.
template <class Model>
constexpr int output_count() {
  if constexpr (eomrt::has_outputs_v<Model>)
    return Model::ny;
  else
    return 0;
}

namespace detail {

inline double number(const std::string& text, const std::string& option) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v))
    throw ArgumentError(option + " '" + text + "'");
  return v;
}

template <std::size_t N>
int index_of(const std::array<const char*, N>& names, const std::string& name) {
  for (std::size_t i = 0; i < N; ++i)
    if (name == names[i]) return static_cast<int>(i);
  return -1;
}

/// "name=value" split at the first '='
inline std::pair<std::string, double> assignment(const std::string& item, const std::string& option) {
  const auto eq = item.find('=');
  if (eq == std::string::npos || eq == 0) throw ArgumentError(option + " '" + item + "'");
  return {item.substr(0, eq), number(item.substr(eq + 1), option + " " + item.substr(0, eq))};
}

/// The entry of x0 = [q; qd] that a coordinate name q or a rate name q_dot sets, or -1.
template <class Model>
int state_index(const std::string& name) {
  const int k = index_of(Model::coordinate_names, name);
  if (k >= 0 || name.size() <= 4 || name.compare(name.size() - 4, 4, "_dot") != 0) return k;
  const int rate = index_of(Model::coordinate_names, name.substr(0, name.size() - 4));
  return rate >= 0 ? rate + Model::nq : -1;
}

template <class Model>
void set_named(RunSettings<Model>& run, const std::string& option, const std::string& item) {
  const auto [name, v] = assignment(item, option);
  int k = -1;
  if (option == "--set") {
    k = index_of(Model::parameter_names, name);
    if (k >= 0) *run.p.fields()[static_cast<std::size_t>(k)] = v;
  } else if (option == "--init" || option == "--guess") {
    k = state_index<Model>(name);
    if (k >= 0) run.x0(k) = v;
    if (k >= 0 && option == "--init") run.held(k) = true;
  } else {
    k = index_of(Model::input_names, name);
    if (k >= 0) run.u(k) = v;
  }
  if (k < 0) throw ArgumentError(option + " '" + item + "': no such name in " + Model::name);
}

/// Applies one option and its value; \return false if the option is not one of the program's
template <class Model>
bool apply_option(RunSettings<Model>& run, const std::string& option, const std::string& value) {
  eomrt::SimulationOptions<double>& o = run.options;
  if (option == "--t-end") {
    o.t_end = number(value, option);
  } else if (option == "--method") {
    const eomrt::IntegratorInfo* method = eomrt::find_integrator(value);
    if (method == nullptr) throw ArgumentError(option + " '" + value + "'");
    o.integrator = method->method;
  } else if (option == "--dt") {
    o.step = number(value, option);
  } else if (option == "--rtol") {
    o.adaptive.rtol = number(value, option);
  } else if (option == "--atol") {
    o.adaptive.atol = number(value, option);
  } else if (option == "--sample") {
    o.sample_interval = number(value, option);
  } else if (option == "--solver" && (value == "kkt" || value == "null-space")) {
    o.solver = value == "kkt" ? eomrt::ConstraintSolver::kkt : eomrt::ConstraintSolver::null_space;
  } else if (option == "--stabilization" && value == "projection") {
    o.stabilization = eomrt::Stabilization::projection;
  } else if (option == "--stabilization" && value == "baumgarte") {
    o.stabilization = eomrt::Stabilization::baumgarte;
  } else if (option == "--stabilization" && value == "none") {
    o.stabilization = eomrt::Stabilization::none;
  } else if (option == "--set" || option == "--init" || option == "--guess" || option == "--input") {
    set_named(run, option, value);
  } else if (option == "--csv") {
    run.csv_path = value;
  } else if (option == "--scene") {
    run.scene_path = value;
  } else if (option == "--scene-first") {
    const double k = number(value, option);
    if (k < 0 || k != std::floor(k) || k > output_count<Model>())
      throw ArgumentError(option + " '" + value + "'");
    run.scene_first = static_cast<int>(k);
  } else {
    return false;
  }
  return true;
}

}  // namespace detail

/// The settings of the command line, with the sample interval chosen when none is given.
/// @throws ArgumentError for an argument eomgen simulate does not write
template <class Model>
RunSettings<Model> parse_arguments(int argc, char** argv) {
  RunSettings<Model> run;
  run.options.t_end = std::numeric_limits<double>::quiet_NaN();
  for (int i = 1; i < argc; ++i) {
    const std::string option = argv[i];
    if (option == "--progress") {
      run.progress = true;
      continue;
    }
    if (i + 1 >= argc || !detail::apply_option(run, option, argv[i + 1])) throw ArgumentError("'" + option + "'");
    ++i;
  }
  if (std::isnan(run.options.t_end) || run.csv_path.empty()) throw ArgumentError("--t-end and --csv are required");
  if (run.scene_first < 0) {
    if (!run.scene_path.empty()) throw ArgumentError("--scene without --scene-first");
    run.scene_first = output_count<Model>();  // a header without the recording: every output is the model's
  }

  eomrt::SimulationOptions<double>& o = run.options;
  if (o.sample_interval == 0) o.sample_interval = eomrt::default_sample_interval(o);
  return run;
}

}  // namespace eomgen::simulation_program
