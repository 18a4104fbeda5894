#pragma once
// `eomgen python`: a model's Python module (docs/python.md). The generator writes the model's
// header, with linearization_terms, and its binding source (python_module.hpp); the configured
// compiler builds them with pybind11 into a cache keyed by content, as `simulate` builds its
// programs; the module is copied into the output directory as NAME<extension suffix>.
#include <string>

#include "eomgen/mechanics/model.hpp"

namespace eomgen::tools {

struct PythonRequest {
  std::string model_path;
  std::string output_dir = ".";
  std::string module_name;  ///< empty: the model's name (python_module_name)
  std::string cache_dir;    ///< empty: as simulate's (cache_root)
  /// write the header (model.hpp) and the source (module.cpp) into output_dir instead of
  /// building: what eomgen_add_python_module() compiles with its own toolchain
  bool source_only = false;
};

/// \return the exit status (0)
/// \throws UsageError for a module name that is not a Python identifier or an unusable directory
/// \throws eomgen::Error when this eomgen was built without Python support or compiling fails
int run_python(const Model& model, const PythonRequest& request);

}  // namespace eomgen::tools
