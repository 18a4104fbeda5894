// Element statements of a model file (bodies, loads, constraints, outputs) -> MechanicalSystem.
#include <fmt/format.h>

#include <algorithm>

#include "eomgen/base/error.hpp"
#include "eomgen/mechanics/kinematics.hpp"
#include "eomgen/symbolic/simplify.hpp"
#include "model_arguments.hpp"
#include "model_elaborator.hpp"
#include "model_matrices.hpp"

namespace eomgen::syntax {

using GiNaC::ex;
using Kind = Statement::Kind;

void Elaborator::element(const Instance& in) {
  const Statement& s = *in.statement;
  const std::string name = s.kind == Kind::gravity ? std::string("gravity") : resolve(s.name, in.environment);
  const std::string what = fmt::format("{} '{}'", statement_word(s.kind), name);
  if (s.kind != Kind::gravity && s.kind != Kind::output) declare(name, statement_word(s.kind), s.name.location);
  // what the C++ API rejects is reported at the statement's name
  const SourceLocation& at = s.name.location.line ? s.name.location : s.location;
  try {
    add_element(in, name, what);
  } catch (const ModelError& e) {
    throw SourceError(at, e.what());
  } catch (const DerivationError& e) {
    throw SourceError(at, e.what());
  } catch (const GiNaC::pole_error&) {  // e.g. a mass 1/l with l = 0, evaluated at the defaults
    throw SourceError(at, fmt::format("{}: division by zero at the parameters' default values: expected finite values",
                                      what));
  }
}

void Elaborator::add_element(const Instance& in, const std::string& name, const std::string& what) {
  const Statement& s = *in.statement;
  MechanicalSystem& sys = model_.system;
  switch (s.kind) {
    case Kind::particle: {
      const Arguments args(*this, in, what, {"mass", "at"});
      const ex mass = args.scalar("mass", "the particle's mass");
      units_.require(mass, args.expect("mass", dimension::kg(), "a mass"));
      sys.add_particle(name, mass, args.point("at"));
      break;
    }
    case Kind::body: body(in, name, what); break;
    case Kind::gravity:
      if (!sys.gravity().is_zero()) throw SourceError(s.location, "gravity is given twice");
      sys.set_gravity(vector(s.value, in.environment, "gravity"));
      units_.require(sys.gravity(), UnitChecks::expect(dimension::m() / (dimension::s() * dimension::s()),
                                                       start_of(*s.value), "gravity", "gravity (an acceleration)"));
      break;
    case Kind::force: {
      const Arguments args(*this, in, what, {"at", "force"});
      const eomgen::Vector force = args.vector("force");
      units_.require(force, args.expect("force", dimension::newton(), "a force"));
      sys.add_force(args.point("at"), force);
      break;
    }
    case Kind::moment: {
      const Arguments args(*this, in, what, {"on", "moment"});
      const FrameId f = args.frame("on", "the body frame");
      // the bodies are built before every other element, so all are known here
      const auto& bodies = sys.rigid_bodies();
      if (std::none_of(bodies.begin(), bodies.end(), [&](const RigidBody& b) { return b.frame == f; })) {
        std::string frames;
        for (const RigidBody& b : bodies) frames += fmt::format("{}'{}' ({})", frames.empty() ? "" : ", ",
                                                               sys.frame(b.frame).name, b.name);
        throw SourceError(args.require("on", "").value->location,
                          fmt::format("{}: no body has the frame '{}', so the moment would act on nothing: expected "
                                      "the frame of a body{}", what, sys.frame(f).name,
                                      bodies.empty() ? " (the model has none)" : ": " + frames));
      }
      const eomgen::Vector moment = args.vector("moment");
      units_.require(moment, args.expect("moment", dimension::joule(), "a moment", "N m"));
      sys.add_moment(f, moment);
      break;
    }
    case Kind::spring: {
      const Arguments args(*this, in, what, {"from", "to", "stiffness", "length"});
      const ex stiffness = args.scalar("stiffness", "k"), length = args.optional_scalar("length");
      units_.require(stiffness, args.expect("stiffness", dimension::newton() / dimension::m(), "a spring's stiffness"));
      if (args.find("length")) units_.require(length, args.expect("length", dimension::m(), "a spring's length"));
      sys.add_spring(name, args.point("from"), args.point("to"), stiffness, length);
      break;
    }
    case Kind::damper: damper(in, name, what); break;
    case Kind::torsion: {
      const Arguments args(*this, in, what, {"angle", "stiffness", "rest"});
      const ex angle = args.scalar("angle", "an angle expression"), stiffness = args.scalar("stiffness", "k");
      const ex rest = args.optional_scalar("rest");
      units_.require_consistent(angle, args.expect("angle", dimension::none(), "").at, what);
      units_.require(stiffness, args.expect("stiffness", dimension::joule(), "a torsion spring's stiffness (J per "
                                            "the angle's unit squared)", "J").per(angle, -2));
      if (args.find("rest")) units_.require(rest, args.expect("rest", dimension::none(), "a rest angle (the angle's "
                                                              "unit)").per(angle, 1));
      sys.add_torsional_spring(name, angle, stiffness, rest);
      break;
    }
    case Kind::potential: {
      const ex potential = scalar(s.value, in.environment, what);
      units_.require(potential, UnitChecks::expect(dimension::joule(), start_of(*s.value), what, "an energy", "J"));
      sys.add_potential(name, potential);
      break;
    }
    case Kind::generalized_force: generalized_force(in, what); break;
    case Kind::constraint: constraint(in, name, what); break;
    case Kind::roll: roll(in); break;
    case Kind::wheel: wheel(in, name, what); break;
    case Kind::shape: shape(in, name, what); break;
    case Kind::output: output(in); break;
    case Kind::model:
    case Kind::description:
    case Kind::constant:
    case Kind::loop:
    case Kind::parameter:
    case Kind::coordinate:
    case Kind::input:
    case Kind::frame:
    case Kind::point:
    case Kind::independent:
      EOMGEN_UNREACHABLE(fmt::format("element(): '{}' is elaborated by another pass of run()", statement_word(s.kind)));
  }
}

void Elaborator::body(const Instance& in, const std::string& name, const std::string& what) {
  const Arguments args(*this, in, what, {"mass", "centre", "center", "frame", "inertia"});
  const ex mass = args.scalar("mass", "the body's mass");
  const PointId c = point_named(args.name_of(args.centre("the mass centre, a point"), "a point"), in.environment);
  const FrameId f = args.frame("frame", "the body frame");
  const Argument& inertia = args.require("inertia", "the inertia matrix about the mass centre in the body "
                                                    "frame, e.g. inertia = diag(J1, J2, J3)");
  const Value J = evaluate(inertia.value, in.environment);
  if (J.kind != Value::Kind::matrix || J.matrix.rows() != 3 || J.matrix.cols() != 3)
    throw SourceError(start_of(*inertia.value), fmt::format("{}: 'inertia' must be a 3x3 matrix, e.g. diag(J1, J2, J3), "
                                                            "got {}", what, shape_name(J)));
  units_.require(mass, args.expect("mass", dimension::kg(), "a mass"));
  units_.require(J.matrix, args.expect("inertia", dimension::kg() * dimension::m() * dimension::m(), "an inertia"));
  model_.system.add_rigid_body(name, mass, c, f, J.matrix);
}

void Elaborator::damper(const Instance& in, const std::string& name, const std::string& what) {
  const Arguments args(*this, in, what, {"from", "to", "on", "damping"});
  const ex c = args.scalar("damping", "the damping coefficient");
  if (const Argument* on = args.find("on")) {
    if (args.find("from") || args.find("to"))
      throw SourceError(in.statement->location,
                        fmt::format("{}: give either 'on' (a coordinate expression) or 'from' and 'to' (points)", what));
    const ex e = scalar(on->value, in.environment, what);
    // the power c (de/dt)^2 is W
    units_.require_consistent(e, start_of(*on->value), what);
    units_.require(c, args.expect("damping", dimension::joule() * dimension::s(), "a damping (W per the squared rate "
                                  "of 'on')").per(e, -2));
    model_.system.add_coordinate_damper(name, e, c);
  } else {
    units_.require(c, args.expect("damping", dimension::newton() * dimension::s() / dimension::m(), "a damping", "N s/m"));
    model_.system.add_damper(name, args.point("from"), args.point("to"), c);
  }
}

void Elaborator::generalized_force(const Instance& in, const std::string& what) {
  MechanicalSystem& sys = model_.system;
  const Arguments args(*this, in, what, {"on", "value"});
  const Argument& on = args.require("on", "a coordinate");
  const std::string coordinate = resolve(args.name_of(on, "a coordinate"), in.environment);
  const auto symbol = sys.variables().find(coordinate);
  if (!symbol || sys.variables().kind_of(*symbol) != SymbolKind::coordinate)
    throw SourceError(on.value->location, fmt::format("{}: '{}' is not a coordinate", what, coordinate));
  used_coordinates_.insert(coordinate);
  const ex value = args.scalar("value", "the force");
  units_.require(value, args.expect("value", dimension::joule(), "a generalized force (J per the unit of 'on')")
                            .per(*symbol, -1));
  sys.add_generalized_force(*sys.variables().coordinate_index(*symbol), value);
}

const RigidBody& Elaborator::rigid_body(const Arguments& args, const Environment& env) {
  const Argument& body_arg = args.require("body", "the rolling rigid body");
  const std::string body_name = resolve(args.name_of(body_arg, "a rigid body"), env);
  for (const RigidBody& b : model_.system.rigid_bodies())
    if (b.name == body_name) return b;
  std::vector<std::string> bodies;
  for (const RigidBody& b : model_.system.rigid_bodies()) bodies.push_back(b.name);
  // particles are declared in file order with the other elements, after every body
  std::string kind = declared_.count(body_name) ? declared_.at(body_name).kind : "";
  for (const Particle& p : model_.system.particles())
    if (p.name == body_name) kind = "particle";
  if (!kind.empty())
    throw SourceError(body_arg.value->location, fmt::format("'{}' is a {}, not a rigid body: expected the name of a "
                                                            "'body' statement (it turns, so it needs a frame)",
                                                            body_name, kind));
  unknown_name(body_name, body_arg.value->location, bodies, "rigid body");
}

GiNaC::matrix Elaborator::plane_normal(const Argument& normal, const Environment& env, const std::string& what) {
  const MechanicalSystem& sys = model_.system;
  const GiNaC::matrix n = eomgen::resolve(sys, vector(normal.value, env, what), sys.inertial_frame());
  ex square = 0;
  for (unsigned i = 0; i < 3; ++i) {
    if (!GiNaC::is_a<GiNaC::numeric>(n(i, 0).evalf()))
      throw SourceError(start_of(*normal.value), fmt::format("{}: the plane's normal must be a constant vector (numbers "
                                                             "and consts only)", what));
    square += GiNaC::pow(n(i, 0), 2);
  }
  if (GiNaC::ex_to<GiNaC::numeric>(square.evalf()).to_double() < 1e-24)
    throw SourceError(start_of(*normal.value), fmt::format("{}: the plane's normal is zero: expected a non-zero "
                                                           "vector", what));
  // unit, so that the rows of Xi do not scale with it and the multipliers are forces
  return n.mul_scalar(1 / GiNaC::sqrt(square));
}

// The plane's tangents t1 = unit(n x e), t2 = n x t1, e the inertial axis least aligned with n
// (the first of equals): (t1, t2, n) is right-handed and constant. For n = a.3, t1 = a.2 and
// t2 = -a.1.
std::array<GiNaC::matrix, 2> plane_tangents(const GiNaC::matrix& n) {
  unsigned least = 0;
  for (unsigned i = 1; i < 3; ++i)
    if (GiNaC::abs(n(i, 0)).evalf() < GiNaC::abs(n(least, 0)).evalf()) least = i;
  const GiNaC::matrix across = cross_matrix(n).mul(unit_column(static_cast<int>(least) + 1));
  const ex length = GiNaC::sqrt(GiNaC::pow(across(0, 0), 2) + GiNaC::pow(across(1, 0), 2) + GiNaC::pow(across(2, 0), 2));
  const GiNaC::matrix t1 = across.mul_scalar(1 / length);
  return {t1, cross_matrix(n).mul(t1)};
}

// t1 . v and t2 . v for the velocity v of the body's material point at the contact
std::vector<ex> Elaborator::no_slip_rows(const RigidBody& body, PointId contact, const GiNaC::matrix& n) {
  const MechanicalSystem& sys = model_.system;
  const GiNaC::matrix v = eomgen::resolve(sys, material_velocity(body, contact), sys.inertial_frame());
  std::vector<ex> rows;
  for (const GiNaC::matrix& t : plane_tangents(n))
    rows.push_back(t(0, 0) * v(0, 0) + t(1, 0) * v(1, 0) + t(2, 0) * v(2, 0));
  return rows;
}

// the velocity of the body's material point at `at`: v^c + omega^body x r^{at, c}
eomgen::Vector Elaborator::material_velocity(const RigidBody& body, PointId at) const {
  const MechanicalSystem& sys = model_.system;
  return eomgen::velocity(sys, body.mass_centre) +
         eomgen::cross(sys, eomgen::angular_velocity(sys, body.frame, sys.inertial_frame()),
                       eomgen::position(sys, at, body.mass_centre));
}

// rows NAME_1, NAME_2... in order; a row that is identically zero is left out, and its number with
// it. Returns the rows added, each with its direction (3x1, inertial) from `directions`.
std::vector<ContactForce::Row> Elaborator::add_rolling_rows(const std::string& name, const std::vector<ex>& rows,
                                                            const std::vector<GiNaC::matrix>& directions,
                                                            const SourceLocation& at) {
  EOMGEN_DEMAND(rows.size() == directions.size(), "add_rolling_rows: one direction per row");
  std::vector<ContactForce::Row> added;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    if (simplify_for_display(rows[k]).is_zero()) continue;
    added.push_back({model_.system.constraints().size(), column_entries(directions[k])});
    model_.system.add_nonholonomic_constraint(fmt::format("{}_{}", name, k + 1), rows[k]);
    model_.constraint_locations.push_back(at);
  }
  return added;
}

// The multipliers of roll: forces at the contact along t1, t2 (with a normal; the plane through
// the contact's position, which the animation takes at the first sample) or along a.1, a.2, a.3.
void Elaborator::roll(const Instance& in) {
  const Statement& s = *in.statement;
  const Environment& env = in.environment;
  MechanicalSystem& sys = model_.system;
  const std::string name = resolve(s.name, env);
  const std::string what = fmt::format("roll '{}'", name);
  const Arguments args(*this, in, what, {"body", "contact", "normal"});
  const RigidBody& body = rigid_body(args, env);
  const PointId contact = point_named(args.name_of(args.require("contact", "the contact point"), "a point"), env);
  ContactForce force{name, contact, {}, std::nullopt, contact, s.name.location};
  if (const Argument* normal = args.find("normal")) {
    if (units_.active())
      units_.require(vector(normal->value, env, what), args.expect("normal", dimension::none(), "a normal (a direction)"));
    const GiNaC::matrix n = plane_normal(*normal, env, what);
    const auto [t1, t2] = plane_tangents(n);
    force.rows = add_rolling_rows(name, no_slip_rows(body, contact, n), {t1, t2}, s.name.location);
    force.plane_normal = column_entries(n);
  } else {
    const GiNaC::matrix v = eomgen::resolve(sys, material_velocity(body, contact), sys.inertial_frame());
    force.rows = add_rolling_rows(name, {v(0, 0), v(1, 0), v(2, 0)}, {unit_column(1), unit_column(2), unit_column(3)},
                                  s.name.location);
  }
  model_.contacts.push_back(std::move(force));
}

void Elaborator::output(const Instance& in) {
  const Statement& s = *in.statement;
  const std::string name = resolve(s.name, in.environment);
  declare(name, "output", s.name.location);
  Output out{name, {}, {}, s.name.location};
  const Value v = evaluate(s.value, in.environment);
  if (v.kind == Value::Kind::scalar) {
    if (s.has_frame) throw SourceError(s.frame.location, fmt::format("output '{}': 'in FRAME' applies to vectors only", name));
    out.components.push_back(v.scalar);
    out.labels.push_back(name);
  } else if (v.kind == Value::Kind::vector) {
    const FrameId f = s.has_frame ? frame_named(s.frame, in.environment) : model_.system.inertial_frame();
    const GiNaC::matrix c = eomgen::resolve(model_.system, v.vector, f);
    for (unsigned i = 0; i < 3; ++i) {
      out.components.push_back(c(i, 0));
      out.labels.push_back(fmt::format("{}_{}", name, i + 1));
    }
  } else {
    throw SourceError(s.value->location, fmt::format("output '{}': expected a scalar or a vector, got {}", name, kind_name(v.kind)));
  }
  for (const ex& c : out.components) {
    model_.system.variables().require_known_symbols(c, fmt::format("output '{}'", name));
    units_.require_consistent(c, start_of(*s.value), fmt::format("output '{}'", name));
  }
  model_.outputs.push_back(std::move(out));
}

}  // namespace eomgen::syntax
