#pragma once
/// \file
/// Statuses of the forward-dynamics solves (ComputationInfo style: returned from the hot loop,
/// never thrown, so a controller can react and an integrator can stop with the time and state).

namespace eomrt {

/// Outcome of one forward-dynamics solve.
enum class DynamicsStatus {
  ok,                            ///< qdd (and lambda) computed
  non_finite,                    ///< M, F, Xi or b evaluated to NaN or infinity
  singular_mass_matrix,          ///< M (or the reduced Upsilon^T M Upsilon) is not positive definite
  singular_kkt_matrix,           ///< [[M, -Xi^T], [-Xi, 0]] is singular
  singular_constraint_jacobian,  ///< Xi (or its block of dependent speeds) lost rank
  projection_failed,             ///< Newton's projection onto phi = 0 did not converge
};

/// \return the enumerator's name, for messages and logs
inline const char* to_string(DynamicsStatus status) {
  switch (status) {
    case DynamicsStatus::ok:
      return "ok";
    case DynamicsStatus::non_finite:
      return "non_finite";
    case DynamicsStatus::singular_mass_matrix:
      return "singular_mass_matrix";
    case DynamicsStatus::singular_kkt_matrix:
      return "singular_kkt_matrix";
    case DynamicsStatus::singular_constraint_jacobian:
      return "singular_constraint_jacobian";
    case DynamicsStatus::projection_failed:
      return "projection_failed";
  }
  return "unknown";
}

}  // namespace eomrt
