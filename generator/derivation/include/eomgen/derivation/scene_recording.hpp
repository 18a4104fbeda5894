#pragma once
// What an animation of a simulation records at each sample (`eomgen simulate --animate`,
// docs/animation.md): the attitude of every frame a body or shape turns with and the position
// of every point, as expressions of the model's state. Recorded by the generated code, as
// outputs, so the animation shows what the simulation computed, not a second derivation.
#include <ginac/ginac.h>

#include <string>
#include <utility>
#include <vector>

#include "eomgen/mechanics/model.hpp"

namespace eomgen {

struct SceneRecording {
  /// Recorded frames (never the inertial one), in the order of the system's frames, each with
  /// the body whose frame it is ("" for none).
  std::vector<std::pair<FrameId, std::string>> frames;
  /// Every point of the system, in its order (index i is PointId{i}).
  std::vector<PointId> points;
  /// Pairs of indices into `points`: a point and its parent when the offset between them is
  /// fixed in a moving frame, the links of the mechanism (a rod from a pivot to a bob).
  std::vector<std::pair<std::size_t, std::size_t>> links;
  /// Indices into `points` whose trails an animation shows from the start.
  std::vector<std::size_t> trails;
  /// Per sample: for each frame f of `frames` the nine entries of C_af (a the inertial frame,
  /// so the columns are f's unit vectors in a's components), row by row; then each point's
  /// position from the inertial origin, resolved in the inertial frame.
  std::vector<GiNaC::ex> components;
};

/// The recording of \p model: the frames of its rigid bodies and of its shapes, its points, their
/// links and default trails (the contact points of `roll` and `wheel`; else the points of the
/// particles and body centres that no other point hangs from; else every such leaf point).
SceneRecording scene_recording(const Model& model);

/// \p model with one more output, "scene", of the recording's components: what `simulate
/// --animate` generates, compiles and runs.
Model with_scene_output(const Model& model, const SceneRecording& recording);

}  // namespace eomgen
