#pragma once
// The description of a mechanical system: a tree of frames rooted at the inertial frame, a tree
// of points rooted at the inertial origin, the bodies, loads and constraints. It is built
// once through the add_* functions (each validates its input) and then only read: the
// derivation (derive_equations) and the kinematics functions take it by const reference.
#include <ginac/ginac.h>

#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <set>
#include <vector>

#include "eomgen/base/overloaded.hpp"
#include "eomgen/mechanics/rotation.hpp"
#include "eomgen/mechanics/variables.hpp"
#include "eomgen/mechanics/vector.hpp"

namespace eomgen {

struct Frame {
  std::string name;
  std::optional<FrameId> parent;  // none for the inertial frame
  Rotation rotation;              // C_{this, parent}
  GiNaC::matrix relative_angular_velocity;  // omega^{this,parent} resolved in this frame
  std::size_t depth = 0;
};

struct Point {
  std::string name;
  std::optional<PointId> parent;  // none for the inertial origin
  Vector offset;                  // r^{this, parent}
  std::size_t depth = 0;
};

struct Particle {
  std::string name;
  GiNaC::ex mass;
  PointId point;
};

struct RigidBody {
  std::string name;
  GiNaC::ex mass;
  PointId mass_centre;
  FrameId frame;
  GiNaC::matrix inertia;  // J_b^Bc: about the mass centre, resolved in the body frame
};

/// A force applied at a point.
struct PointForce {
  PointId point;
  Vector force;
};

/// A moment (couple) applied to the body whose frame is `frame`.
struct BodyMoment {
  FrameId frame;
  Vector moment;
};

/// Linear spring between two points: V = 1/2 k (|r^{ab}| - L0)^2.
struct LinearSpring {
  std::string name;
  PointId a, b;
  GiNaC::ex stiffness, rest_length;
};

/// Torsional spring on an angle expression theta(q, t): V = 1/2 k (theta - theta0)^2.
struct TorsionalSpring {
  std::string name;
  GiNaC::ex angle, stiffness, rest_angle;
};

/// Linear viscous damper between two points, acting along the line joining them.
struct LinearDamper {
  std::string name;
  PointId a, b;
  GiNaC::ex damping;
};

/// Viscous damper on a coordinate expression theta(q): generalized force -c dtheta/dt dtheta/dq.
struct CoordinateDamper {
  std::string name;
  GiNaC::ex coordinate_expression, damping;
};

/// A generalized force added directly to one equation (a joint torque, an input).
struct GeneralizedForce {
  std::size_t coordinate;
  GiNaC::ex value;
};

/// A potential energy given by the user, V(q, t).
struct Potential {
  std::string name;
  GiNaC::ex value;
};

/// Every load but gravity: what the derivations turn into generalized forces and potential
/// energy. A new kind of load is a new alternative here, and each derivation visits loads with
/// visit_load, which does not compile until it handles every alternative.
using Load = std::variant<PointForce, BodyMoment, LinearDamper, CoordinateDamper, GeneralizedForce, LinearSpring,
                          TorsionalSpring, Potential>;

namespace detail {
struct NotALoad {};

template <class Visitor, class LoadType>
constexpr bool handles_load() {
  static_assert(std::is_invocable_v<const Visitor&, const LoadType&>,
                "visit_load: no handler for a load type (named as LoadType in the instantiation above)");
  return std::is_invocable_v<const Visitor&, const LoadType&>;
}

template <class Visitor, class... LoadTypes>
constexpr bool handles_every_load(const std::variant<LoadTypes...>*) {
  return (handles_load<Visitor, LoadTypes>() && ...);
}
}  // namespace detail

/// Calls the one of `handlers` that takes the load's type, by const reference. There must be
/// one for every load type and no generic one, so that a forgotten type is a compile error:
///   visit_load(load, [&](const PointForce& f) { ... }, [&](const BodyMoment& m) { ... }, ...);
template <class... Handlers>
void visit_load(const Load& load, Handlers&&... handlers) {
  const Overloaded<std::decay_t<Handlers>...> visitor{std::forward<Handlers>(handlers)...};
  using Visitor = decltype(visitor);
  static_assert(!std::is_invocable_v<Visitor, const detail::NotALoad&>,
                "visit_load: a generic handler would hide the load types it does not name");
  if constexpr (detail::handles_every_load<Visitor>(static_cast<const Load*>(nullptr))) std::visit(visitor, load);
}

/// Holonomic phi(q, t) = 0, or nonholonomic Xi(q,t) qd + Xi_t(q,t) = 0 given by its left side.
struct Constraint {
  enum class Kind { holonomic, nonholonomic };
  std::string name;
  Kind kind;
  GiNaC::ex expression;
};

class MechanicalSystem {
 public:
  /// Creates the inertial frame and the inertial origin (a point fixed in it).
  explicit MechanicalSystem(const std::string& inertial_frame = "a",
                            const std::string& origin = "w");

  Variables& variables() { return variables_; }
  const Variables& variables() const { return variables_; }

  // convenience forwarding to variables()
  Coordinate add_coordinate(const std::string& name) { return variables_.add_coordinate(name); }
  GiNaC::ex add_parameter(const std::string& name, double value, const std::string& unit = "") {
    return variables_.add_parameter(name, value, unit).symbol;
  }
  GiNaC::ex add_input(const std::string& name) { return variables_.add_input(name).symbol; }
  GiNaC::ex add_derived_parameter(const std::string& name, const GiNaC::ex& definition, const std::string& unit = "") {
    return variables_.add_derived_parameter(name, definition, unit).symbol;
  }

  FrameId inertial_frame() const { return FrameId{0}; }
  PointId origin() const { return PointId{0}; }

  /// A frame whose attitude relative to `parent` is `rotation` (C_{new,parent}).
  /// \throws ModelError on a duplicate name or unknown symbols in the rotation.
  FrameId add_frame(const std::string& name, FrameId parent, const Rotation& rotation);
  /// A point at `offset` from `parent`: r^{new,parent} = offset.
  PointId add_point(const std::string& name, PointId parent, const Vector& offset);

  /// \throws ModelError for a mass that is numerically non-positive.
  void add_particle(const std::string& name, const GiNaC::ex& mass, PointId point);
  /// \throws ModelError for non-positive mass or an inertia that no mass distribution has: not
  /// symmetric, a negative principal moment, or one larger than the sum of the other two
  /// (checked numerically at the parameters' default values). A slender rod's or a thin disk's
  /// inertia, on the boundary, is accepted.
  void add_rigid_body(const std::string& name, const GiNaC::ex& mass, PointId mass_centre,
                      FrameId frame, const GiNaC::matrix& inertia);

  /// Uniform gravitational acceleration g (a physical vector).
  void set_gravity(const Vector& g);
  void add_force(PointId point, const Vector& force);
  void add_moment(FrameId body_frame, const Vector& moment);
  void add_spring(const std::string& name, PointId a, PointId b, const GiNaC::ex& stiffness,
                  const GiNaC::ex& rest_length);
  void add_torsional_spring(const std::string& name, const GiNaC::ex& angle,
                            const GiNaC::ex& stiffness, const GiNaC::ex& rest_angle);
  void add_damper(const std::string& name, PointId a, PointId b, const GiNaC::ex& damping);
  void add_coordinate_damper(const std::string& name, const GiNaC::ex& coordinate_expression,
                             const GiNaC::ex& damping);
  void add_generalized_force(std::size_t coordinate, const GiNaC::ex& value);
  void add_potential(const std::string& name, const GiNaC::ex& value);
  /// phi(q, t) = 0. \throws ModelError if phi contains rates or inputs, or is identically zero.
  void add_holonomic_constraint(const std::string& name, const GiNaC::ex& phi);
  /// Xi(q,t) qd + Xi_t(q,t) = 0 given by its left side.
  /// \throws ModelError if the expression is not linear in the rates or has no rate in it.
  void add_nonholonomic_constraint(const std::string& name, const GiNaC::ex& expression);
  /// Removes the constraints at `indices` (distinct, in any order); the others keep their order,
  /// those after a removed one moving up. Their names stay taken: a model file's notes still name
  /// them. For constraints found redundant once every constraint is known.
  /// \throws ModelError for an index out of range or given twice.
  void remove_constraints(std::vector<std::size_t> indices);

  std::optional<FrameId> find_frame(const std::string& name) const;
  std::optional<PointId> find_point(const std::string& name) const;

  const std::vector<Frame>& frames() const { return frames_; }
  const Frame& frame(FrameId id) const { return frames_.at(id.index); }
  const std::vector<Point>& points() const { return points_; }
  const Point& point(PointId id) const { return points_.at(id.index); }
  const std::vector<Particle>& particles() const { return particles_; }
  const std::vector<RigidBody>& rigid_bodies() const { return rigid_bodies_; }
  const Vector& gravity() const { return gravity_; }
  /// The loads, grouped by type in the order of Load's alternatives and in the order they were
  /// added within a type. The derivations add their terms, and name shared subexpressions, in
  /// this order, and the generated code follows it.
  const std::vector<Load>& loads() const { return loads_; }
  const std::vector<Constraint>& constraints() const { return constraints_; }

  /// Numeric substitution of every parameter, derived or not, by its default value.
  GiNaC::exmap parameter_defaults() const;

 private:
  void require_frame(FrameId id, const std::string& what) const;
  void require_point(PointId id, const std::string& what) const;
  void require_vector(const Vector& v, const std::string& what) const;
  void require_unique_element_name(const std::string& name, const std::string& what);
  void add_load(Load load);

  Variables variables_;
  std::vector<Frame> frames_;
  std::vector<Point> points_;
  std::vector<Particle> particles_;
  std::vector<RigidBody> rigid_bodies_;
  Vector gravity_;
  std::vector<Load> loads_;
  std::vector<Constraint> constraints_;
  std::set<std::string> element_names_;
};

/// Inertia about a point o from the inertia J_c about the mass centre (same frame) and
/// r = r^{c o} resolved in that frame: J_o = J_c - m r^x r^x (parallel-axis theorem).
GiNaC::matrix parallel_axis(const GiNaC::matrix& inertia_about_centre, const GiNaC::ex& mass,
                            const GiNaC::matrix& r_centre_from_point);

}  // namespace eomgen
