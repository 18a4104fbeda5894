#pragma once
// The mass matrix of a URDF robot in numbers at one configuration, from the file's own
// kinematics (T_child = T_parent T(origin) motion(q)) and the bodies' Jacobians,
// M = sum_b m_b Jv_b^T Jv_b + Jw_b^T J_b Jw_b: for refusing a robot whose mass matrix is
// singular at every state, naming the joint, before any model is written. Independent of the
// model language and its derivation, which then derive the same matrix symbolically.
#include <Eigen/Dense>

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "eomgen/urdf/urdf_robot.hpp"

namespace eomgen::urdf {

struct BodyData {
  double mass = 0;
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  ///< about the mass centre, in the inertial origin's axes
};

/// Robots of more coordinates are not checked (their mass matrix would not be derived either).
inline constexpr std::size_t largest_checked = 400;

/// The first joint, in `order` (parents before children), whose coordinates make the mass
/// matrix singular at a generic configuration (null for robots of more than largest_checked), given the joints before it: a joint that moves
/// no inertia, or only as joints before it already do. The coordinates of a joint that mimics
/// another count as the other's (multiplier times its column). Null if M is regular there.
/// `body` gives the mass and inertia a link has in the model (none: no body). A joint of `order`
/// whose parent is "" joins its child to the world (the floating base of a robot).
const Joint* first_singular_joint(const Robot& robot, const std::vector<const Joint*>& order,
                                  const std::function<std::optional<BodyData>(const Link&)>& body);

}  // namespace eomgen::urdf
