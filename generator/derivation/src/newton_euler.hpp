#pragma once
// Inverse dynamics by the recursive Newton-Euler algorithm of a tree of bodies, and the same
// recursion split by the bodies' inertial parameters (the regressor). Both run on the tree of the
// bodies whatever the constraints (link_tree_of_bodies): M qdd - F does not depend on them.
#include <ginac/ginac.h>

#include <string>
#include <variant>
#include <vector>

#include "eomgen/mechanics/mechanical_system.hpp"
#include "eomgen/symbolic/subexpressions.hpp"

namespace eomgen {

/// M qdd - F (n x 1) by Newton-Euler: outward the accelerations with qdd, inward the forces,
/// their projections on the joints less the loads. Bound in `z`; or why the bodies do not form a tree.
std::variant<GiNaC::matrix, std::string> derive_newton_euler_torques(const MechanicalSystem& system,
                                                                     Subexpressions& z);

/// M qdd - F = Y pi + (the loads other than gravity, with their sign), for the ten inertial
/// parameters of every body: its mass m, its first moment m c about its link's origin and its
/// inertia about that origin, resolved in its frame, in the order m, mx, my, mz, Ixx, Ixy, Iyy,
/// Ixz, Iyz, Izz (Pinocchio's).
struct RegressorTerms {
  GiNaC::matrix Y;                  ///< n x 10 L, bound in the caller's intermediates
  GiNaC::matrix parameters;         ///< 10 L x 1: the model's own pi, in its parameters
  std::vector<std::string> names;   ///< "BODY.m", "BODY.mx", ...
  std::vector<std::string> origins; ///< the point each body's pi is about, one per body
};

/// The regressor of the system's bodies, bound in `z`; or why the bodies do not form a tree.
std::variant<RegressorTerms, std::string> derive_regressor(const MechanicalSystem& system, Subexpressions& z);

}  // namespace eomgen
