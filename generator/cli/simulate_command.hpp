#pragma once
// `eomgen simulate`: generate a model's code, compile it with the simulation program
// (simulation_program/) and the runtime into a cache keyed by content, run it, and plot the
// result with gnuplot.
#include <map>
#include <string>
#include <vector>

#include "eomgen/derivation/model_equations.hpp"
#include "eomgen/language/model_file.hpp"

namespace eomgen::tools {

/// A command line CLI11 accepted but whose content is malformed (exit status 2).
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// What the user asked `eomgen simulate` for; numbers are already parsed and finite.
struct SimulateRequest {
  std::string model_path;
  double t_end = 0;
  std::string method;  ///< a name of the integrator registry; empty: its default for a step, or without one
  double step = 0;     ///< 0: not given
  double rtol = 0;     ///< 0: not given
  double atol = 0;     ///< 0: not given
  double sample = 0;   ///< 0: about 1000 rows
  std::string solver = "kkt";
  std::string stabilization = "projection";
  std::map<std::string, double> parameters;  ///< --set
  std::map<std::string, double> initial;     ///< --init (coordinates and NAME_dot rates)
  std::map<std::string, double> guesses;     ///< --guess (starting values of the assembly, not kept)
  std::map<std::string, double> inputs;      ///< --input (constant inputs)
  std::string csv_path;                      ///< empty: <model>.csv
  std::string plot_path;                     ///< empty: <model>.svg
  bool plot = true;
  std::string animation_path;  ///< empty: no animation
  std::string cache_dir;  ///< empty: $EOMGEN_CACHE_DIR, else $XDG_CACHE_HOME/eomgen, else ~/.cache/eomgen
};

/// The names `--method` accepts: the integrator registry's (eomrt/integrators.hpp), in its order.
std::vector<std::string> integrator_names();

/// The names of the fixed-step (or of the adaptive) methods in the registry's order, joined by
/// \p separator: "euler/rk4".
std::string integrator_names(bool adaptive, const std::string& separator);

/// The help of `--method`: the defaults, then one line per registered method.
std::string method_help();

/// Runs the request for an already loaded model.
/// \return the exit status: 0; 1 when the simulation failed (its message is on stderr, and no CSV
///   or plot was written); plot_failed_status when the CSV was written but the plot was not
/// \throws UsageError for names or settings the model does not have
/// \throws eomgen::Error when compiling, running or plotting fails
int run_simulate(const Model& model, const SimulateRequest& request);

}  // namespace eomgen::tools
