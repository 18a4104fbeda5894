#include "eomgen/mechanics/kinematics.hpp"

#include <fmt/format.h>

#include "eomgen/base/error.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;
using GiNaC::matrix;

matrix identity3() { return GiNaC::ex_to<matrix>(GiNaC::unit_matrix(3)); }

matrix cross3(const matrix& u, const matrix& v) { return cross_matrix(u).mul(v); }

// C_{f, ancestor}, compounding C_{f,p} C_{p,pp} ... up the tree
matrix dcm_to_ancestor(const MechanicalSystem& s, FrameId f, FrameId ancestor) {
  matrix C = identity3();
  while (f != ancestor) {
    const Frame& frame = s.frame(f);
    C = C.mul(frame.rotation.dcm());
    f = *frame.parent;
  }
  return C;
}

// nearest common ancestor in a tree whose nodes know their parent and depth (frames, points)
template <class Id, class Node>
Id common_ancestor(Id a, Id b, Node&& node) {
  while (node(a).depth > node(b).depth) a = *node(a).parent;
  while (node(b).depth > node(a).depth) b = *node(b).parent;
  while (a != b) {
    a = *node(a).parent;
    b = *node(b).parent;
  }
  return a;
}


// omega^{f,ancestor} as the sum of relative angular velocities along the path
Vector angular_velocity_to_ancestor(const MechanicalSystem& s, FrameId f, FrameId ancestor) {
  Vector w;
  while (f != ancestor) {
    const Frame& frame = s.frame(f);
    w += Vector(f, frame.relative_angular_velocity);
    f = *frame.parent;
  }
  return w;
}

PointId common_point_ancestor(const MechanicalSystem& s, PointId a, PointId b) {
  return common_ancestor(a, b, [&](PointId p) -> const Point& { return s.point(p); });
}

Vector position_to_ancestor(const MechanicalSystem& s, PointId p, PointId ancestor) {
  Vector r;
  while (p != ancestor) {
    r += s.point(p).offset;
    p = *s.point(p).parent;
  }
  return r;
}

}  // namespace

FrameId common_ancestor(const MechanicalSystem& s, FrameId a, FrameId b) {
  return common_ancestor(a, b, [&](FrameId f) -> const Frame& { return s.frame(f); });
}

matrix dcm(const MechanicalSystem& s, FrameId b, FrameId a) {
  const FrameId anc = common_ancestor(s, a, b);
  return dcm_to_ancestor(s, b, anc).mul(dcm_to_ancestor(s, a, anc).transpose());
}

Vector angular_velocity(const MechanicalSystem& s, FrameId b, FrameId a) {
  const FrameId anc = common_ancestor(s, a, b);
  return angular_velocity_to_ancestor(s, b, anc) - angular_velocity_to_ancestor(s, a, anc);
}

matrix resolve(const MechanicalSystem& s, const Vector& v, FrameId f) {
  matrix out(3, 1);
  for (const auto& [frame, c] : v.terms()) out = out.add(frame == f ? c : dcm(s, f, frame).mul(c));
  return out;
}

ex dot(const MechanicalSystem& s, const Vector& u, const Vector& v) {
  ex result = 0;
  for (const auto& [frame, c] : u.terms()) {
    const matrix w = resolve(s, v, frame);
    result += c(0, 0) * w(0, 0) + c(1, 0) * w(1, 0) + c(2, 0) * w(2, 0);
  }
  return result;
}

Vector cross(const MechanicalSystem& s, const Vector& u, const Vector& v) {
  Vector out;
  for (const auto& [frame, c] : u.terms()) out += Vector(frame, cross3(c, resolve(s, v, frame)));
  return out;
}

Vector time_derivative(const MechanicalSystem& s, const Vector& v, FrameId a) {
  const Variables& vars = s.variables();
  Vector out;
  for (const auto& [frame, c] : v.terms()) {
    // transport theorem: v^{.a} = v^{.f} + omega^{fa} x v
    Vector term(frame, c);
    out += term.map_components([&](const ex& e) { return vars.time_derivative(e); });
    out += cross(s, angular_velocity(s, frame, a), term);
  }
  return out;
}

Vector partial_derivative(const MechanicalSystem& s, const Vector& v, const GiNaC::symbol& x, FrameId a) {
  const Variables& vars = s.variables();
  const auto kind = vars.kind_of(x);
  if (!kind || (*kind != SymbolKind::coordinate && *kind != SymbolKind::rate))
    throw DerivationError(fmt::format("partial derivative of a vector: '{}' is not a coordinate "
                                      "or a rate of the model", x.get_name()));
  Vector out = v.map_components([&](const ex& e) { return e.diff(x); });
  if (*kind == SymbolKind::coordinate) {
    const GiNaC::symbol& rate = GiNaC::ex_to<GiNaC::symbol>(ex(vars.coordinates()[*vars.coordinate_index(x)].qd));
    for (const auto& [frame, c] : v.terms()) {
      const Vector partial_w =
          angular_velocity(s, frame, a).map_components([&](const ex& e) { return e.diff(rate); });
      out += cross(s, partial_w, Vector(frame, c));
    }
  }
  return out;
}

Vector position(const MechanicalSystem& s, PointId p, PointId q) {
  const PointId anc = common_point_ancestor(s, p, q);
  return position_to_ancestor(s, p, anc) - position_to_ancestor(s, q, anc);
}

Vector velocity(const MechanicalSystem& s, PointId p, FrameId a, PointId o) {
  return time_derivative(s, position(s, p, o), a);
}

Vector velocity(const MechanicalSystem& s, PointId p) {
  return velocity(s, p, s.inertial_frame(), s.origin());
}

Vector acceleration(const MechanicalSystem& s, PointId p, FrameId a, PointId o) {
  return time_derivative(s, velocity(s, p, a, o), a);
}

Vector acceleration(const MechanicalSystem& s, PointId p) {
  return acceleration(s, p, s.inertial_frame(), s.origin());
}

}  // namespace eomgen
