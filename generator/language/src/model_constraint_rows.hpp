#pragma once
// A constraint's row of the rate-level form Xi qd + Xi_t = 0 (docs/conventions.md) in numbers at
// a state: what the elaborator looks at to find constraints that are identically zero, redundant
// or that leave the dependent speeds unsolvable.
#include <Eigen/Dense>
#include <ginac/ginac.h>

#include <optional>

#include "eomgen/mechanics/mechanical_system.hpp"

namespace eomgen::syntax {

/// One constraint's row of Xi (dphi/dq of a holonomic one, the coefficients of the rates of a
/// nonholonomic one) and its Xi_t (dphi/dt, or what is left with the rates at zero).
struct RateRow {
  Eigen::RowVectorXd xi;
  double xi_t = 0;
};

/// The row at `state`; nothing where an entry is not a real number there (a pole, a root of a
/// negative number).
std::optional<RateRow> rate_row_at(const Constraint& c, const Variables& vars, const GiNaC::exmap& state);

/// The rows of the constraints a model keeps, in order: Xi and Xi_t at a generic state.
struct ConstraintRows {
  Eigen::MatrixXd xi;
  Eigen::VectorXd xi_t;
};

}  // namespace eomgen::syntax
