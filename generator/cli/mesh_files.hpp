#pragma once
// Where a mesh shape's file is (docs/model-language.md, "shape ... = mesh(...)"): the file as
// written in the model, found the way URDF readers find it, for the animation page to draw.
#include <filesystem>
#include <optional>
#include <string>

namespace eomgen::tools {

/// The STL file a mesh shape names, or why it is not drawn.
struct MeshFileLookup {
  std::optional<std::filesystem::path> path;  // a regular file with the extension .stl
  std::string reason;                         // when there is no path: "not found (searched ...)", "not STL ..."
};

/// Finds \p file as written in a model in \p model_directory:
/// - `package://PKG/REST`: REST in the package directory PKG, looked for in every directory of
///   \p ros_package_path (colon-separated, as $ROS_PACKAGE_PATH: an entry that is PKG, or holds
///   PKG), then in the model's directory and each directory above it (one that is PKG, or holds
///   PKG);
/// - `file://PATH`: PATH, which must be absolute;
/// - a path: relative to the model's directory, or absolute.
/// Only STL is drawn (by its extension, in any case); other schemes (`model://`, `http://`) are
/// not read.
MeshFileLookup find_mesh_file(const std::string& file, const std::filesystem::path& model_directory,
                              const std::string& ros_package_path);

}  // namespace eomgen::tools
