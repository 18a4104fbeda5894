#include "simulate_command.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <set>

#include "eomgen/codegen/emit_model.hpp"
#include "eomgen/derivation/equations_of_motion.hpp"
#include "eomgen/derivation/scene_recording.hpp"
#include "eomgen/report/animation_page.hpp"
#include "eomgen/base/error.hpp"
#include "eomgen_build_config.hpp"
#include "eomrt/integrators.hpp"
#include "animation.hpp"
#include "cached_build.hpp"
#include "command_values.hpp"
#include "file_output.hpp"
#include "gnuplot.hpp"
#include "process.hpp"

namespace eomgen::tools {

namespace fs = std::filesystem;

namespace {

/// %.17g: the value the user gave, exactly, for the simulation program to read back
std::string exact(double v) { return fmt::format("{:.17g}", v); }

/// Every name the request uses must be one of the model's; reported before anything is built.
void check_names(const Model& model, const SimulateRequest& r) {
  const Variables& vars = model.system.variables();
  std::vector<std::string> parameters, coordinates, rates, inputs;
  for (const Parameter& p : vars.parameters()) parameters.push_back(p.name);
  for (const Coordinate& c : vars.coordinates()) coordinates.push_back(c.name), rates.push_back(c.name + "_dot");
  for (const Input& u : vars.inputs()) inputs.push_back(u.name);
  const auto has = [](const std::vector<std::string>& names, const std::string& n) {
    return std::find(names.begin(), names.end(), n) != names.end();
  };
  for (const auto& [name, value] : r.parameters)
    if (!has(parameters, name)) throw UsageError("--set: " + not_a_parameter(model, name, "--init", "--input"));
  for (const auto& [name, value] : r.initial)
    if (!has(coordinates, name) && !has(rates, name))
      throw UsageError(fmt::format("--init: '{}' is not a coordinate or rate of {}; expected one of {} or {}", name,
                                   model.name, join(coordinates), join(rates)));
  for (const auto& [name, value] : r.inputs)
    if (!has(inputs, name))
      throw UsageError(fmt::format("--input: '{}' is not an input of {}; its inputs: {}", name, model.name,
                                   join(inputs)));
}

/// The method taken when none is asked for: for a step (--dt) or for tolerances. The registry
/// checks at compile time that both defaults are registered.
const eomrt::IntegratorInfo& default_method(bool fixed_step) {
  return *eomrt::find_integrator(fixed_step ? eomrt::default_fixed_step_integrator : eomrt::default_integrator);
}

/// The fixed-step methods as the --dt message suggests them, the default first: "rk4, euler".
std::string fixed_step_suggestions() {
  const eomrt::IntegratorInfo& preferred = default_method(true);
  std::vector<std::string> names{preferred.name};
  for (const eomrt::IntegratorInfo& info : eomrt::integrators)
    if (!info.adaptive && info.method != preferred.method) names.push_back(info.name);
  return join(names);
}

/// The method of the request: the one asked for, else the default for a step (--dt) or for
/// tolerances; its step options must be those of its kind.
const eomrt::IntegratorInfo& method_of(const SimulateRequest& r) {
  const eomrt::IntegratorInfo* method = r.method.empty() ? &default_method(r.step > 0) : eomrt::find_integrator(r.method);
  if (method == nullptr)
    throw UsageError(fmt::format("--method: expected one of {}, got '{}'", join(integrator_names()), r.method));
  if (method->adaptive && r.step > 0)
    throw UsageError(fmt::format("--dt: {} chooses its own steps; give --rtol, or a fixed-step --method ({})",
                                 method->name, fixed_step_suggestions()));
  if (!method->adaptive && (r.rtol > 0 || r.atol > 0))
    throw UsageError(fmt::format("--rtol/--atol: {} takes fixed steps; give --dt, or --method {}", method->name,
                                 default_method(false).name));
  return *method;
}

/// The main() of the simulation program: next to an installed eomgen
/// (bin/../share/eomgen/simulation_program), else the source tree.
fs::path simulation_program_dir() {
  const std::optional<fs::path> found = find_sources(
      build_config::installed_simulation_program_dir, build_config::source_simulation_program_dir, "simulation_main.hpp");
  if (found) return *found;
  throw Error(fmt::format("the simulation program's sources are neither next to eomgen nor in '{}'; "
                          "reinstall eomgen",
                          build_config::source_simulation_program_dir));
}

/// The compiler command of one translation unit of the simulation program (-c: an object file).
std::vector<std::string> compile_command(const fs::path& source, const fs::path& output, const fs::path& runtime,
                                         const fs::path& program) {
  std::vector<std::string> cmd = compiler_invocation();
  cmd.push_back("-I" + source.parent_path().string());
  cmd.push_back("-I" + program.string());
  cmd.push_back("-I" + runtime.string());
  cmd.push_back(std::string("-I") + build_config::eigen_include_dir);
  cmd.push_back("-c");
  cmd.push_back(source.string());
  cmd.push_back("-o");
  cmd.push_back(output.string());
  return cmd;
}

/// The simulation program's methods as C++: the eomrt::OnlyMethods of the request. A program
/// compiled with every integrator and constraint solver took 35 to 50 s for a constrained model,
/// most of it in the solvers' fixed-size decompositions; with the request's only, a request
/// with other methods is built once more, under its own cache key.
std::string methods_of(const eomrt::IntegratorInfo& method, const SimulateRequest& r) {
  return fmt::format("eomrt::OnlyMethods<static_cast<eomrt::Integrator>({}) /* {} */, eomrt::ConstraintSolver::{}, "
                     "eomrt::Stabilization::{}>",
                     static_cast<int>(method.method), method.name, r.solver == "null-space" ? "null_space" : "kkt",
                     r.stabilization);
}

/// Builds the simulation program for `header` unless the cache has it; returns its path. A
/// constrained model's program is two translation units compiled at the same time, the start
/// (assembly onto the constraints: a third of the compile) and the rest, then linked.
fs::path simulation_program(const Model& model, const std::string& header, const std::string& methods,
                            const fs::path& runtime, const fs::path& program_dir, const fs::path& cache) {
  const std::string type = fmt::format("eomgen_models::{}::Model", cpp_identifier(model.name));
  const bool split = !model.system.constraints().empty();
  const std::string start_instance = fmt::format(
      "template bool eomgen::simulation_program::assemble_start<{0}>(eomgen::simulation_program::RunSettings<{0}>&);\n",
      type);
  const std::string driver = fmt::format(
      "// The simulation program of model '{}', written by eomgen simulate.\n"
      "#include \"model.hpp\"\n#include \"simulation_main.hpp\"\n\n"
      "{}"
      "int main(int argc, char** argv) {{\n"
      "  return eomgen::simulation_program::simulation_main<{},\n"
      "                                                     {}>(argc, argv);\n}}\n",
      cpp_string_contents(model.name), split ? "// compiled in start.cpp\nextern " + start_instance + "\n" : "", type,
      methods);
  CachedBuild build;
  build.what = "the simulation of " + model.name;
  build.key_name = cpp_identifier(model.name);
  build.files = {{"model.hpp", header}, {"driver.cpp", driver}};
  build.header_dirs = {program_dir, runtime / "eomrt"};
  build.product = "simulate";
  if (!split) {
    build.command = [&](const fs::path& directory) {
      std::vector<std::string> cmd = compile_command(directory / "driver.cpp", directory / "simulate", runtime,
                                                     program_dir);
      cmd.erase(std::find(cmd.begin(), cmd.end(), "-c"));  // compiled and linked at once
      return cmd;
    };
    return build_cached(build, cache);
  }
  build.files.emplace_back("start.cpp", fmt::format("// The start (assembly) of the simulation program of model '{}'.\n"
                                                    "#include \"model.hpp\"\n#include \"simulation_main.hpp\"\n\n{}",
                                                    cpp_string_contents(model.name), start_instance));
  build.units = [&](const fs::path& directory) {
    return std::vector<std::vector<std::string>>{
        compile_command(directory / "driver.cpp", directory / "driver.o", runtime, program_dir),
        compile_command(directory / "start.cpp", directory / "start.o", runtime, program_dir)};
  };
  build.command = [&](const fs::path& directory) {
    std::vector<std::string> cmd = compiler_invocation();
    for (const char* object : {"driver.o", "start.o"}) cmd.push_back((directory / object).string());
    cmd.push_back("-o");
    cmd.push_back((directory / "simulate").string());
    return cmd;
  };
  return build_cached(build, cache);
}

/// The cache holds the programs simulate runs, and the builds of concurrent runs: no output of a
/// run goes in there.
void refuse_outputs_in(const fs::path& cache, const std::vector<OutputFile>& outputs) {
  fs::path root = written_file(cache.string());
  if (!root.has_filename()) root = root.parent_path();  // "cache/"
  for (const OutputFile& output : outputs) {
    if (output.path.empty()) continue;
    const fs::path target = written_file(output.path);
    if (std::mismatch(root.begin(), root.end(), target.begin(), target.end()).first == root.end())
      throw UsageError(fmt::format("{}: '{}' is in the cache directory '{}', whose compiled programs eomgen runs; "
                                   "choose a file outside it",
                                   output.option, output.path, cache.string()));
  }
}

/// gnuplot script: coordinates against time above, T, V and T+V below; `image` is where gnuplot
/// writes (a temporary name), `image_name`'s extension chooses the terminal.
std::string plot_script(const Model& model, const std::string& csv, const std::string& image,
                        const std::string& image_name, const std::string& title) {
  const Variables& vars = model.system.variables();
  const std::size_t nq = vars.coordinates().size();
  const std::size_t nc = model.system.constraints().size();
  const std::size_t nu = vars.inputs().size();
  const std::size_t energy_column = 1 + 2 * nq + nc + nu + 1;  // of T; gnuplot counts from 1 (t)
  std::string s = gnuplot_terminal(image_name, 1000, 800);
  s += "set output " + gnuplot_path(image) + "\n";
  s += "set datafile separator ','\n";
  s += "set grid\nset key outside right top\nset xlabel 't [s]'\n";
  s += "set multiplot layout 2,1 title " + gnuplot_text(title) + "\n";
  s += "set ylabel 'coordinates'\n";
  s += fmt::format("plot for [i=2:{}] {} using 1:i with lines lw 1.5 title columnheader(i)\n", 1 + nq,
                   gnuplot_path(csv));
  s += "set ylabel 'energy [J]'\n";
  s += fmt::format(
      "plot {0} using 1:{1} with lines lw 1.5 title 'T', '' using 1:{2} with lines lw 1.5 title 'V', "
      "'' using 1:{3} with lines lw 2 title 'T + V'\n",
      gnuplot_path(csv), energy_column, energy_column + 1, energy_column + 2);
  s += "unset multiplot\nset output\n";
  return s;
}

}  // namespace

std::vector<std::string> integrator_names() {
  std::vector<std::string> names;
  for (const eomrt::IntegratorInfo& info : eomrt::integrators) names.push_back(info.name);
  return names;
}

std::string integrator_names(bool adaptive, const std::string& separator) {
  std::string out;
  for (const eomrt::IntegratorInfo& info : eomrt::integrators)
    if (info.adaptive == adaptive) out += (out.empty() ? "" : separator) + info.name;
  return out;
}

std::string method_help() {
  std::string help = fmt::format("Integrator (default: {}, or {} when --dt is given):", default_method(false).name,
                                 default_method(true).name);
  std::size_t width = 0;
  for (const eomrt::IntegratorInfo& info : eomrt::integrators) width = std::max(width, std::strlen(info.name));
  for (const eomrt::IntegratorInfo& info : eomrt::integrators)
    help += fmt::format("\n  {:<{}}  {}", info.name, width, info.description);
  return help;
}

int run_simulate(const Model& model, const SimulateRequest& r) {
  check_names(model, r);
  const eomrt::IntegratorInfo& method_info = method_of(r);
  const std::string method = method_info.name;
  // default names from the model's name as an identifier: a name is free text in a model
  // file without a `model` line (the file's stem), and must not become a path or an option
  const std::string stem = cpp_identifier(model.name);
  const std::string csv_path = r.csv_path.empty() ? stem + ".csv" : r.csv_path;
  const std::string plot_path = r.plot_path.empty() ? stem + ".svg" : r.plot_path;
  const std::vector<OutputFile> outputs{
      {"-o", csv_path}, {"--plot", r.plot ? plot_path : std::string()}, {"--animate", r.animation_path}};
  const fs::path runtime = runtime_include_dir(), program_dir = simulation_program_dir(),
                 cache = cache_root(r.cache_dir);
  std::vector<std::string> sources;
  for (const fs::path& dir : {program_dir, runtime / "eomrt"})
    for (const fs::path& h : headers_in(dir)) sources.push_back(h.string());
  check_output_files(outputs, r.model_path, sources, "the sources of the simulation program");
  refuse_outputs_in(cache, outputs);
  if (r.plot) {
    require_plot_target(plot_path, "--plot", "pass --no-plot");
    require_gnuplot_path(csv_path, "-o");  // gnuplot reads the CSV
    std::error_code ec;
    const fs::file_status csv_status = fs::status(csv_path, ec);
    if (fs::exists(csv_status) && !fs::is_regular_file(csv_status))
      throw UsageError(fmt::format("-o: '{}' is not a regular file, which gnuplot could read the CSV back from for the "
                                   "plot; pass --no-plot, or write the CSV to a file",
                                   csv_path));
  }

  // with an animation the generated code also records the scene, as outputs after the model's
  // (its own program in the cache: recording a long three-dimensional chain costs seconds to
  // generate, which a run without an animation does not pay)
  const bool animate = !r.animation_path.empty();
  const SceneRecording recording = animate ? scene_recording(model) : SceneRecording{};
  const Model simulated = animate ? with_scene_output(model, recording) : model;
  std::size_t model_outputs = 0;
  for (const Output& output : model.outputs) model_outputs += output.components.size();
  if (animate) check_animation_parameters(model, r.parameters);
  const ModelEquations eom = derive_equations(simulated);
  EmitOptions emit;
  emit.source_name = fs::path(r.model_path).filename().string();
  // the simulation needs no functions for controllers: their code would only lengthen the compile
  HeaderOptions without_controller_functions;
  without_controller_functions.controller_functions = false;
  const std::string header =
      emit_model(simulated, derive_header_functions(simulated, eom, nullptr, without_controller_functions), emit).header;
  const fs::path program = simulation_program(model, header, methods_of(method_info, r), runtime, program_dir, cache);

  std::vector<std::string> cmd{program.string(), "--t-end", exact(r.t_end), "--method", method,
                               "--solver", r.solver, "--stabilization", r.stabilization};
  if (r.step > 0) cmd.insert(cmd.end(), {"--dt", exact(r.step)});
  if (r.rtol > 0) cmd.insert(cmd.end(), {"--rtol", exact(r.rtol)});
  if (r.atol > 0) cmd.insert(cmd.end(), {"--atol", exact(r.atol)});
  if (r.sample > 0) cmd.insert(cmd.end(), {"--sample", exact(r.sample)});
  for (const auto& [name, value] : r.parameters) cmd.insert(cmd.end(), {"--set", name + "=" + exact(value)});
  for (const auto& [name, value] : r.initial) cmd.insert(cmd.end(), {"--init", name + "=" + exact(value)});
  for (const auto& [name, value] : r.guesses) cmd.insert(cmd.end(), {"--guess", name + "=" + exact(value)});
  for (const auto& [name, value] : r.inputs) cmd.insert(cmd.end(), {"--input", name + "=" + exact(value)});
  if (::isatty(STDERR_FILENO)) cmd.push_back("--progress");

  PendingFile csv(csv_path);
  cmd.insert(cmd.end(), {"--csv", csv.path()});
  std::optional<PendingFile> samples;  // the animation's samples: a temporary file beside the page
  if (animate) {
    samples.emplace(r.animation_path + ".samples");
    cmd.insert(cmd.end(), {"--scene-first", std::to_string(model_outputs), "--scene", samples->path()});
  }
  std::cout << std::flush;
  const int status = run_process(cmd);
  if (status == 1) {
    std::cerr << fmt::format("eomgen: error: the simulation of {} failed (see above); no CSV or plot was written\n",
                             model.name);
    return 1;
  }
  if (status != 0)
    throw Error(fmt::format("the simulation program of {} ended with status {}", model.name, status));
  if (animate) {
    // the page before the CSV is committed: a run whose page cannot be made leaves neither
    const char* ros_package_path = std::getenv("ROS_PACKAGE_PATH");
    const MeshPlaces places{fs::absolute(fs::path(r.model_path)).parent_path(),
                            ros_package_path ? ros_package_path : ""};
    const AnimationScene scene =
        animation_scene(model, recording, r.parameters, samples->path(), emit.source_name, places);
    for (const MissingMesh& m : scene.missing_meshes)
      std::cerr << fmt::format("warning: shape '{}': mesh \"{}\" not drawn (a stand-in is): {}\n", m.shape, m.file,
                               m.reason);
    write_atomically(r.animation_path,
                     animation_page(fmt::format("{}: {}", model.name, model.description), scene.json));
  }
  csv.commit();
  std::cout << fmt::format("CSV:  {}\n", csv_path) << std::flush;
  if (animate) {
    std::error_code ec;
    const std::uintmax_t bytes = fs::file_size(r.animation_path, ec);  // none for a device or pipe
    std::cout << (ec ? fmt::format("animation: {}\n", r.animation_path)
                     : fmt::format("animation: {} ({:.2f} MB)\n", r.animation_path, static_cast<double>(bytes) / 1e6))
              << std::flush;
  }

  if (r.plot) {
    const std::string title = fmt::format("{}: {}", model.name, model.description);
    try {
      plot_with_gnuplot(plot_path, [&](const std::string& image) {
        return plot_script(model, fs::absolute(csv_path).string(), image, plot_path, title);
      });
    } catch (const Error& e) {
      return report_plot_failure(plot_path, fmt::format("the CSV '{}'", csv_path), e);
    }
    std::cout << fmt::format("plot: {}\n", plot_path);
  }
  return 0;
}

}  // namespace eomgen::tools
