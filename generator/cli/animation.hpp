#pragma once
// The animation of a simulation (`eomgen simulate --animate run.html`, docs/animation.md): the
// scene the page shows, as the JSON the viewer reads, from the model, the recording the
// simulation program made with the generated code, and the run's parameter values.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "eomgen/derivation/scene_recording.hpp"
#include "eomgen/mechanics/model.hpp"

namespace eomgen::tools {

/// At most this many samples go into a page; a longer run is thinned evenly, its last sample kept.
inline constexpr std::size_t max_animation_samples = 2500;

/// Checks, before a run, that every shape's dimensions and axis are what they must be at the
/// run's parameters (--set can make a radius zero or negative).
/// \throws SourceError at the shape's statement
void check_animation_parameters(const Model& model, const std::map<std::string, double>& parameters);

/// Where a mesh shape's file is looked for (mesh_files.hpp).
struct MeshPlaces {
  std::filesystem::path model_directory;  // of the model file or URDF
  std::string ros_package_path;           // $ROS_PACKAGE_PATH, for package:// names
};

/// A mesh shape the page does not draw, and why (its body is drawn as if it had no shape).
struct MissingMesh {
  std::string shape, file, reason;
};

/// The scene of docs/animation.md ("The scene", format 1), and the meshes it leaves out.
struct AnimationScene {
  std::string json;
  std::vector<MissingMesh> missing_meshes;
};

/// At most this many triangles of meshes go into a page (36 bytes each, before base64); a mesh
/// that would cross it is left out, and said.
inline constexpr std::size_t max_animation_triangles = 500000;
/// A mesh file larger than this is not read.
inline constexpr std::uintmax_t max_mesh_file_bytes = 200u << 20;

/// The scene of docs/animation.md ("The scene", format 1).
/// \param parameters  the run's --set values; the others are the defaults
/// \param samples     the path of the simulation program's scene file: per sample a line of t, q, lambda,
///                    T, V and the recording's components (simulation_program/sample_writer.hpp)
/// \throws eomgen::Error for a file that does not have that form (a bug), and for a shape's
///         dimension that is not a finite positive number at the run's parameters
AnimationScene animation_scene(const Model& model, const SceneRecording& recording,
                               const std::map<std::string, double>& parameters, const std::string& samples_path,
                               const std::string& source_name, const MeshPlaces& places);

}  // namespace eomgen::tools
