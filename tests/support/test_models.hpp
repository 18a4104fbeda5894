#pragma once
// Small models built through the C++ API, shared by tests that need the same system.
#include "eomgen/mechanics/model.hpp"

namespace eomgen::testing {

/// Planar double pendulum: point masses on massless rods, relative angles q1, q2 (frames
/// b = C3(q1) a, c = C3(q2) b), gravity g along a1; all parameters 1 except g = 9.81.
inline Model double_pendulum_model() {
  Model model;
  model.name = "double_pendulum";
  MechanicalSystem& s = model.system;
  const Coordinate q1 = s.add_coordinate("q1"), q2 = s.add_coordinate("q2");
  const GiNaC::ex m1 = s.add_parameter("m1", 1.0, "kg"), m2 = s.add_parameter("m2", 1.0, "kg");
  const GiNaC::ex l1 = s.add_parameter("l1", 1.0, "m"), l2 = s.add_parameter("l2", 1.0, "m");
  const GiNaC::ex g = s.add_parameter("g", 9.81, "m/s^2");
  const FrameId b = s.add_frame("b", s.inertial_frame(), Rotation::principal(3, q1.q));
  const FrameId c = s.add_frame("c", b, Rotation::principal(3, q2.q));
  const PointId p1 = s.add_point("p1", s.origin(), Vector(b, l1, 0, 0));
  s.add_particle("bob1", m1, p1);
  s.add_particle("bob2", m2, s.add_point("p2", p1, Vector(c, l2, 0, 0)));
  s.set_gravity(Vector(s.inertial_frame(), g, 0, 0));
  return model;
}

/// The simple pendulum in Cartesian coordinates: a particle at (x, y) in frame a, the rod a
/// holonomic constraint x^2 + y^2 - l^2 = 0; m = 2, l = 1.5, gravity g = 9.81 along a1.
inline Model cartesian_pendulum_model() {
  Model model;
  model.name = "cartesian_pendulum";
  MechanicalSystem& s = model.system;
  const Coordinate x = s.add_coordinate("x"), y = s.add_coordinate("y");
  const GiNaC::ex m = s.add_parameter("m", 2.0, "kg"), l = s.add_parameter("l", 1.5, "m");
  const GiNaC::ex g = s.add_parameter("g", 9.81, "m/s^2");
  s.add_particle("bob", m, s.add_point("p", s.origin(), Vector(s.inertial_frame(), x.q, y.q, 0)));
  s.set_gravity(Vector(s.inertial_frame(), g, 0, 0));
  s.add_holonomic_constraint("rod", x.q * x.q + y.q * y.q - l * l);
  return model;
}

}  // namespace eomgen::testing
