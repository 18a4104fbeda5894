// The shape statement: how a body, a particle or a fixed part looks in the animation of a
// simulation. Shapes have no part in the equations; they fill Model::shapes.
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
using ShapeKind = VisualShape::Kind;

struct KindSyntax {
  const char* word;
  ShapeKind kind;
  std::vector<std::string> arguments;
};

const KindSyntax kinds[] = {
    {"sphere", ShapeKind::sphere, {"body", "radius", "at", "frame"}},
    {"box", ShapeKind::box, {"body", "size", "at", "frame"}},
    {"cylinder", ShapeKind::cylinder, {"body", "radius", "length", "axis", "at", "frame"}},
    {"disk", ShapeKind::disk, {"body", "radius", "axis", "thickness", "at", "frame"}},
    {"rod", ShapeKind::rod, {"from", "to", "radius", "body"}},
    {"mesh", ShapeKind::mesh, {"body", "file", "scale", "at", "frame"}},
};

bool has_state(const Variables& vars, const ex& e) {
  return vars.contains(e, SymbolKind::coordinate) || vars.contains(e, SymbolKind::rate) ||
         vars.contains(e, SymbolKind::acceleration) || vars.contains(e, SymbolKind::input) || e.has(vars.time());
}

}  // namespace

// A radius, length, thickness or edge: numbers, consts and parameters, finite and positive at the
// parameters' defaults; a length in a model with units.
ex Elaborator::shape_length(const ExprPtr& value, const std::string& what,
                            const std::string& role, const Environment& env) {
  const MechanicalSystem& sys = model_.system;
  const ex e = scalar(value, env, fmt::format("{}: {}", what, role));
  const std::optional<double> at_defaults = value_at(e, sys.parameter_defaults());
  if (has_state(sys.variables(), e) || !at_defaults || !std::isfinite(*at_defaults) || *at_defaults <= 0)
    throw SourceError(start_of(*value), fmt::format("{}: {} must be a positive constant (numbers, consts and "
                                                    "parameters, positive at the parameters' default values){}",
                                                    what, role, at_defaults && !has_state(sys.variables(), e)
                                                                    ? fmt::format(", got {:.6g}", *at_defaults)
                                                                    : std::string()));
  units_.require(e, UnitChecks::expect(dimension::m(), start_of(*value), what, fmt::format("{} (a length)", role)));
  return e;
}

// A mesh's file, a string, and its scale: one factor for all three axes or [X, Y, Z], each a
// constant that is not zero (a negative factor mirrors, as URDFs use for left and right parts).
// The factors are pure numbers: the file's coordinates are lengths in metres.
void Elaborator::mesh_file_and_scale(VisualShape& shape, const Arguments& args, const std::string& what,
                                     const Environment& env) {
  const Argument& file = args.require("file", "the mesh's STL file, a string such as \"meshes/link1.stl\"");
  if (file.value->kind != Expr::Kind::text)
    throw SourceError(start_of(*file.value), fmt::format("{}: 'file' must be a string in double quotes, such as "
                                                         "\"meshes/link1.stl\"", what));
  shape.file = file.value->number_text;
  if (shape.file.empty()) throw SourceError(file.value->location, fmt::format("{}: 'file' is empty: expected a file name", what));
  const Argument* scale = args.find("scale");
  if (!scale) return;
  std::vector<ExprPtr> factors;
  if (scale->value->kind == Expr::Kind::list) {
    if (scale->value->args.size() != 3)
      throw SourceError(start_of(*scale->value), fmt::format("{}: 'scale' must be one factor or [X, Y, Z], the "
                                                             "factors along the axes 1, 2, 3 of the shape's frame", what));
    factors = scale->value->args;
  } else {
    factors = {scale->value, scale->value, scale->value};
  }
  const MechanicalSystem& sys = model_.system;
  for (std::size_t i = 0; i < 3; ++i) {
    const std::string role = factors[0] == factors[1] ? std::string("'scale'") : fmt::format("factor {} of 'scale'", i + 1);
    const ex e = scalar(factors[i], env, fmt::format("{}: {}", what, role));
    const std::optional<double> at_defaults = value_at(e, sys.parameter_defaults());
    if (has_state(sys.variables(), e) || !at_defaults || !std::isfinite(*at_defaults) || *at_defaults == 0)
      throw SourceError(start_of(*factors[i]),
                        fmt::format("{}: {} must be a constant that is not zero (numbers, consts and parameters, "
                                    "not zero at the parameters' default values){}", what, role,
                                    at_defaults && !has_state(sys.variables(), e) ? fmt::format(", got {:.6g}", *at_defaults)
                                                                                  : std::string()));
    units_.require(e, UnitChecks::expect(dimension::none(), start_of(*factors[i]), what,
                                         fmt::format("{} (a pure number)", role)));
    shape.scale[i] = e;
  }
}

void Elaborator::shape(const Instance& in, const std::string& name, const std::string& what) {
  const Statement& s = *in.statement;
  const Environment& env = in.environment;
  MechanicalSystem& sys = model_.system;
  const std::string word = resolve(s.shape_kind, env);
  const KindSyntax* syntax = nullptr;
  for (const KindSyntax& k : kinds)
    if (word == k.word) syntax = &k;
  if (!syntax)
    throw SourceError(s.shape_kind.location, fmt::format("{}: unknown kind of shape '{}': expected sphere, box, "
                                                         "cylinder, disk, rod or mesh", what, word));
  const std::string described = fmt::format("{} ({})", what, word);
  const Arguments args(*this, in, described, syntax->arguments);
  VisualShape shape;
  shape.kind = syntax->kind;
  shape.name = name;
  shape.location = s.name.location;

  // the body or particle it belongs to: its frame and its centre are the defaults
  std::optional<FrameId> body_frame;
  std::optional<PointId> body_point;
  bool particle = false;
  if (const Argument* body = args.find("body")) {
    shape.body = resolve(args.name_of(*body, "a body or a particle"), env);
    for (const RigidBody& b : sys.rigid_bodies())
      if (b.name == shape.body) body_frame = b.frame, body_point = b.mass_centre;
    for (const Particle& p : sys.particles())
      if (p.name == shape.body) body_point = p.point, particle = true;
    if (!body_point && declared_.count(shape.body))
      throw SourceError(body->value->location, fmt::format("{}: '{}' is a {}, not a body or a particle: expected the "
                                                           "name of a 'body' or 'particle' statement", described,
                                                           shape.body, declared_.at(shape.body).kind));
    if (!body_point) {
      std::vector<std::string> candidates;
      for (const RigidBody& b : sys.rigid_bodies()) candidates.push_back(b.name);
      for (const Particle& p : sys.particles()) candidates.push_back(p.name);
      unknown_name(shape.body, body->value->location, candidates, "body or particle");
    }
  }

  if (shape.kind == ShapeKind::rod) {
    shape.at = args.point("from");
    shape.to = args.point("to");
    if (const Argument* radius = args.find("radius"))
      shape.radius = shape_length(radius->value, described, "'radius'", env);
    model_.shapes.push_back(std::move(shape));
    return;
  }

  const Argument* frame = args.find("frame");
  if (particle && !frame && shape.kind != ShapeKind::sphere)
    throw SourceError(args.find("body")->value->location,
                      fmt::format("{}: '{}' is a particle, which has no attitude: a {} needs one; expected 'frame = "
                                  "FRAME', or a sphere or a rod for the particle", described, shape.body, word));
  shape.frame = frame ? std::optional<FrameId>(args.frame("frame", "the shape's attitude"))
                : particle ? std::nullopt
                : body_frame ? body_frame : std::optional<FrameId>(sys.inertial_frame());
  if (const Argument* at = args.find("at")) {
    shape.at = point_named(args.name_of(*at, "a point"), env);
  } else if (body_point) {
    shape.at = *body_point;
  } else {
    args.require("at", "the shape's centre, a point; or 'body = BODY', whose centre it then is");
  }

  if (shape.kind == ShapeKind::mesh) {
    mesh_file_and_scale(shape, args, described, env);
  } else if (shape.kind == ShapeKind::box) {
    const Argument& size = args.require("size", "the edge lengths [X, Y, Z] along the frame's axes 1, 2, 3");
    if (size.value->kind != Expr::Kind::list || size.value->args.size() != 3)
      throw SourceError(start_of(*size.value), fmt::format("{}: 'size' must be [X, Y, Z], the edge lengths along the "
                                                           "axes 1, 2, 3 of the shape's frame", described));
    for (unsigned i = 0; i < 3; ++i)
      shape.size[i] = shape_length(size.value->args[i], described, fmt::format("edge {} of 'size'", i + 1), env);
  } else {
    shape.radius = shape_length(args.require("radius", "the radius").value, described, "'radius'", env);
  }
  if (shape.kind == ShapeKind::cylinder)
    shape.length = shape_length(args.require("length", "the length along the axis").value, described,
                                "'length'", env);
  if (shape.kind == ShapeKind::disk) {
    const Argument* thickness = args.find("thickness");
    shape.length = thickness ? shape_length(thickness->value, described, "'thickness'", env) : shape.radius / 10;
  }
  if (shape.kind == ShapeKind::cylinder || shape.kind == ShapeKind::disk) {
    // the axis in the shape's frame, where it must be constant
    const Argument& axis_arg = args.require("axis", "the direction of the axis, fixed in the shape's frame");
    const FrameId f = shape.frame ? *shape.frame : sys.inertial_frame();
    const eomgen::Vector axis = vector(axis_arg.value, env, fmt::format("{}: 'axis'", described));
    const GiNaC::matrix c = eomgen::resolve(sys, axis, f);
    for (unsigned i = 0; i < 3; ++i) {
      shape.axis[i] = simplify_for_display(c(i, 0));
      if (has_state(sys.variables(), shape.axis[i]))
        throw SourceError(start_of(*axis_arg.value),
                          fmt::format("{}: the axis turns relative to the shape's frame '{}': expected a direction "
                                      "fixed in it, such as {}.1, {}.2 or {}.3", described, sys.frame(f).name,
                                      sys.frame(f).name, sys.frame(f).name, sys.frame(f).name));
    }
    reject_zero_vector(axis, lean_norm(sys, axis), start_of(*axis_arg.value), fmt::format("{}: 'axis'", described));
    // any length, but one unit for all its components
    units_.require_consistent(GiNaC::pow(shape.axis[0], 2) + GiNaC::pow(shape.axis[1], 2) +
                                  GiNaC::pow(shape.axis[2], 2), start_of(*axis_arg.value), described);
  }
  model_.shapes.push_back(std::move(shape));
}

}  // namespace eomgen::syntax
