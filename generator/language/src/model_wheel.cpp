// The wheel statement: a rigid disk rolling without slip on a fixed plane. Its contact point is
// built with the points (other definitions may use it); its constraints with the elements.
#include <fmt/format.h>

#include <cmath>

#include "eomgen/base/error.hpp"
#include "eomgen/mechanics/kinematics.hpp"
#include "eomgen/mechanics/lean_products.hpp"
#include "eomgen/symbolic/simplify.hpp"
#include "model_arguments.hpp"
#include "model_elaborator.hpp"

namespace eomgen::syntax {
namespace {

using GiNaC::ex;

const std::vector<std::string> wheel_arguments = {"body", "centre", "center", "axle", "radius", "normal", "plane"};

// sqrt(1 - s^2) for s = d . e, the sine of the wheel's tilt from the plane's normal. Where s is
// +-sin(X), the root is cos(X): X is then zero when the wheel stands upright and, the model's
// motion staying on the side of upright where the disk touches the plane at one point, |X| < pi/2
// (at pi/2 the disk lies flat and the contact is undefined). Any other s (+-cos(X) among them,
// whose sine's sign the model does not fix) keeps its root.
ex cosine_of_tilt(const ex& s) {
  const ex x = GiNaC::wild(0);
  GiNaC::exmap match;
  if (s.match(GiNaC::sin(x), match) || (-s).match(GiNaC::sin(x), match)) return GiNaC::cos(match[x]);
  return GiNaC::sqrt(1 - GiNaC::pow(s, 2));
}

bool has_state(const Variables& vars, const ex& e) {
  return vars.contains(e, SymbolKind::coordinate) || vars.contains(e, SymbolKind::rate) ||
         vars.contains(e, SymbolKind::input) || e.has(vars.time());
}

}  // namespace

// C = centre + r (d - (d.e) e) / sqrt(1 - (d.e)^2), e the unit axle and d = -n toward the plane:
// the point of the rim farthest along d
PointId Elaborator::wheel_contact(const Instance& in, const std::string& contact_name) {
  const Environment& env = in.environment;
  MechanicalSystem& sys = model_.system;
  const Variables& vars = sys.variables();
  const std::string what = fmt::format("wheel '{}'", resolve(in.statement->name, env));
  const Arguments args(*this, in, what, wheel_arguments);
  const PointId centre = point_named(args.name_of(args.centre("the wheel's centre, a point"), "a point"), env);

  const Argument& radius_arg = args.require("radius", "the wheel's radius");
  const ex radius = scalar(radius_arg.value, env, fmt::format("{}: 'radius'", what));
  const std::optional<double> radius_value = value_at(radius, sys.parameter_defaults());
  if (has_state(vars, radius) || !radius_value || *radius_value <= 0)
    throw SourceError(start_of(*radius_arg.value),
                      fmt::format("{}: 'radius' must be a positive constant (numbers, consts and parameters, positive "
                                  "at the parameters' default values)", what));

  const GiNaC::matrix n = plane_normal(args.require("normal", "the plane's unit normal, toward the wheel's side"),
                                       env, what);
  const eomgen::Vector down(sys.inertial_frame(), n.mul_scalar(-1));

  const Argument& axle_arg = args.require("axle", "the direction of the wheel's axle, fixed in its body");
  const eomgen::Vector axle = vector(axle_arg.value, env, fmt::format("{}: 'axle'", what));
  const ex axle_length = lean_norm(sys, axle);
  reject_zero_vector(axle, axle_length, start_of(*axle_arg.value), fmt::format("{}: 'axle'", what));
  const eomgen::Vector e = ex(1) / axle_length * axle;

  const ex s = lean_dot(sys, down, e);
  for (const GiNaC::exmap& state : generic_states()) {
    const std::optional<double> sine = value_at(s, state);
    if (sine && 1 - *sine * *sine < 1e-12)
      throw SourceError(start_of(*axle_arg.value),
                        fmt::format("{}: the axle is along the plane's normal at a generic state, so the disk lies "
                                    "flat on the plane and touches it along its whole rim: expected an axle across "
                                    "the normal", what));
  }
  const eomgen::Vector toward_contact = lean_resolved(sys, down - s * e);
  try {
    return sys.add_point(contact_name, centre, radius / cosine_of_tilt(s) * toward_contact);
  } catch (const ModelError& error) {
    throw SourceError(in.statement->name.location, error.what());
  }
}

void Elaborator::wheel(const Instance& in, const std::string& name, const std::string& what) {
  const Statement& st = *in.statement;
  const Environment& env = in.environment;
  MechanicalSystem& sys = model_.system;
  const Variables& vars = sys.variables();
  const Arguments args(*this, in, what, wheel_arguments);
  const RigidBody& body = rigid_body(args, env);

  const Argument& axle_arg = args.require("axle", "the direction of the wheel's axle, fixed in its body");
  const GiNaC::matrix axle_in_body = eomgen::resolve(sys, vector(axle_arg.value, env, what), body.frame);
  for (unsigned i = 0; i < 3; ++i)
    if (has_state(vars, simplify_for_display(axle_in_body(i, 0))))
      throw SourceError(start_of(*axle_arg.value),
                        fmt::format("{}: the axle turns relative to the body '{}': expected a direction fixed in it, "
                                    "such as one of {}.1, {}.2, {}.3", what, body.name, sys.frame(body.frame).name,
                                    sys.frame(body.frame).name, sys.frame(body.frame).name));

  const PointId plane = args.find("plane") ? args.point("plane") : sys.origin();
  const GiNaC::matrix plane_position = eomgen::resolve(sys, eomgen::position(sys, plane, sys.origin()),
                                                       sys.inertial_frame());
  for (unsigned i = 0; i < 3; ++i)
    if (has_state(vars, simplify_for_display(plane_position(i, 0))))
      throw SourceError(start_of(*args.find("plane")->value),
                        fmt::format("{}: the point 'plane' moves: expected a point fixed in the inertial frame "
                                    "(the plane does not move)", what));

  const GiNaC::matrix n = plane_normal(args.require("normal", "the plane's unit normal"), env, what);
  if (units_.active()) {
    units_.require(vector(args.require("normal", "").value, env, what),
                   args.expect("normal", dimension::none(), "a normal (a direction)"));
    units_.require(args.scalar("radius", "the wheel's radius"), args.expect("radius", dimension::m(), "a radius"));
    // the axle is normalized, so any unit will do, but one for all its components
    units_.require_consistent(GiNaC::pow(axle_in_body(0, 0), 2) + GiNaC::pow(axle_in_body(1, 0), 2) +
                                  GiNaC::pow(axle_in_body(2, 0), 2), start_of(*axle_arg.value), what);
  }
  const PointId contact = points_.at(wheel_contact_name(name));
  const auto [t1, t2] = plane_tangents(n);
  ContactForce force{name, contact, add_rolling_rows(name, no_slip_rows(body, contact, n), {t1, t2}, st.name.location),
                     column_entries(n), plane, st.name.location};

  // on the plane: n . (C - plane) = 0, where the model does not already hold C there
  const eomgen::Vector normal(sys.inertial_frame(), n);
  const eomgen::Vector height_vector = eomgen::position(sys, contact, plane);
  const ex height = lean_dot(sys, normal, height_vector);
  const std::optional<double> radius = value_at(args.scalar("radius", "the wheel's radius"), sys.parameter_defaults());
  bool on_plane = simplify_for_display(height).is_zero();
  if (!on_plane) {
    on_plane = true;
    for (const GiNaC::exmap& state : generic_states()) {
      const std::optional<double> value = value_at(height, state);
      on_plane = on_plane && value && std::fabs(*value) <= 1e-10 * radius.value_or(1.0);
    }
  }
  if (!on_plane) {
    // its multiplier is the normal force: Xi's row is n . dC/dq, the force along n at C
    force.rows.push_back({sys.constraints().size(), column_entries(n)});
    sys.add_holonomic_constraint(fmt::format("{}_3", name), height);
    model_.constraint_locations.push_back(st.name.location);
  }
  model_.contacts.push_back(std::move(force));
}

}  // namespace eomgen::syntax
