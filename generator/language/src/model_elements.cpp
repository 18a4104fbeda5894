// Element statements of a model file (bodies, loads, constraints, outputs) -> MechanicalSystem.
#include <fmt/format.h>

#include <algorithm>

#include "eomgen/base/error.hpp"
#include "eomgen/mechanics/kinematics.hpp"
#include "eomgen/symbolic/simplify.hpp"
#include "model_elaborator.hpp"

namespace eomgen::syntax {

using GiNaC::ex;
using Kind = Statement::Kind;

// the key = value arguments of an element statement, checked against what the statement takes
class Elaborator::Arguments {
 public:
  Arguments(Elaborator& elaborator, const Instance& in, std::string what, std::vector<std::string> allowed)
      : elaborator_(elaborator), s_(*in.statement), env_(in.environment), what_(std::move(what)),
        allowed_(std::move(allowed)) {
    for (const Argument& a : s_.arguments) {
      if (std::find(allowed_.begin(), allowed_.end(), a.key) == allowed_.end())
        throw SourceError(a.location, fmt::format("{}: unknown argument '{}'; expected {}", what_, a.key, list()));
      for (const Argument& b : s_.arguments)
        if (&b != &a && b.key == a.key && &b > &a)
          throw SourceError(b.location, fmt::format("{}: argument '{}' is given twice", what_, a.key));
    }
  }
  const Argument* find(const std::string& key) const {
    for (const Argument& a : s_.arguments)
      if (a.key == key) return &a;
    return nullptr;
  }
  const Argument& require(const std::string& key, const std::string& hint) const {
    if (const Argument* a = find(key)) return *a;
    throw SourceError(s_.location, fmt::format("{}: missing argument '{}' ({})", what_, key, hint));
  }
  const Name& name_of(const Argument& a, const std::string& expected) const {
    if (a.value->kind != Expr::Kind::name)
      throw SourceError(a.value->location, fmt::format("{}: argument '{}' must name {}", what_, a.key, expected));
    return a.value->name;
  }
  PointId point(const char* key) const {
    return elaborator_.point_named(name_of(require(key, "a point"), "a point"), env_);
  }
  FrameId frame(const char* key, const char* hint) const {
    return elaborator_.frame_named(name_of(require(key, hint), "a frame"), env_);
  }
  GiNaC::ex scalar(const char* key, const char* hint) const {
    return elaborator_.scalar(require(key, hint).value, env_, fmt::format("{}: '{}'", what_, key));
  }
  GiNaC::ex optional_scalar(const char* key) const {
    const Argument* a = find(key);
    return a ? elaborator_.scalar(a->value, env_, fmt::format("{}: '{}'", what_, key)) : GiNaC::ex(0);
  }
  eomgen::Vector vector(const char* key) const {
    return elaborator_.vector(require(key, "a vector").value, env_, what_);
  }

 private:
  std::string list() const {
    std::string out;
    for (std::size_t i = 0; i < allowed_.size(); ++i) out += (i ? ", " : "") + allowed_[i];
    return out;
  }
  Elaborator& elaborator_;
  const Statement& s_;
  const Environment& env_;
  std::string what_;
  std::vector<std::string> allowed_;
};

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
      sys.add_particle(name, args.scalar("mass", "the particle's mass"), args.point("at"));
      break;
    }
    case Kind::body: body(in, name, what); break;
    case Kind::gravity:
      if (!sys.gravity().is_zero()) throw SourceError(s.location, "gravity is given twice");
      sys.set_gravity(vector(s.value, in.environment, "gravity"));
      break;
    case Kind::force: {
      const Arguments args(*this, in, what, {"at", "force"});
      sys.add_force(args.point("at"), args.vector("force"));
      break;
    }
    case Kind::moment: {
      const Arguments args(*this, in, what, {"on", "moment"});
      const FrameId f = args.frame("on", "the body frame");
      sys.add_moment(f, args.vector("moment"));
      break;
    }
    case Kind::spring: {
      const Arguments args(*this, in, what, {"from", "to", "stiffness", "length"});
      sys.add_spring(name, args.point("from"), args.point("to"), args.scalar("stiffness", "k"),
                     args.optional_scalar("length"));
      break;
    }
    case Kind::damper: damper(in, name, what); break;
    case Kind::torsion: {
      const Arguments args(*this, in, what, {"angle", "stiffness", "rest"});
      sys.add_torsional_spring(name, args.scalar("angle", "an angle expression"), args.scalar("stiffness", "k"),
                               args.optional_scalar("rest"));
      break;
    }
    case Kind::potential: sys.add_potential(name, scalar(s.value, in.environment, what)); break;
    case Kind::generalized_force: generalized_force(in, what); break;
    case Kind::constraint: constraint(in, name, what); break;
    case Kind::roll: roll(in); break;
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
  const Argument* centre = args.find("centre") ? args.find("centre") : args.find("center");
  if (!centre) args.require("centre", "the mass centre, a point");
  const PointId c = point_named(args.name_of(*centre, "a point"), in.environment);
  const FrameId f = args.frame("frame", "the body frame");
  const Argument& inertia = args.require("inertia", "the inertia matrix about the mass centre in the body "
                                                    "frame, e.g. inertia = diag(J1, J2, J3)");
  const Value J = evaluate(inertia.value, in.environment);
  if (J.kind != Value::Kind::matrix || J.matrix.rows() != 3 || J.matrix.cols() != 3)
    throw SourceError(inertia.value->location, fmt::format("{}: 'inertia' must be a 3x3 matrix, e.g. diag(J1, J2, J3)", what));
  model_.system.add_rigid_body(name, mass, c, f, J.matrix);
}

void Elaborator::damper(const Instance& in, const std::string& name, const std::string& what) {
  const Arguments args(*this, in, what, {"from", "to", "on", "damping"});
  const ex c = args.scalar("damping", "the damping coefficient");
  if (const Argument* on = args.find("on")) {
    if (args.find("from") || args.find("to"))
      throw SourceError(in.statement->location,
                        fmt::format("{}: give either 'on' (a coordinate expression) or 'from' and 'to' (points)", what));
    model_.system.add_coordinate_damper(name, scalar(on->value, in.environment, what), c);
  } else {
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
  sys.add_generalized_force(*sys.variables().coordinate_index(*symbol), args.scalar("value", "the force"));
}

void Elaborator::constraint(const Instance& in, const std::string& name, const std::string& what) {
  const Statement& s = *in.statement;
  MechanicalSystem& sys = model_.system;
  const ex expression = scalar(s.value, in.environment, what) - scalar(s.value2, in.environment, what);
  bool has_rate = false;
  for (const auto& c : sys.variables().coordinates()) has_rate = has_rate || expression.has(c.qd);
  if (has_rate) {
    sys.add_nonholonomic_constraint(name, expression);
  } else {
    sys.add_holonomic_constraint(name, expression);
  }
  model_.constraint_locations.push_back(s.name.location);
}

void Elaborator::roll(const Instance& in) {
  const Statement& s = *in.statement;
  const Environment& env = in.environment;
  MechanicalSystem& sys = model_.system;
  const std::string name = resolve(s.name, env);
  const std::string what = fmt::format("roll '{}'", name);
  const Arguments args(*this, in, what, {"body", "contact", "normal"});
  const Argument& body_arg = args.require("body", "the rolling rigid body");
  const std::string body_name = resolve(args.name_of(body_arg, "a rigid body"), env);
  const RigidBody* body = nullptr;
  for (const RigidBody& b : sys.rigid_bodies())
    if (b.name == body_name) body = &b;
  if (!body) {
    std::vector<std::string> bodies;
    for (const RigidBody& b : sys.rigid_bodies()) bodies.push_back(b.name);
    unknown_name(body_name, body_arg.value->location, bodies, "rigid body");
  }
  const PointId contact = point_named(args.name_of(args.require("contact", "the contact point"), "a point"), env);
  // the material point of the body at the contact has zero velocity (fixed surface)
  const eomgen::Vector slip = eomgen::velocity(sys, body->mass_centre) +
                              eomgen::cross(sys, eomgen::angular_velocity(sys, body->frame, sys.inertial_frame()),
                                            eomgen::position(sys, contact, body->mass_centre));
  std::vector<ex> rows;
  if (const Argument* normal = args.find("normal")) {
    const GiNaC::matrix n = eomgen::resolve(sys, vector(normal->value, env, what), sys.inertial_frame());
    for (unsigned i = 0; i < 3; ++i)
      if (!GiNaC::is_a<GiNaC::numeric>(n(i, 0).evalf()))
        throw SourceError(normal->value->location, fmt::format("{}: the plane's normal must be a constant vector", what));
    // two tangent directions: n x e and n x (n x e), e the axis least aligned with n
    unsigned least = 0;
    for (unsigned i = 1; i < 3; ++i)
      if (GiNaC::abs(n(i, 0)).evalf() < GiNaC::abs(n(least, 0)).evalf()) least = i;
    const GiNaC::matrix t1 = cross_matrix(n).mul(unit_column(static_cast<int>(least) + 1));
    const GiNaC::matrix t2 = cross_matrix(n).mul(t1);
    const GiNaC::matrix v = eomgen::resolve(sys, slip, sys.inertial_frame());
    for (const GiNaC::matrix& t : {t1, t2}) rows.push_back(t(0, 0) * v(0, 0) + t(1, 0) * v(1, 0) + t(2, 0) * v(2, 0));
  } else {
    const GiNaC::matrix v = eomgen::resolve(sys, slip, sys.inertial_frame());
    for (unsigned i = 0; i < 3; ++i) rows.push_back(v(i, 0));
  }
  int index = 0;
  for (const ex& row : rows) {
    ++index;
    if (simplify_for_display(row).is_zero()) continue;
    sys.add_nonholonomic_constraint(fmt::format("{}_{}", name, index), row);
    model_.constraint_locations.push_back(s.name.location);
  }
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
  for (const ex& c : out.components) model_.system.variables().require_known_symbols(c, fmt::format("output '{}'", name));
  model_.outputs.push_back(std::move(out));
}

}  // namespace eomgen::syntax
