// The constraint statement: `constraint NAME: LEFT = RIGHT`, both sides scalars (one row, NAME)
// or both vectors (a row per component, NAME_1, NAME_2, NAME_3), each row holonomic or
// nonholonomic by whether it holds rates (docs/model-language.md, constraint).
#include <fmt/format.h>

#include <cmath>

#include "eomgen/base/error.hpp"
#include "eomgen/mechanics/kinematics.hpp"
#include "model_constraint_rows.hpp"
#include "model_elaborator.hpp"

namespace eomgen::syntax {
namespace {

// zero within rounding at `state`: against the size of its terms, so that a sum that cancels to
// rounding counts as zero
bool vanishes_at(const GiNaC::ex& e, const GiNaC::exmap& state) {
  const std::optional<double> value = value_at(e, state);
  if (!value) return false;
  double scale = std::fabs(*value);
  if (GiNaC::is_a<GiNaC::add>(e)) {
    scale = 0;
    for (const GiNaC::ex& term : e) scale += std::fabs(value_at(term, state).value_or(0.0));
  }
  return std::fabs(*value) <= 1e-12 * scale;
}

}  // namespace

void Elaborator::constraint(const Instance& in, const std::string& name, const std::string& what) {
  const Statement& s = *in.statement;
  const Value left = evaluate(s.value, in.environment), right = evaluate(s.value2, in.environment);
  for (const auto& [side, expression] : {std::pair{&left, &s.value}, std::pair{&right, &s.value2}})
    if (side->kind != Value::Kind::scalar && side->kind != Value::Kind::vector)
      throw SourceError(start_of(**expression), fmt::format("{}: expected a scalar or a vector on each side, got {}",
                                                            what, kind_name(side->kind)));
  if (left.kind == Value::Kind::scalar && right.kind == Value::Kind::scalar) {
    if (s.has_frame)
      throw SourceError(s.frame.location, fmt::format("{}: 'in FRAME' resolves the rows of a vector constraint, and "
                                                      "both sides are scalars: expected no 'in'", what));
    const GiNaC::ex expression = left.scalar - right.scalar;
    units_.require_consistent(expression, start_of(*s.value), what);
    add_constraint_row(name, expression, s.name.location);
    return;
  }
  // a vector and a scalar: the scalar may be 0, the zero vector (velocity(p) = 0)
  const bool left_is_vector = left.kind == Value::Kind::vector;
  const Value& scalar_side = left_is_vector ? right : left;
  if (scalar_side.kind == Value::Kind::scalar && !scalar_side.scalar.is_zero())
    throw SourceError(start_of(left_is_vector ? *s.value2 : *s.value),
                      fmt::format("{}: the {} side is a vector and this one a scalar: expected a vector on both sides "
                                  "(or 0, the zero vector), or a scalar on both",
                                  what, left_is_vector ? "left" : "right"));
  const eomgen::Vector difference = right.kind == Value::Kind::scalar ? left.vector
                                    : left.kind == Value::Kind::scalar ? -right.vector
                                                                       : left.vector - right.vector;
  vector_constraint(in, name, what, difference);
}

// one row per component along FRAME.1, FRAME.2, FRAME.3, as a vector output has; a component that
// is identically zero (a planar loop's along the normal of its plane) is left out, and its number
// with it, as roll's rows are
void Elaborator::vector_constraint(const Instance& in, const std::string& name, const std::string& what,
                                   const eomgen::Vector& difference) {
  const Statement& s = *in.statement;
  const MechanicalSystem& sys = model_.system;
  const FrameId frame = s.has_frame ? frame_named(s.frame, in.environment) : sys.inertial_frame();
  const GiNaC::matrix rows = eomgen::resolve(sys, difference, frame);
  const std::vector<GiNaC::exmap> states = generic_states();
  std::size_t added = 0;
  for (unsigned i = 0; i < 3; ++i) {
    const std::string row_name = fmt::format("{}_{}", name, i + 1);
    const GiNaC::ex row = rows(i, 0);
    units_.require_consistent(row, start_of(*s.value), fmt::format("{}, row '{}'", what, row_name));
    if (row.is_zero()) continue;
    bool has_rate = false;
    for (const Coordinate& c : sys.variables().coordinates()) has_rate = has_rate || row.has(c.qd);
    const Constraint candidate{row_name, has_rate ? Constraint::Kind::nonholonomic : Constraint::Kind::holonomic, row};
    const std::optional<RateRow> rate_row = rate_row_at(candidate, sys.variables(), states.front());
    // the test of checks() for a constraint that is identically zero
    if (rate_row && rate_row->xi.norm() < 1e-12) {
      bool zero = true;
      for (const GiNaC::exmap& state : states) zero = zero && vanishes_at(row, state);
      if (zero) continue;
      throw SourceError(s.name.location,
                        fmt::format("{}: its component along {}.{} (row '{}') does not depend on the {} at a generic "
                                    "state and is not zero there, so the constraint cannot hold: expected sides "
                                    "that can be equal",
                                    what, sys.frame(frame).name, i + 1, row_name, has_rate ? "rates" : "coordinates"));
    }
    add_constraint_row(row_name, row, s.name.location);
    ++added;
  }
  if (added == 0)
    throw SourceError(s.name.location, fmt::format("{} is identically zero: each of its components vanishes at a "
                                                   "generic state", what));
}

// holonomic without rates, nonholonomic (and then linear in them) with
void Elaborator::add_constraint_row(const std::string& name, const GiNaC::ex& expression, const SourceLocation& at) {
  MechanicalSystem& sys = model_.system;
  bool has_rate = false;
  for (const Coordinate& c : sys.variables().coordinates()) has_rate = has_rate || expression.has(c.qd);
  if (has_rate)
    sys.add_nonholonomic_constraint(name, expression);
  else
    sys.add_holonomic_constraint(name, expression);
  model_.constraint_locations.push_back(at);
}

}  // namespace eomgen::syntax
