#pragma once
// An operating point of a constrained model completed from what the user gives: the
// coordinates and rates the constraints determine are solved, not typed in by hand (a rolling
// wheel's spin from its forward speed, a bicycle's pitch from its lean and steer).
#include <functional>
#include <string>
#include <vector>

#include "eomgen/derivation/model_equations.hpp"
#include "eomgen/derivation/numeric_evaluation.hpp"

namespace eomgen {

/// How far a point may be off the constraints, relative to the size of their terms, and how
/// small a column of A must be for its state to count as something nothing depends on: one
/// tolerance, so that a point the constraint check accepts never leaves a spurious coupling
/// (an eigenvalue of 1e-12 beside a cyclic coordinate) behind.
inline constexpr double operating_point_tolerance = 1e-9;

struct ConstrainedPoint {
  NamedValues point;                ///< the given values and the solved ones
  std::vector<std::string> solved;  ///< the names solved, coordinates (in order) then rates
};

/// Completes `given` (names as in numeric_substitution; a name left out is 0) so that it
/// satisfies the constraints: phi(q, t) = 0 and Xi qd + Xi_t = 0.
///
/// Only names the point leaves out are solved. Coordinates first: when phi is violated, one
/// coordinate per holonomic constraint, chosen among those not given by a pivoted QR of the
/// constraint gradients, found by Newton's method. Then rates: when the velocity constraints
/// are violated, the dependent rates (the complement of the model's `independent` speeds, else
/// a pivoted QR of Xi at the point) that are not given, and where some of them are given, as
/// many rates of independent speeds as still needed, picked by a pivoted QR of their columns
/// projected off the dependent ones (given x_dot of a bicycle, its rear wheel's spin). Rates of
/// other independent speeds stay 0.
/// \throws Error naming the constraint with the largest residual if the point cannot be
///   completed (the names it involves are all given, or Newton's method fails)
ConstrainedPoint satisfy_constraints(const Model& model, const ModelEquations& eom, const NamedValues& given);

/// The same with the equations at a point from `evaluate` (which must give Xi, Xi_t and phi):
/// a compiled evaluation where many points are completed.
ConstrainedPoint satisfy_constraints(const Model& model,
                                     const std::function<NumericEquations(const NamedValues&)>& evaluate,
                                     const NamedValues& given);

}  // namespace eomgen
