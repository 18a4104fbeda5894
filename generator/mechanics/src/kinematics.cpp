#include "eomgen/mechanics/kinematics.hpp"
#include "eomgen/symbolic/graph_calculus.hpp"

#include <fmt/format.h>

#include <vector>

#include "eomgen/base/error.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;
using GiNaC::matrix;

matrix identity3() { return GiNaC::ex_to<matrix>(GiNaC::unit_matrix(3)); }

matrix cross3(const matrix& u, const matrix& v) { return cross_matrix(u).mul(v); }

// one factor of C_{f,ancestor}: a principal rotation by a summed angle, or any other rotation
struct Factor {
  int axis = 0;  // 1..3 for a principal rotation, 0 for a general one
  ex angle;
  matrix dcm;
  matrix value() const { return axis == 0 ? dcm : principal_rotation(axis, angle); }
};

// C_{f,ancestor} = C_{f,p} C_{p,pp} ... as factors in that order, consecutive principal rotations
// about one axis merged into one
std::vector<Factor> factors_to_ancestor(const MechanicalSystem& s, FrameId f, FrameId ancestor) {
  std::vector<Factor> factors;
  for (; f != ancestor; f = *s.frame(f).parent) {
    const Rotation& rotation = s.frame(f).rotation;
    switch (rotation.kind()) {
      case Rotation::Kind::identity:
        continue;
      case Rotation::Kind::principal: {
        const int axis = rotation.axes()[0];
        const ex angle = rotation.parameters().op(0);
        if (!factors.empty() && factors.back().axis == axis)
          factors.back().angle += angle;
        else
          factors.push_back(Factor{axis, angle, {}});
        continue;
      }
      case Rotation::Kind::euler:
      case Rotation::Kind::axis_angle:
      case Rotation::Kind::quaternion:
      case Rotation::Kind::rodrigues:
      case Rotation::Kind::modified_rodrigues:
      case Rotation::Kind::matrix:
        factors.push_back(Factor{0, 0, rotation.dcm()});
        continue;
    }
  }
  return factors;
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
  const FrameId ancestor = common_ancestor(s, a, b);
  std::vector<Factor> down = factors_to_ancestor(s, b, ancestor);  // C_{b,anc}
  std::vector<Factor> up = factors_to_ancestor(s, a, ancestor);    // C_{a,anc}
  // C_ba = C_{b,anc} C_{a,anc}^T; two rotations about one axis meet at the ancestor as one
  if (!down.empty() && !up.empty() && down.back().axis != 0 && down.back().axis == up.back().axis) {
    down.back().angle -= up.back().angle;
    up.pop_back();
  }
  matrix C = identity3();
  for (const Factor& f : down) C = C.mul(f.value());
  for (auto it = up.rbegin(); it != up.rend(); ++it) C = C.mul(it->value().transpose());
  return C;
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
  Vector out = v.map_components([&](const ex& e) { return derivative(e, x); });
  if (*kind == SymbolKind::coordinate) {
    // the model's own symbol, not the heap copy a temporary ex(qd) would own and free
    const GiNaC::symbol& rate = vars.coordinates()[*vars.coordinate_index(x)].qd;
    for (const auto& [frame, c] : v.terms()) {
      const Vector partial_w =
          angular_velocity(s, frame, a).map_components([&](const ex& e) { return derivative(e, rate); });
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
