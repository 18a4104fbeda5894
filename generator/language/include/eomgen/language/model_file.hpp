#pragma once
// The model language's entry points: model text (a .eom file) in, a Model out.
#include <map>
#include <string>

#include "eomgen/mechanics/model.hpp"
#include "eomgen/urdf/urdf_import.hpp"

namespace eomgen {

/// Parses model text. `overrides` replace `const` values (e.g. {"n", 8}).
/// \throws SourceError (file:line:col: error: ...) for every syntax or model error.
Model parse_model(const std::string& text, const std::string& file_name,
                  const std::map<std::string, double>& overrides = {});

/// Reads and parses a model file; a URDF file (.urdf) is read as the model `eomgen import` writes
/// from it with `import_options` (urdf/urdf_import.hpp), which a model file does not take.
/// \throws SourceError, or Error if the file cannot be read or is given import options.
Model load_model(const std::string& path, const std::map<std::string, double>& overrides = {},
                 const urdf::ImportOptions& import_options = {});

}  // namespace eomgen
