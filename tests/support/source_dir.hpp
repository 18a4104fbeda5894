#pragma once
// Where the tests find the repository's files (models/, docs/, ...). The path is compiled into
// one small translation unit only (source_dir.cpp), so every other test object is the same
// whatever folder the repository is cloned into and ccache can share it between clones.
#include <filesystem>
#include <string>

namespace eomgen::testing {

/// The repository root (absolute).
std::filesystem::path source_dir();

/// models/NAME.eom of the repository.
inline std::string shipped_model_path(const std::string& name) {
  return (source_dir() / "models" / (name + ".eom")).string();
}

}  // namespace eomgen::testing
