// Statements of a model file -> MechanicalSystem, through the C++ API.
#include "model_elaborator.hpp"

#include <Eigen/Dense>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "eomgen/base/error.hpp"
#include "eomgen/mechanics/kinematics.hpp"
#include "eomgen/symbolic/simplify.hpp"
#include "definition_in_progress.hpp"
#include "model_matrices.hpp"

namespace eomgen::syntax {

using GiNaC::ex;
using Kind = Statement::Kind;

const char* statement_word(Kind kind) {
  switch (kind) {
    case Kind::model: return "model";
    case Kind::description: return "description";
    case Kind::constant: return "const";
    case Kind::parameter: return "parameter";
    case Kind::coordinate: return "coordinate";
    case Kind::input: return "input";
    case Kind::frame: return "frame";
    case Kind::point: return "point";
    case Kind::particle: return "particle";
    case Kind::body: return "body";
    case Kind::gravity: return "gravity";
    case Kind::force: return "force";
    case Kind::moment: return "moment";
    case Kind::spring: return "spring";
    case Kind::damper: return "damper";
    case Kind::torsion: return "torsion";
    case Kind::potential: return "potential";
    case Kind::generalized_force: return "generalized_force";
    case Kind::constraint: return "constraint";
    case Kind::roll: return "roll";
    case Kind::wheel: return "wheel";
    case Kind::shape: return "shape";
    case Kind::independent: return "independent";
    case Kind::output: return "output";
    case Kind::loop: return "for";
  }
  EOMGEN_UNREACHABLE("statement_word: a Statement::Kind outside its enumerators");
}

Pass pass_of(Kind kind) {
  switch (kind) {
    case Kind::model:
    case Kind::description:
    case Kind::constant:
    case Kind::loop: return Pass::flatten;
    case Kind::parameter:
    case Kind::coordinate:
    case Kind::input: return Pass::declarations;
    case Kind::frame:
    case Kind::point: return Pass::frames_and_points;
    case Kind::particle:
    case Kind::body:
    case Kind::gravity:
    case Kind::force:
    case Kind::moment:
    case Kind::spring:
    case Kind::damper:
    case Kind::torsion:
    case Kind::potential:
    case Kind::generalized_force:
    case Kind::constraint:
    case Kind::roll:
    case Kind::wheel:  // and its contact point with the points (collect_frames_and_points)
    case Kind::output:
    case Kind::shape: return Pass::elements;  // shapes last: they name bodies and particles
    case Kind::independent: return Pass::independent_speeds;
  }
  EOMGEN_UNREACHABLE("pass_of: a Statement::Kind outside its enumerators");
}

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
  if (is_keyword(name))
    throw SourceError(at, fmt::format("'{}' is a keyword of the model language: expected a {} name that is not one",
                                      name, kind));
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
      if (is_keyword(var))
        throw SourceError(s.name.location, fmt::format("'{}' is a keyword of the model language: expected a loop "
                                                       "variable that is not one", var));
      if (env.count(var) || constants_.count(var) || declared_.count(var) || var == "pi")
        throw SourceError(s.name.location, fmt::format("loop variable '{}' hides another name", var));
      // names declared later in the file (parameters, coordinates...) are checked once all are known
      loop_variables_.emplace(var, s.name.location);
      const int first = integer(s.value, env, "the first value of the loop");
      const int last = integer(s.value2, env, "the last value of the loop");
      if (static_cast<long>(last) - first > 100000)  // long: the bounds may be 10^9 apart
        throw SourceError(s.location, "loop has more than 100000 iterations");
      for (int i = first; i <= last; ++i) {
        expand(s.token_count, s.location);
        Environment inner = env;
        inner[var] = i;
        flatten(s.body, inner);
      }
      continue;
    }
    expand(s.token_count, s.location);
    EOMGEN_DEMAND(pass_of(s.kind) != Pass::flatten, fmt::format("flatten(): '{}' is not handled", statement_word(s.kind)));
    instances_.push_back(Instance{&s, env});
  }
}

// Counts the work of one more iteration or statement instance, so that loops inside loops stop
// at max_expanded_tokens instead of running for hours or exhausting memory.
void Elaborator::expand(std::size_t tokens, const SourceLocation& at) {
  expanded_tokens_ += std::max<std::size_t>(tokens, 1);
  if (expanded_tokens_ > max_expanded_tokens)
    throw SourceError(at, fmt::format("the loops expand the model beyond {} tokens (iterations times the "
                                      "statements they repeat): expected fewer or shorter loops",
                                      max_expanded_tokens));
}

void Elaborator::collect_frames_and_points() {
  for (std::size_t i = 0; i < instances_.size(); ++i) {
    const Statement& s = *instances_[i].statement;
    if (s.kind != Kind::frame && s.kind != Kind::point) continue;
    const std::string name = resolve(s.name, instances_[i].environment);
    declare(name, s.kind == Kind::frame ? "frame" : "point", s.name.location);
    (s.kind == Kind::frame ? frame_instances_ : point_instances_)[name] = i;
  }
  // a wheel declares its contact point, which other definitions may use
  for (std::size_t i = 0; i < instances_.size(); ++i) {
    const Statement& s = *instances_[i].statement;
    if (s.kind != Kind::wheel) continue;
    const std::string name = wheel_contact_name(resolve(s.name, instances_[i].environment));
    declare(name, "point", s.name.location);
    point_instances_[name] = i;
  }
}

// a definition's parent is the leftmost name: `b`, `rotate(b, ...)`, `p + ...`
static const Expr* leftmost(const Expr* e) {
  while (e->kind == Expr::Kind::sum) e = e->args[0].get();
  return e;
}

FrameId Elaborator::build_frame(const std::string& name) {
  if (auto it = frames_.find(name); it != frames_.end()) return it->second;
  const Instance& in = instances_[frame_instances_.at(name)];
  const Statement& s = *in.statement;
  const Environment& env = in.environment;
  const DefinitionInProgress building(in_progress_, "frame", name, s.name.location, "frames and points");
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
  const FrameId parent = frame_named(parent_expr.name, env);
  if (!is_call) return frames_[name] = parent;  // an alias of its parent

  const std::string f = def.name.plain();
  // counts what the user wrote, parent included, as the usage does
  auto expect_args = [&](std::size_t n, const std::string& usage) {
    if (def.args.size() != n)
      throw SourceError(def.location, fmt::format("{} takes {} arguments, got {}", usage, n, def.args.size()));
  };
  // angles, axes, rotation parameters and direction cosines are numbers
  auto dimensionless = [&](std::size_t i) {
    return UnitChecks::expect(dimension::none(), start_of(*def.args[i]), fmt::format("frame '{}'", name),
                              "an angle or a parameter of a rotation", "", UnitChecks::Evidence::rotation);
  };
  auto col3 = [&](std::size_t i) {
    const Value v = evaluate(def.args[i], env);
    if (v.kind != Value::Kind::column || v.matrix.rows() != 3)
      throw SourceError(def.args[i]->location, fmt::format("{}(): expected a column of three scalars [x, y, z]", f));
    units_.require(v.matrix, dimensionless(i));
    return v.matrix;
  };
  auto angle = [&](std::size_t i) {
    const ex value = scalar(def.args[i], env, fmt::format("argument {} of {}()", i + 1, f));
    units_.require(value, dimensionless(i));
    return value;
  };
  try {
    Rotation rotation = Rotation::identity();
    if (f == "rotate") {
      expect_args(3, "rotate(PARENT, AXIS, ANGLE)");
      const int axis = integer(def.args[1], env, "rotate(): the axis");
      if (axis < 1 || axis > 3) throw SourceError(def.args[1]->location, fmt::format("rotate(): expected axis 1, 2 or 3, got {}", axis));
      rotation = Rotation::principal(axis, angle(2));
    } else if (f == "euler") {
      expect_args(5, "euler(PARENT, SEQUENCE, ANGLE1, ANGLE2, ANGLE3)");
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
      const GiNaC::matrix axis = col3(1);
      reject_non_unit(axis, GiNaC::matrix(0, 0), start_of(*def.args[1]),
                      "axis_angle(): the axis", "a unit axis (divide each component by the length)");
      rotation = Rotation::axis_angle(axis, angle(2));
    } else if (f == "quaternion") {
      expect_args(3, "quaternion(PARENT, [E1, E2, E3], ETA)");
      const GiNaC::matrix epsilon = col3(1);
      const ex eta = angle(2);
      reject_non_unit(epsilon, GiNaC::matrix(1, 1, GiNaC::lst{eta}), start_of(*def.args[1]),
                      "quaternion(): the quaternion [E1, E2, E3, ETA]", "a unit quaternion");
      rotation = Rotation::quaternion(epsilon, eta);
    } else if (f == "rodrigues" || f == "mrp") {
      expect_args(2, f + "(PARENT, [P1, P2, P3])");
      rotation = f == "rodrigues" ? Rotation::rodrigues(col3(1)) : Rotation::modified_rodrigues(col3(1));
    } else {
      expect_args(2, "dcm(PARENT, MATRIX)");
      // dcm(B, A) of two frames is a matrix in expressions; here the first frame is the parent
      if (const Expr& matrix = *def.args[1]; matrix.kind == Expr::Kind::name) {
        const std::string other = resolve(matrix.name, env);
        if (frames_.count(other) || frame_instances_.count(other))
          throw SourceError(matrix.location, fmt::format("dcm(): expected a 3x3 matrix after the parent frame, got the "
                                                         "frame '{}' (the DCM of two frames is the matrix dcm(B, A): "
                                                         "dcm(PARENT, dcm(B, A)))", other));
      }
      const Value m = evaluate(def.args[1], env);
      if (m.kind != Value::Kind::matrix || m.matrix.rows() != 3 || m.matrix.cols() != 3)
        throw SourceError(start_of(*def.args[1]), fmt::format("dcm(): expected a 3x3 matrix such as [[C11, C12, C13], "
                                                              "[C21, C22, C23], [C31, C32, C33]] or dcm(B, A), got {}",
                                                              shape_name(m)));
      reject_non_rotation(m.matrix, start_of(*def.args[1]));
      units_.require(m.matrix, dimensionless(1));
      rotation = Rotation::explicit_matrix(m.matrix);
    }
    return frames_[name] = model_.system.add_frame(name, parent, rotation);
  } catch (const ModelError& e) {
    throw SourceError(def.location, e.what());
  }
}

namespace {

// The numbers of a matrix at the parameters' defaults, or nothing when an entry depends on the
// state (coordinates, rates, inputs, time): such rotation parameters are the model's to keep
// valid, usually by a constraint (a quaternion's unit norm), and cannot be judged here.
std::optional<Eigen::MatrixXd> at_defaults(const GiNaC::matrix& m, const GiNaC::exmap& defaults) {
  Eigen::MatrixXd out(m.rows(), m.cols());
  for (unsigned i = 0; i < m.rows(); ++i)
    for (unsigned j = 0; j < m.cols(); ++j) {
      const std::optional<double> v = value_at(m(i, j), defaults);
      if (!v) return std::nullopt;
      out(i, j) = *v;
    }
  return out;
}

}  // namespace

// An axis or a quaternion (part, rest) of constants must have length 1: the rotation formulas
// assume it, and a longer one gives a matrix that is no rotation (a zero axis gives M = 0).
void Elaborator::reject_non_unit(const GiNaC::matrix& part, const GiNaC::matrix& rest, const SourceLocation& at,
                                 const std::string& what, const std::string& expected) const {
  const GiNaC::exmap defaults = model_.system.parameter_defaults();
  const auto a = at_defaults(part, defaults), b = at_defaults(rest, defaults);
  if (!a || !b) return;
  const double length = std::sqrt(a->squaredNorm() + b->squaredNorm());
  if (std::fabs(length - 1) <= 1e-9) return;
  throw SourceError(at, fmt::format("{} has length {:.6g} at the parameters' default values: expected {}", what,
                                    length, expected));
}

// A constant dcm(...) must be a rotation: orthogonal, with determinant +1 (not a reflection).
void Elaborator::reject_non_rotation(const GiNaC::matrix& dcm, const SourceLocation& at) const {
  const auto c = at_defaults(dcm, model_.system.parameter_defaults());
  if (!c) return;
  const double orthogonality = (*c * c->transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (orthogonality > 1e-9)
    throw SourceError(at, fmt::format("dcm(): the matrix is not orthogonal at the parameters' default values (C C^T "
                                      "differs from the identity by {:.3g}): expected a rotation matrix",
                                      orthogonality));
  if (c->determinant() < 0)
    throw SourceError(at, "dcm(): the matrix is a reflection (determinant -1) at the parameters' default values: "
                          "expected a rotation matrix (determinant +1)");
}

PointId Elaborator::build_point(const std::string& name) {
  if (auto it = points_.find(name); it != points_.end()) return it->second;
  const Instance& in = instances_[point_instances_.at(name)];
  const Statement& s = *in.statement;
  const Environment& env = in.environment;
  const DefinitionInProgress building(in_progress_, "point", name, s.name.location, "frames and points");
  if (s.kind == Kind::wheel) return points_[name] = wheel_contact(in, name);
  const Expr* parent_expr = leftmost(s.value.get());
  if (parent_expr->kind != Expr::Kind::name)
    throw SourceError(start_of(*s.value), "expected a point definition: PARENT_POINT + VECTOR");
  const PointId parent = point_named(parent_expr->name, env);
  // the offset: every term right of the parent along the chain of + and -
  eomgen::Vector offset;
  for (const Expr* e = s.value.get(); e != parent_expr; e = e->args[0].get())
    for (std::size_t k = 1; k < e->args.size(); ++k) {
      const eomgen::Vector term = vector(e->args[k], env, fmt::format("point '{}'", name));
      units_.require(term, UnitChecks::expect(dimension::m(), start_of(*e->args[k]), fmt::format("point '{}'", name),
                                              "a position", "", UnitChecks::Evidence::position));
      offset += e->operations[k - 1].inverse ? -term : term;
    }
  try {
    return points_[name] = parent_expr == s.value.get() ? parent : model_.system.add_point(name, parent, offset);
  } catch (const ModelError& e) {
    throw SourceError(start_of(*s.value), e.what());
  }
}

Model Elaborator::run(const std::vector<Statement>& statements) {
  constants(statements);
  flatten(statements, {});
  if (!saw_statement_) throw SourceError({file_, 1, 1}, "empty model: expected statements such as 'coordinate', 'frame', 'point' and 'particle'");
  declarations();
  collect_frames_and_points();
  reject_hiding_loop_variables();
  // in file order, which numbers the frames and points and so orders the generated code
  for (const Instance& in : instances_)
    if (in.statement->kind == Kind::frame) build_frame(resolve(in.statement->name, in.environment));
  for (const Instance& in : instances_) {
    if (in.statement->kind == Kind::point) build_point(resolve(in.statement->name, in.environment));
    if (in.statement->kind == Kind::wheel) build_point(wheel_contact_name(resolve(in.statement->name, in.environment)));
  }
  kinematics_ready_ = true;
  // bodies first: a roll statement names its body, which may come later in the file
  for (const Instance& in : instances_)
    if (in.statement->kind == Kind::body) element(in);
  for (const Instance& in : instances_)
    if (in.statement->kind != Kind::body && in.statement->kind != Kind::shape &&
        pass_of(in.statement->kind) == Pass::elements)
      element(in);
  // shapes once every body and particle is known
  for (const Instance& in : instances_)
    if (in.statement->kind == Kind::shape) element(in);
  reject_hiding_loop_variables();  // and element names, now declared
  checks();
  model_.dimensions = units_.finish(model_.system.variables(), model_.coordinate_locations);
  return std::move(model_);
}

}  // namespace eomgen::syntax
