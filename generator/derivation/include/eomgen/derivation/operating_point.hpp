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

/// A given value assembly had to move: the given values admit no consistent state.
struct MovedValue {
  std::string name;
  double requested = 0.0;
  double used = 0.0;
};

struct ConstrainedPoint {
  NamedValues point;                ///< the given values and the solved ones
  std::vector<std::string> solved;  ///< the names solved, coordinates (in order) then rates
  std::vector<MovedValue> moved;    ///< given values that could not be kept, in the same order
};

/// Completes `given` (names as in numeric_substitution; a name left out is its guess, else 0)
/// so that it satisfies the constraints, phi(q, t) = 0 and Xi qd + Xi_t = 0, by the runtime's
/// assembly (eomrt/assembly.hpp, docs/conventions.md "Assembly"): the consistent state nearest
/// the given values and the guesses, keeping every given value where that is possible.
///
/// A point that satisfies a set of constraints already is left as it is. Otherwise the names
/// left out are solved, from their guesses, moving them as little as possible (weighted by M's
/// diagonal); the rates of the declared independent speeds (`independent`) that are not given
/// stay at their guesses where the constraints allow it. Where the given values admit no
/// solution, they move too, as little as they must, and `moved` lists them.
/// \throws Error naming the constraint with the largest residual if no consistent state is
///   found near the point, or where a term is not finite
ConstrainedPoint satisfy_constraints(const Model& model, const ModelEquations& eom, const NamedValues& given,
                                     const NamedValues& guesses = {});

/// The same with the equations at a point from `evaluate` (which must give M, Xi, Xi_t and
/// phi): a compiled evaluation where many points are completed.
ConstrainedPoint satisfy_constraints(const Model& model,
                                     const std::function<NumericEquations(const NamedValues&)>& evaluate,
                                     const NamedValues& given, const NamedValues& guesses = {});

/// The text of a `moved` list, "q1 = 0.5 (given 0.49, moved by 0.01), ..." for messages.
std::string describe_moved(const std::vector<MovedValue>& moved);

}  // namespace eomgen
