#pragma once
// How a body looks in the animation of a simulation (`eomgen simulate --animate`): a shape of
// the `shape` statement, placed at a point and turned with a frame. Shapes have no mass and no
// part in the equations; the animation draws them from the recorded positions and attitudes.
#include <ginac/ginac.h>

#include <array>
#include <optional>
#include <string>

#include "eomgen/base/source_location.hpp"
#include "eomgen/mechanics/vector.hpp"

namespace eomgen {

struct VisualShape {
  /// sphere: `radius`; box: `size` (edge lengths along the frame's axes 1, 2, 3); cylinder:
  /// `radius` and `length` along `axis`; disk: `radius` and `length` (its thickness) along
  /// `axis`; rod: from `at` to `to`, of `radius`; mesh: the triangles of `file`, their
  /// coordinates along the frame's axes from `at`, times `scale`.
  enum class Kind { sphere, box, cylinder, disk, rod, mesh };
  Kind kind = Kind::sphere;
  std::string name;               // the statement's name
  std::string body;               // the rigid body or particle it belongs to (its colour and name in the view); empty: none
  std::optional<FrameId> frame;   // its attitude: the body's frame, the `frame` argument, else the inertial frame
                                  // (none: a particle's sphere, a rod)
  PointId at;                     // its centre; a rod's first end
  PointId to;                     // a rod's second end (the other kinds: unused)
  GiNaC::ex radius = 0, length = 0;  // numbers and parameters only
  std::array<GiNaC::ex, 3> size{0, 0, 0};
  /// cylinder and disk: the axis's components in `frame` (constant; any length, it is
  /// normalized where it is drawn); the other kinds: unused
  std::array<GiNaC::ex, 3> axis{0, 0, 1};
  /// mesh: the file as written (a path relative to the model's directory, an absolute one, or
  /// a URDF's package:// or file:// address), found and read where the animation is written
  std::string file;
  /// mesh: the factors of its coordinates along the frame's axes (numbers and parameters, not
  /// zero; negative mirrors); the other kinds: unused
  std::array<GiNaC::ex, 3> scale{1, 1, 1};
  SourceLocation location;
};

/// The force a surface exerts on a body at a contact (`roll`, `wheel`): the sum over its rows of
/// lambda_row times the row's direction, the multipliers' meaning of docs/model-language.md.
struct ContactForce {
  struct Row {
    std::size_t constraint;                  // index into MechanicalSystem::constraints()
    std::array<GiNaC::ex, 3> direction;      // unit, resolved in the inertial frame; numbers and parameters
  };
  std::string name;   // the statement's name
  PointId point;      // the contact point
  std::vector<Row> rows;
  /// the surface's plane when the statement gives a normal: its unit normal (inertial frame) and
  /// a point of it; drawn as the ground
  std::optional<std::array<GiNaC::ex, 3>> plane_normal;
  PointId plane_point;
  SourceLocation location;
};

}  // namespace eomgen
