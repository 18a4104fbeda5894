#pragma once
// The tangent space of a constrained model's state at a point on its constraints: independent
// coordinates (one dependent coordinate per holonomic constraint) and independent speeds (one
// dependent rate per constraint), in which the linear model needs no multipliers. Private to
// the derivation layer.
#include <Eigen/Dense>

#include <vector>

#include "eomgen/mechanics/model.hpp"

namespace eomgen {

/// Independent coordinates and speeds at a point on the constraints: the full state's
/// perturbations on the tangent space are dx = T dz, and P picks z out of x (P T = 1).
struct TangentSpace {
  std::vector<Eigen::Index> q_dependent, q_kept;       ///< one dependent coordinate per holonomic constraint
  std::vector<Eigen::Index> v_dependent, v_independent;  ///< one dependent rate per constraint
  Eigen::MatrixXd T, P;
};

/// The tangent space at the point: dqd = Gq dq + Gv dnu (dnu the independent rates), with the
/// dependent rates the complement of the declared independent speeds, else pivoted QR of Xi.
/// \throws Error if the declared independent speeds leave a singular block of Xi
TangentSpace tangent_space(const Model& model, const Eigen::MatrixXd& Xi, const Eigen::MatrixXd& C_q);

/// The holonomic constraints' rows of Xi, in order.
std::vector<Eigen::Index> holonomic_rows_of(const Model& model);

}  // namespace eomgen
