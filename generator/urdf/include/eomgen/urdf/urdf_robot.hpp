#pragma once
// A robot as a URDF file describes it (https://wiki.ros.org/urdf/XML): links with their
// inertia and visuals, joined into a tree by joints. Numbers keep the text the file gives them
// (a model written from it repeats 1.57079632679 as written) beside their value, and every part
// keeps where the file says it, so the checks of the import point at the file.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "eomgen/base/source_location.hpp"

namespace eomgen::urdf {

/// A number of the file: its text, normalized only where the model language reads it otherwise
/// (a leading `+`), and its value.
struct Number {
  std::string text = "0";
  double value = 0;
  bool is_zero() const { return value == 0; }
};

using Triple = std::array<Number, 3>;

/// `<origin xyz rpy>`: the pose of a frame in its parent, C = Rz(yaw) Ry(pitch) Rx(roll) taking
/// the frame's components to the parent's.
struct Origin {
  Triple xyz;
  Triple rpy;  ///< roll, pitch, yaw
  SourceLocation location;
  bool translates() const { return !xyz[0].is_zero() || !xyz[1].is_zero() || !xyz[2].is_zero(); }
  bool turns() const { return !rpy[0].is_zero() || !rpy[1].is_zero() || !rpy[2].is_zero(); }
};

struct Inertial {
  Origin origin;  ///< of the mass centre and the axes the inertia is given in
  Number mass;
  Number ixx, ixy, ixz, iyy, iyz, izz;
  SourceLocation location, mass_location, inertia_location;
};

struct Visual {
  /// `unsupported`: a geometry URDF readers differ on (a capsule, say), drawn as its body's default
  enum class Kind { box, cylinder, sphere, mesh, unsupported };
  Kind kind = Kind::box;
  Origin origin;
  Triple size;          ///< box
  Number radius, length;  ///< cylinder (along z of its origin), sphere
  std::string mesh;     ///< mesh file name as written; the element's name for `unsupported`
  Triple scale;         ///< mesh: the factors along its origin's axes (1 1 1 when not written)
  SourceLocation location;
};

struct Link {
  std::string name;
  std::optional<Inertial> inertial;
  std::vector<Visual> visuals;
  /// the <collision> geometries that read as visuals do (the others are left out): drawn in
  /// place of visuals none of which can be drawn (COLLADA meshes, most often)
  std::vector<Visual> collisions;
  SourceLocation location;
};

struct Joint {
  enum class Type { revolute, continuous, prismatic, fixed, floating, planar };
  struct Mimic {
    std::string joint;
    Number multiplier{"1", 1}, offset;
    SourceLocation location;
  };
  std::string name;
  Type type = Type::fixed;
  std::string parent, child;
  Origin origin;
  Triple axis{Number{"1", 1}, Number{}, Number{}};
  SourceLocation axis_location;
  std::optional<Number> lower, upper, effort, velocity;  ///< <limit>: carried, not enforced
  std::optional<Number> damping, friction;               ///< <dynamics>; friction carried only
  SourceLocation damping_location;
  std::optional<Mimic> mimic;
  SourceLocation location, parent_location, child_location;
  bool locked = false;  ///< a moving joint made fixed (ImportOptions::fix_massless_joints)
};

/// The type as URDF writes it ("revolute", ...).
std::string type_name(Joint::Type t);

struct Robot {
  std::string name;
  std::string file;          ///< as given to the reader
  std::vector<Link> links;   ///< in file order
  std::vector<Joint> joints; ///< in file order
  SourceLocation location;
};

/// Reads URDF text. Refuses (SourceError at the place in the file) malformed XML, document type
/// declarations and entities (never expanded nor fetched), a root element that is not <robot>,
/// missing or duplicate names, unknown joint types, joints whose parent or child is no link,
/// a link with two parents, no root or more than one, cycles, numbers that are not finite,
/// negative masses and moving joints with a zero axis.
/// \throws SourceError
Robot read_robot(const std::string& text, const std::string& file);

/// The largest URDF file read, in bytes: a robot's description is kilobytes; meshes are files of
/// their own.
inline constexpr std::size_t max_urdf_bytes = 8u << 20;

}  // namespace eomgen::urdf
