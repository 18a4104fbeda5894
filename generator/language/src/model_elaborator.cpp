// Statements of a model file -> MechanicalSystem, through the C++ API.
#include "model_elaborator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "eomgen/base/error.hpp"
#include "eomgen/mechanics/kinematics.hpp"
#include "eomgen/symbolic/simplify.hpp"

namespace eomgen::syntax {
namespace {

using GiNaC::ex;
using Kind = Statement::Kind;

const char* statement_word(Kind kind) {
  switch (kind) {
    case Kind::particle: return "particle";
    case Kind::body: return "body";
    case Kind::force: return "force";
    case Kind::moment: return "moment";
    case Kind::spring: return "spring";
    case Kind::damper: return "damper";
    case Kind::torsion: return "torsion";
    case Kind::roll: return "roll";
    case Kind::generalized_force: return "generalized_force";
    case Kind::potential: return "potential";
    case Kind::constraint: return "constraint";
    case Kind::output: return "output";
    case Kind::gravity: return "gravity";
    default: return "statement";
  }
}

// the key = value arguments of an element statement, checked against what the statement takes
class Arguments {
 public:
  Arguments(const Statement& s, std::string what, std::vector<std::string> allowed)
      : s_(s), what_(std::move(what)), allowed_(std::move(allowed)) {
    for (const Argument& a : s.arguments) {
      if (std::find(allowed_.begin(), allowed_.end(), a.key) == allowed_.end())
        throw SourceError(a.location, fmt::format("{}: unknown argument '{}'; expected {}", what_, a.key, list()));
      for (const Argument& b : s.arguments)
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

 private:
  std::string list() const {
    std::string out;
    for (std::size_t i = 0; i < allowed_.size(); ++i) out += (i ? ", " : "") + allowed_[i];
    return out;
  }
  const Statement& s_;
  std::string what_;
  std::vector<std::string> allowed_;
};

}  // namespace

Elaborator::Elaborator(std::string file, const std::map<std::string, double>& overrides)
    : file_(std::move(file)), overrides_(overrides) {
  declared_["a"] = {"frame", {file_, 0, 0}};
  declared_["w"] = {"point", {file_, 0, 0}};
  declared_["t"] = {"time", {file_, 0, 0}};
  frames_["a"] = model_.system.inertial_frame();
  points_["w"] = model_.system.origin();
}

void Elaborator::declare(const std::string& name, const std::string& kind, const SourceLocation& at) {
  if (name == "pi") throw SourceError(at, "'pi' is reserved for the constant 3.14159...");
  auto it = declared_.find(name);
  if (it != declared_.end()) {
    if (it->second.location.line == 0)
      throw SourceError(at, fmt::format("'{}' is reserved (the inertial frame is 'a', its origin 'w', time 't')", name));
    // names are declared kind by kind (consts, parameters, frames, elements...), not in file
    // order: report at the later position and name the earlier one as the first declaration
    const Declared here{kind, at};
    const bool earlier = std::make_pair(at.line, at.column) < std::make_pair(it->second.location.line,
                                                                          it->second.location.column);
    const Declared& first = earlier ? here : it->second;
    const Declared& second = earlier ? it->second : here;
    throw SourceError(second.location, fmt::format("duplicate name '{}': already declared as a {} at {}:{}:{}", name,
                                                   first.kind, first.location.file, first.location.line,
                                                   first.location.column));
  }
  declared_[name] = {kind, at};
}

void Elaborator::constants(const std::vector<Statement>& statements) {
  for (const Statement& s : statements) {
    if (s.kind != Kind::constant) continue;
    const std::string name = resolve(s.name, {});
    declare(name, "const", s.name.location);
    auto override_value = overrides_.find(name);
    if (override_value == overrides_.end()) {
      constants_[name] = constant(s.value, {}, fmt::format("const '{}'", name));
    } else {
      // whole numbers stay exact integers, so they can bound loops
      const double v = override_value->second;
      constants_[name] = v == std::floor(v) && std::fabs(v) < 1e15 ? ex(GiNaC::numeric(static_cast<long>(v)))
                                                                   : ex(GiNaC::numeric(v));
    }
    // Model::constants reports them (after overrides) to the caller, e.g. the n of a chain
    model_.constants[name] = GiNaC::ex_to<GiNaC::numeric>(constants_[name].evalf()).to_double();
  }
  for (const auto& [name, value] : overrides_)
    if (!constants_.count(name)) {
      std::string known;
      for (const auto& [k, v] : constants_) known += (known.empty() ? "" : ", ") + k;
      throw SourceError({file_, 1, 1}, fmt::format("--define {}: the model has no const named '{}'; expected {}", name,
                                                   name, known.empty() ? "no --define (it declares no const)"
                                                                       : "one of its consts: " + known));
    }
}

void Elaborator::flatten(const std::vector<Statement>& statements, const Environment& env) {
  for (const Statement& s : statements) {
    saw_statement_ = true;
    if (s.kind == Kind::constant) {
      if (!env.empty()) throw SourceError(s.location, "'const' must be at the top level, not inside a loop");
      continue;
    }
    if (s.kind == Kind::model || s.kind == Kind::description) {
      if (!env.empty()) throw SourceError(s.location, "'model' and 'description' must be at the top level");
      if (s.kind == Kind::model) model_.name = resolve(s.name, env);
      if (!s.text.empty()) model_.description = s.text;
      continue;
    }
    if (s.kind == Kind::loop) {
      const std::string var = resolve(s.name, env);
      if (env.count(var) || constants_.count(var) || declared_.count(var))
        throw SourceError(s.name.location, fmt::format("loop variable '{}' hides another name", var));
      const int first = integer(s.value, env, "the first value of the loop");
      const int last = integer(s.value2, env, "the last value of the loop");
      if (static_cast<long>(last) - first > 100000)  // long: the bounds may be 10^9 apart
        throw SourceError(s.location, "loop has more than 100000 iterations");
      for (int i = first; i <= last; ++i) {
        Environment inner = env;
        inner[var] = i;
        flatten(s.body, inner);
      }
      continue;
    }
    instances_.push_back(Instance{&s, env});
  }
}

void Elaborator::declarations() {
  Variables& vars = model_.system.variables();
  for (const Instance& in : instances_) {
    const Statement& s = *in.statement;
    if (s.kind == Kind::parameter) {
      const std::string name = resolve(s.name, in.environment);
      declare(name, "parameter", s.name.location);
      const double value = constant(s.value, in.environment, fmt::format("parameter '{}'", name)).to_double();
      vars.add_parameter(name, value, s.text);
    } else if (s.kind == Kind::coordinate || s.kind == Kind::input) {
      for (const Name& n : s.names) {
        const std::string name = resolve(n, in.environment);
        declare(name, s.kind == Kind::coordinate ? "coordinate" : "input", n.location);
        try {
          if (s.kind == Kind::coordinate) {
            declare(name + "_dot", "rate", n.location);
            declare(name + "_ddot", "acceleration", n.location);
            vars.add_coordinate(name);
            model_.coordinate_locations.push_back(n.location);
          } else {
            vars.add_input(name);
          }
        } catch (const ModelError& e) {
          throw SourceError(n.location, e.what());
        }
      }
    }
  }
}

void Elaborator::collect_frames_and_points() {
  for (std::size_t i = 0; i < instances_.size(); ++i) {
    const Statement& s = *instances_[i].statement;
    if (s.kind != Kind::frame && s.kind != Kind::point) continue;
    const std::string name = resolve(s.name, instances_[i].environment);
    declare(name, s.kind == Kind::frame ? "frame" : "point", s.name.location);
    (s.kind == Kind::frame ? frame_instances_ : point_instances_)[name] = i;
  }
}

// `name` is being defined while its own definition is on the stack: report the whole loop
static void reject_cycle(const char* kind, const std::string& name, const std::vector<std::string>& stack,
                         const SourceLocation& at) {
  auto start = std::find(stack.begin(), stack.end(), name);
  if (start == stack.end()) return;
  std::string cycle;
  for (auto it = start; it != stack.end(); ++it) cycle += *it + " -> ";
  throw SourceError(at, fmt::format("{} '{}' is defined through a cycle: {}{}", kind, name, cycle, name));
}

// a definition's parent is the leftmost name: `b`, `rotate(b, ...)`, `p + ...`
static const Expr* leftmost(const Expr* e) {
  while (e->kind == Expr::Kind::add || e->kind == Expr::Kind::subtract) e = e->args[0].get();
  return e;
}

FrameId Elaborator::build_frame(const std::string& name, std::vector<std::string>& stack) {
  if (auto it = frames_.find(name); it != frames_.end()) return it->second;
  const Instance& in = instances_[frame_instances_.at(name)];
  const Statement& s = *in.statement;
  const Environment& env = in.environment;
  reject_cycle("frame", name, stack, s.name.location);
  stack.push_back(name);
  const Expr& def = *s.value;
  const std::vector<std::string> kinds = {"rotate", "euler", "axis_angle", "quaternion", "rodrigues", "mrp", "dcm"};
  const bool is_call = def.kind == Expr::Kind::call && def.name.is_plain() &&
                       std::find(kinds.begin(), kinds.end(), def.name.plain()) != kinds.end();
  if (def.kind != Expr::Kind::name && !is_call)
    throw SourceError(def.location, "expected a frame definition: a parent frame, or rotate(...), euler(...), "
                                    "axis_angle(...), quaternion(...), rodrigues(...), mrp(...), dcm(...)");
  // checked before args[0] is read: `rotate()` has none
  if (is_call && (def.args.empty() || def.args[0]->kind != Expr::Kind::name))
    throw SourceError(def.location, fmt::format("{}(): expected the parent frame as the first argument", def.name.plain()));
  const Expr& parent_expr = is_call ? *def.args[0] : def;
  const std::string parent_name = resolve(parent_expr.name, env);
  FrameId parent;
  if (frame_instances_.count(parent_name)) {
    parent = build_frame(parent_name, stack);
  } else {
    parent = frame_named(parent_expr.name, env);
  }
  stack.pop_back();
  if (!is_call) return frames_[name] = parent;  // an alias of its parent

  const std::string f = def.name.plain();
  auto expect_args = [&](std::size_t n, const char* usage) {
    if (def.args.size() != n)
      throw SourceError(def.location, fmt::format("{}: expected {}, got {} argument{}", f, usage, def.args.size(),
                                                  def.args.size() == 1 ? "" : "s"));
  };
  auto col3 = [&](std::size_t i) {
    const Value v = evaluate(def.args[i], env);
    if (v.kind != Value::Kind::column || v.matrix.rows() != 3)
      throw SourceError(def.args[i]->location, fmt::format("{}(): expected a column of three scalars [x, y, z]", f));
    return v.matrix;
  };
  auto angle = [&](std::size_t i) { return scalar(def.args[i], env, fmt::format("argument {} of {}()", i + 1, f)); };
  try {
    Rotation rotation = Rotation::identity();
    if (f == "rotate") {
      expect_args(3, "rotate(PARENT, AXIS, ANGLE) with AXIS 1, 2 or 3");
      const int axis = integer(def.args[1], env, "rotate(): the axis");
      if (axis < 1 || axis > 3) throw SourceError(def.args[1]->location, fmt::format("rotate(): expected axis 1, 2 or 3, got {}", axis));
      rotation = Rotation::principal(axis, angle(2));
    } else if (f == "euler") {
      expect_args(5, "euler(PARENT, SEQUENCE, ANGLE1, ANGLE2, ANGLE3) with SEQUENCE such as 313 or 321");
      const int seq = integer(def.args[1], env, "euler(): the sequence");
      const EulerSequence sequence = [&] {
        try {  // reported at the sequence, not at euler(
          return EulerSequence::parse(std::to_string(seq));
        } catch (const ModelError& e) {
          throw SourceError(start_of(*def.args[1]), e.what());
        }
      }();
      rotation = Rotation::euler(sequence, angle(2), angle(3), angle(4));
    } else if (f == "axis_angle") {
      expect_args(3, "axis_angle(PARENT, [A1, A2, A3], ANGLE)");
      rotation = Rotation::axis_angle(col3(1), angle(2));
    } else if (f == "quaternion") {
      expect_args(3, "quaternion(PARENT, [E1, E2, E3], ETA) (scalar last)");
      rotation = Rotation::quaternion(col3(1), angle(2));
    } else if (f == "rodrigues" || f == "mrp") {
      expect_args(2, fmt::format("{}(PARENT, [P1, P2, P3])", f).c_str());
      rotation = f == "rodrigues" ? Rotation::rodrigues(col3(1)) : Rotation::modified_rodrigues(col3(1));
    } else {
      expect_args(2, "dcm(PARENT, [[C11, C12, C13], [C21, C22, C23], [C31, C32, C33]])");
      const Value m = evaluate(def.args[1], env);
      if (m.kind != Value::Kind::matrix || m.matrix.rows() != 3 || m.matrix.cols() != 3)
        throw SourceError(def.args[1]->location, "dcm(): expected a 3x3 matrix [[...], [...], [...]]");
      rotation = Rotation::explicit_matrix(m.matrix);
    }
    return frames_[name] = model_.system.add_frame(name, parent, rotation);
  } catch (const ModelError& e) {
    throw SourceError(def.location, e.what());
  }
}

PointId Elaborator::build_point(const std::string& name, std::vector<std::string>& stack) {
  if (auto it = points_.find(name); it != points_.end()) return it->second;
  const Instance& in = instances_[point_instances_.at(name)];
  const Statement& s = *in.statement;
  const Environment& env = in.environment;
  reject_cycle("point", name, stack, s.name.location);
  const Expr* parent_expr = leftmost(s.value.get());
  if (parent_expr->kind != Expr::Kind::name)
    throw SourceError(start_of(*s.value), "expected a point definition: PARENT_POINT + VECTOR");
  stack.push_back(name);
  const std::string parent_name = resolve(parent_expr->name, env);
  const PointId parent = point_instances_.count(parent_name) ? build_point(parent_name, stack)
                                                             : point_named(parent_expr->name, env);
  stack.pop_back();
  // the offset: every term right of the parent along the chain of + and -
  eomgen::Vector offset;
  for (const Expr* e = s.value.get(); e != parent_expr; e = e->args[0].get()) {
    const eomgen::Vector term = vector(e->args[1], env, fmt::format("point '{}'", name));
    offset += e->kind == Expr::Kind::add ? term : -term;
  }
  try {
    return points_[name] = parent_expr == s.value.get() ? parent : model_.system.add_point(name, parent, offset);
  } catch (const ModelError& e) {
    throw SourceError(start_of(*s.value), e.what());
  }
}

void Elaborator::element(const Instance& in) {
  const Statement& s = *in.statement;
  const Environment& env = in.environment;
  MechanicalSystem& sys = model_.system;
  const std::string name = s.kind == Kind::gravity ? std::string("gravity") : resolve(s.name, env);
  const std::string what = fmt::format("{} '{}'", statement_word(s.kind), name);
  if (s.kind != Kind::gravity && s.kind != Kind::output) declare(name, statement_word(s.kind), s.name.location);
  auto point_arg = [&](const Arguments& args, const char* key) {
    return point_named(args.name_of(args.require(key, "a point"), "a point"), env);
  };
  auto scalar_arg = [&](const Arguments& args, const char* key, const char* hint) {
    const Argument& a = args.require(key, hint);
    return scalar(a.value, env, fmt::format("{}: '{}'", what, key));
  };
  auto optional_scalar = [&](const Arguments& args, const char* key) {
    const Argument* a = args.find(key);
    return a ? scalar(a->value, env, fmt::format("{}: '{}'", what, key)) : ex(0);
  };
  try {
    switch (s.kind) {
      case Kind::particle: {
        Arguments args(s, what, {"mass", "at"});
        sys.add_particle(name, scalar_arg(args, "mass", "the particle's mass"), point_arg(args, "at"));
        break;
      }
      case Kind::body: {
        Arguments args(s, what, {"mass", "centre", "center", "frame", "inertia"});
        const ex mass = scalar_arg(args, "mass", "the body's mass");
        const Argument* centre = args.find("centre") ? args.find("centre") : args.find("center");
        if (!centre) args.require("centre", "the mass centre, a point");
        const PointId c = point_named(args.name_of(*centre, "a point"), env);
        const FrameId f = frame_named(args.name_of(args.require("frame", "the body frame"), "a frame"), env);
        const Argument& inertia = args.require("inertia", "the inertia matrix about the mass centre in the body "
                                                          "frame, e.g. inertia = diag(J1, J2, J3)");
        const Value J = evaluate(inertia.value, env);
        if (J.kind != Value::Kind::matrix || J.matrix.rows() != 3 || J.matrix.cols() != 3)
          throw SourceError(inertia.value->location, fmt::format("{}: 'inertia' must be a 3x3 matrix, e.g. diag(J1, J2, J3)", what));
        sys.add_rigid_body(name, mass, c, f, J.matrix);
        break;
      }
      case Kind::gravity:
        if (!sys.gravity().is_zero()) throw SourceError(s.location, "gravity is given twice");
        sys.set_gravity(vector(s.value, env, "gravity"));
        break;
      case Kind::force: {
        Arguments args(s, what, {"at", "force"});
        sys.add_force(point_arg(args, "at"), vector(args.require("force", "a vector").value, env, what));
        break;
      }
      case Kind::moment: {
        Arguments args(s, what, {"on", "moment"});
        const FrameId f = frame_named(args.name_of(args.require("on", "the body frame"), "a frame"), env);
        sys.add_moment(f, vector(args.require("moment", "a vector").value, env, what));
        break;
      }
      case Kind::spring: {
        Arguments args(s, what, {"from", "to", "stiffness", "length"});
        sys.add_spring(name, point_arg(args, "from"), point_arg(args, "to"), scalar_arg(args, "stiffness", "k"),
                       optional_scalar(args, "length"));
        break;
      }
      case Kind::damper: {
        Arguments args(s, what, {"from", "to", "on", "damping"});
        const ex c = scalar_arg(args, "damping", "the damping coefficient");
        if (const Argument* on = args.find("on")) {
          if (args.find("from") || args.find("to"))
            throw SourceError(s.location, fmt::format("{}: give either 'on' (a coordinate expression) or 'from' and 'to' (points)", what));
          sys.add_coordinate_damper(name, scalar(on->value, env, what), c);
        } else {
          sys.add_damper(name, point_arg(args, "from"), point_arg(args, "to"), c);
        }
        break;
      }
      case Kind::torsion: {
        Arguments args(s, what, {"angle", "stiffness", "rest"});
        sys.add_torsional_spring(name, scalar_arg(args, "angle", "an angle expression"),
                                 scalar_arg(args, "stiffness", "k"), optional_scalar(args, "rest"));
        break;
      }
      case Kind::potential:
        sys.add_potential(name, scalar(s.value, env, what));
        break;
      case Kind::generalized_force: {
        Arguments args(s, what, {"on", "value"});
        const Argument& on = args.require("on", "a coordinate");
        const std::string coordinate = resolve(args.name_of(on, "a coordinate"), env);
        const auto symbol = sys.variables().find(coordinate);
        if (!symbol || sys.variables().kind_of(*symbol) != SymbolKind::coordinate)
          throw SourceError(on.value->location, fmt::format("{}: '{}' is not a coordinate", what, coordinate));
        used_coordinates_.insert(coordinate);
        sys.add_generalized_force(*sys.variables().coordinate_index(*symbol), scalar_arg(args, "value", "the force"));
        break;
      }
      case Kind::constraint: {
        const ex expression = scalar(s.value, env, what) - scalar(s.value2, env, what);
        bool has_rate = false;
        for (const auto& c : sys.variables().coordinates()) has_rate = has_rate || expression.has(c.qd);
        if (has_rate) {
          sys.add_nonholonomic_constraint(name, expression);
        } else {
          sys.add_holonomic_constraint(name, expression);
        }
        model_.constraint_locations.push_back(s.name.location);
        break;
      }
      case Kind::roll:
        roll(in);
        break;
      case Kind::output:
        output(in);
        break;
      default:
        break;
    }
  } catch (const ModelError& e) {
    throw SourceError(s.name.location.line ? s.name.location : s.location, e.what());
  } catch (const DerivationError& e) {
    throw SourceError(s.name.location.line ? s.name.location : s.location, e.what());
  } catch (const GiNaC::pole_error&) {  // e.g. a mass 1/l with l = 0, evaluated at the defaults
    throw SourceError(s.name.location.line ? s.name.location : s.location,
                      fmt::format("{}: division by zero at the parameters' default values: expected finite values",
                                  what));
  }
}

void Elaborator::roll(const Instance& in) {
  const Statement& s = *in.statement;
  const Environment& env = in.environment;
  MechanicalSystem& sys = model_.system;
  const std::string name = resolve(s.name, env);
  const std::string what = fmt::format("roll '{}'", name);
  Arguments args(s, what, {"body", "contact", "normal"});
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

Model Elaborator::run(const std::vector<Statement>& statements) {
  constants(statements);
  flatten(statements, {});
  if (!saw_statement_) throw SourceError({file_, 1, 1}, "empty model: expected statements such as 'coordinate', 'frame', 'point' and 'particle'");
  declarations();
  collect_frames_and_points();
  std::vector<std::string> stack;
  for (const Instance& in : instances_)
    if (in.statement->kind == Kind::frame) build_frame(resolve(in.statement->name, in.environment), stack);
  for (const Instance& in : instances_)
    if (in.statement->kind == Kind::point) build_point(resolve(in.statement->name, in.environment), stack);
  kinematics_ready_ = true;
  // bodies first: a roll statement names its body, which may come later in the file
  for (const Instance& in : instances_)
    if (in.statement->kind == Kind::body) element(in);
  for (const Instance& in : instances_) {
    const Kind k = in.statement->kind;
    if (k != Kind::parameter && k != Kind::coordinate && k != Kind::input && k != Kind::frame && k != Kind::point &&
        k != Kind::body && k != Kind::independent)
      element(in);
  }
  checks();
  return std::move(model_);
}

}  // namespace eomgen::syntax
