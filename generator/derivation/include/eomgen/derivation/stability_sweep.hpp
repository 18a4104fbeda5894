#pragma once
// Stability against one swept value (a parameter, or a value of the operating point such as a
// forward speed): the model is derived and differentiated once, then every point is only
// numbers. Where the verdict changes between two points, the change is located by bisection
// on the largest real part of the eigenvalues, which crosses zero there (the classic bicycle
// figure: the weave speed, where an oscillation stops growing, and the capsize speed).
#include <Eigen/Dense>

#include <string>
#include <vector>

#include "eomgen/derivation/linearization.hpp"

namespace eomgen {

/// NAME = FROM, FROM + STEP, ..., up to TO (inclusive to within a millionth of a step).
struct SweepRange {
  std::string name;
  double from = 0, to = 0, step = 0;
  /// \throws Error unless from, to, step are finite, step > 0, from <= to and the sweep has at
  ///   most max_sweep_points points
  std::vector<double> values() const;
};

inline constexpr std::size_t max_sweep_points = 100000;

struct SweepPoint {
  double value = 0;
  std::vector<std::string> state_names;  ///< as LinearModel::state_names (may change along the sweep)
  Eigen::VectorXcd eigenvalues;          ///< of A, sorted as assess_stability sorts them
  LinearStability linear = LinearStability::unstable;
  bool equilibrium = true;  ///< whether the accelerations vanish there (else no verdict holds)
};

/// A change of the linear verdict between two neighbouring points of the sweep.
struct StabilityChange {
  double value = 0;  ///< where the largest real part crosses zero, to within `tolerance`
  LinearStability below, above;
};

struct StabilitySweep {
  std::string name;
  std::vector<SweepPoint> points;
  std::vector<StabilityChange> changes;
};

/// Linearizes at `base` with range.name set to each value of the range (an operating-point
/// name or a parameter), and locates every change of the verdict to within `tolerance` (in
/// the swept value) by bisection. Eigenvalues that are zero at both ends of a bracket (a mode
/// nothing depends on that --drop-cyclic did not remove) are left out of the largest real
/// part. With constraints, each point is completed from `base` and the swept value afresh
/// (satisfy_constraints).
/// \throws Error as linearize does, naming the swept value where it failed
StabilitySweep sweep_stability(const Model& model, const ModelEquations& eom, const SymbolicLinearization& symbolic,
                               const NamedValues& base, const SweepRange& range, const LinearizeOptions& options,
                               double tolerance = 1e-12);

}  // namespace eomgen
