#include "python_command.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <sstream>
#include <vector>

#include "eomgen/base/error.hpp"
#include "eomgen/codegen/emit_model.hpp"
#include "eomgen/codegen/python_module.hpp"
#include "eomgen/derivation/equations_of_motion.hpp"
#include "eomgen/derivation/linearization.hpp"
#include "eomgen_build_config.hpp"
#include "cached_build.hpp"
#include "file_output.hpp"
#include "simulate_command.hpp"

namespace eomgen::tools {

namespace fs = std::filesystem;

namespace {

// a name `import` accepts: an ASCII identifier that is not a keyword
void check_module_name(const std::string& name) {
  bool valid = !name.empty() && !std::isdigit(static_cast<unsigned char>(name[0]));
  for (char c : name) valid = valid && (std::isalnum(static_cast<unsigned char>(c)) || c == '_');
  if (!valid || python_identifier(name) != name)
    throw UsageError(fmt::format("--module-name: expected a Python identifier (a letter or _, then letters, digits "
                                 "and _, not a keyword), got '{}'",
                                 name));
}

// the directory holding eompy/: next to an installed eomgen (share/eomgen/python), else the
// source tree
fs::path eompy_dir() {
  const std::optional<fs::path> found =
      find_sources(build_config::installed_python_dir, build_config::source_python_dir, "eompy/module.hpp");
  if (found) return *found;
  throw Error(fmt::format("the eompy headers are neither next to eomgen nor in '{}'; reinstall eomgen",
                          build_config::source_python_dir));
}

// the compiler's command for the module of the source in `directory`
std::vector<std::string> module_command(const fs::path& directory, const fs::path& eompy, const fs::path& runtime) {
  std::vector<std::string> cmd = compiler_invocation();
  for (const char* flag : {"-shared", "-fPIC", "-fvisibility=hidden"}) cmd.push_back(flag);
  for (const fs::path& dir : {directory, eompy, runtime}) cmd.push_back("-I" + dir.string());
  cmd.push_back(std::string("-I") + build_config::eigen_include_dir);
  std::istringstream python_dirs(build_config::python_include_dirs);
  for (std::string dir; std::getline(python_dirs, dir, ';');)
    if (!dir.empty()) cmd.push_back("-I" + dir);
  cmd.push_back((directory / "module.cpp").string());
  cmd.push_back("-o");
  cmd.push_back((directory / "module.so").string());
  return cmd;
}

}  // namespace

int run_python(const Model& model, const PythonRequest& r) {
  const std::string module = r.module_name.empty() ? python_module_name(model) : r.module_name;
  check_module_name(module);
  if (!r.source_only && std::string(build_config::python_extension_suffix).empty())
    throw Error("this eomgen was configured without Python support (EOMGEN_PYTHON off, or pybind11 or Python's "
                "headers missing): install python3-pybind11, python3-dev and python3-numpy "
                "(scripts/install-deps.sh) and configure eomgen again");

  std::error_code ec;
  const fs::path dir = r.output_dir.empty() ? fs::path(".") : fs::path(r.output_dir);
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir, ec))
    throw UsageError(fmt::format("-o: '{}' is not a directory, and cannot be made one", r.output_dir));
  const std::string header_path = (dir / "model.hpp").string(), source_path = (dir / "module.cpp").string();
  const std::string module_path = (dir / (module + build_config::python_extension_suffix)).string();
  if (r.source_only)
    check_output_files({{"-o", header_path}, {"-o", source_path}}, r.model_path);
  else
    check_output_files({{"-o", module_path}}, r.model_path);

  const ModelEquations eom = derive_equations(model);
  const SymbolicLinearization linearization = linearize_symbolic(model, eom);
  const HeaderFunctions functions = derive_header_functions(model, eom, &linearization);
  EmitOptions emit;
  emit.source_name = fs::path(r.model_path).filename().string();
  const std::string header = emit_model(model, functions, emit).header;
  const std::string source = python_module_source(model, functions, module);
  if (r.source_only) {
    write_atomically(header_path, header);
    write_atomically(source_path, source);
    return 0;
  }

  const fs::path eompy = eompy_dir(), runtime = runtime_include_dir();
  CachedBuild build;
  build.what = "the Python module of " + model.name;
  build.key_name = module + "-python";
  build.files = {{"model.hpp", header}, {"module.cpp", source}};
  build.header_dirs = {eompy / "eompy", runtime / "eomrt"};
  build.command = [&](const fs::path& directory) { return module_command(directory, eompy, runtime); };
  build.product = "module.so";
  const fs::path built = build_cached(build, cache_root(r.cache_dir));
  write_atomically(module_path, read_file(built));
  std::cout << fmt::format("module: {}\n", module_path) << std::flush;
  return 0;
}

}  // namespace eomgen::tools
