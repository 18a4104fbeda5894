#pragma once
// URDF in, model text out: `eomgen import ROBOT.urdf`, and every command given a .urdf file.
//
// The model is the robot as the language writes one by hand, readable and editable: a frame
// per link (named after it) and a coordinate per joint degree of freedom (named after the
// joint), the joint origins as written in the file, a parameter for each link's mass, mass
// centre and inertia (`upper_arm_link_mass`), an input and a generalized force per actuated
// joint, a damper per `<dynamics damping>`, a constraint per `<mimic>`, shapes from the
// box, cylinder, sphere and mesh visuals (the collision geometry for a link whose visuals are all
// meshes the animation cannot draw), and the pose of every leaf link as outputs. What the file
// says that the equations do not use (limits, efforts, friction) is kept as comments.
// docs/robots.md describes the mapping joint by joint.
#include <string>
#include <vector>

#include "eomgen/urdf/urdf_robot.hpp"

namespace eomgen::urdf {

struct ImportOptions {
  /// Replace inertias no mass distribution has (a principal moment below zero or above the sum
  /// of the other two) by the nearest one on the rule of `repair_inertia`, instead of refusing.
  bool repair_inertia = false;
  /// The root link flies free: a floating joint from the inertial frame to it (translations
  /// along a's axes, then 3-2-1 Euler angles), instead of the root fixed to the ground.
  bool floating_base = false;
  /// Make fixed, at their zero position, the moving joints that move only links without mass
  /// (a gripper's fingers published without inertia), instead of refusing them.
  bool fix_massless_joints = false;
  /// Where the written model will be: a mesh file named relative to the URDF is written
  /// relative to this directory. Empty: as written in the URDF (the model read in its place).
  std::string model_directory;
};

struct ImportResult {
  std::string text;                  ///< the model, in the model language
  std::vector<std::string> repairs;  ///< one line per inertia replaced (repair_inertia)
  std::vector<std::string> locked;   ///< one line per joint made fixed (fix_massless_joints)
};

/// The model text of a robot read by read_robot().
/// \throws SourceError at the file's place: a name that collides with another once made an
///   identifier, an inertia no body has (unless repaired), a mass of zero with an inertia, a
///   moving joint that moves no mass (a zero row of the mass matrix).
ImportResult write_model(const Robot& robot, const ImportOptions& options = {});

/// read_robot() and write_model() of a file. \throws SourceError, or Error if it cannot be read.
ImportResult import_urdf(const std::string& path, const ImportOptions& options = {});

/// Whether a path names a URDF file (it ends in .urdf, in any case).
bool is_urdf_path(const std::string& path);

}  // namespace eomgen::urdf
