#pragma once
// The links of a system arranged as a kinematic tree, when its coordinates map to one: what the
// articulated-body algorithm (articulated_body.hpp) needs. The test is structural and
// conservative: a model it rejects keeps M and F.
#include <ginac/ginac.h>

#include <cstddef>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "eomgen/mechanics/mechanical_system.hpp"

namespace eomgen {

/// A rigid body, or a particle (inertia zero, frame the one it hangs from).
struct Link {
  std::string name;
  GiNaC::ex mass;
  GiNaC::matrix inertia;  ///< J about the mass centre, resolved in `frame`
  FrameId frame;
  PointId centre;
  /// The point the recursions refer the link's motion and loads to: the one nearest the root of
  /// the point tree that is still fixed in the link (the hinge of a pendulum, where a revolute
  /// joint's motion subspace has no linear part); the centre when no other is.
  PointId origin;
  /// The link it moves relative to: none for the ground (inertial frame, origin).
  std::optional<std::size_t> parent;
  /// J(i): the coordinates of the joint to the parent, in model order; empty for a link
  /// rigidly attached to its parent.
  std::vector<std::size_t> joint;
};

/// Links in an order where every parent comes before its children.
struct LinkTree {
  std::vector<Link> links;
};

/// The system's links as a tree, or the reason why they do not form one whose joint i moves
/// the link i relative to its parent through the coordinates J(i) only.
std::variant<LinkTree, std::string> link_tree(const MechanicalSystem& system);

/// The tree of the system's bodies whatever its constraints: what M and F, which constraints do
/// not change (they enter as Xi^T lambda), are computed on. A model with constraints has no
/// recursive forward dynamics, which link_tree() refuses it for.
std::variant<LinkTree, std::string> link_tree_of_bodies(const MechanicalSystem& system);

}  // namespace eomgen
