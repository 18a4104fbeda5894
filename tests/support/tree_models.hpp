#pragma once
// Kinematic trees built through the C++ API for the recursive algorithms (articulated body,
// composite body): loads of every kind, a branch, joints that move with time.
#include "eomgen/mechanics/model.hpp"

namespace eomgen::testing {

// two rods, a torque input on the elbow, a force at the tip, a moment on rod 1, a spring and a
// damper from the tip to a fixed point and a torsional spring on the elbow; the rods' inertia is
// one a mass distribution has (each principal moment at most the sum of the other two)
inline Model loaded_double_rod() {
  Model model;
  MechanicalSystem& s = model.system;
  const Coordinate q1 = s.add_coordinate("q1"), q2 = s.add_coordinate("q2");
  const GiNaC::ex m = s.add_parameter("m", 1.3), l = s.add_parameter("l", 0.7);
  const GiNaC::ex torque = s.add_input("torque"), push = s.add_input("push");
  const FrameId b = s.add_frame("b", s.inertial_frame(), Rotation::principal(3, q1.q));
  const FrameId c = s.add_frame("c", b, Rotation::principal(3, q2.q));
  const GiNaC::matrix J = GiNaC::ex_to<GiNaC::matrix>(GiNaC::diag_matrix(GiNaC::lst{0.01, m * l * l / 12, m * l * l / 12 + 0.005}));
  const PointId elbow = s.add_point("elbow", s.origin(), Vector(b, l, 0, 0));
  s.add_rigid_body("rod1", m, s.add_point("c1", s.origin(), Vector(b, l / 2, 0, 0)), b, J);
  s.add_rigid_body("rod2", m, s.add_point("c2", elbow, Vector(c, l / 2, 0.05, 0)), c, J);
  const PointId tip = s.add_point("tip", elbow, Vector(c, l, 0, 0));
  const PointId anchor = s.add_point("anchor", s.origin(), Vector(s.inertial_frame(), 0.5, 1.5, 0.2));
  s.set_gravity(Vector(s.inertial_frame(), 9.81, 0, 0));
  s.add_generalized_force(1, torque);
  s.add_force(tip, Vector(s.inertial_frame(), push, 0.3, 0));
  s.add_moment(b, Vector(s.inertial_frame(), 0, 0, 0.4));
  s.add_spring("spring", tip, anchor, 20.0, 0.5);
  s.add_damper("damper", tip, anchor, 0.7);
  s.add_torsional_spring("elbow_spring", q2.q, 3.0, 0.1);
  return model;
}

// a body on a rail (x) turning about a.3 (psi), two pendulums hanging from it: a branched tree
inline Model branched_tree() {
  Model model;
  MechanicalSystem& s = model.system;
  const Coordinate x = s.add_coordinate("x"), psi = s.add_coordinate("psi");
  const Coordinate q1 = s.add_coordinate("q1"), q2 = s.add_coordinate("q2");
  const FrameId body = s.add_frame("platform", s.inertial_frame(), Rotation::principal(3, psi.q));
  const FrameId arm1 = s.add_frame("arm1", body, Rotation::principal(1, q1.q));
  const FrameId arm2 = s.add_frame("arm2", body, Rotation::principal(2, q2.q));
  const PointId centre = s.add_point("centre", s.origin(), Vector(s.inertial_frame(), x.q, 0, 0));
  GiNaC::matrix J(3, 3);
  J(0, 0) = 0.3, J(1, 1) = 0.4, J(2, 2) = 0.5, J(0, 1) = J(1, 0) = 0.05;
  s.add_rigid_body("carriage", 3.0, centre, body, J);
  const PointId hinge1 = s.add_point("hinge1", centre, Vector(body, 0.4, 0, 0));
  const PointId hinge2 = s.add_point("hinge2", centre, Vector(body, -0.4, 0.1, 0));
  s.add_rigid_body("rod1", 0.7, s.add_point("c1", hinge1, Vector(arm1, 0, 0.1, -0.3)), arm1, J);
  s.add_particle("bob2", 0.9, s.add_point("c2", hinge2, Vector(arm2, 0.05, 0, -0.5)));
  s.set_gravity(Vector(s.inertial_frame(), 0, 0, -9.81));
  return model;
}

// a rigid pendulum on a pivot that shakes along a.1 inside a frame that spins about a.3: joints
// whose motion depends on time explicitly
inline Model shaken_pendulum_with_slider() {
  Model model;
  MechanicalSystem& s = model.system;
  const Coordinate q = s.add_coordinate("q"), x = s.add_coordinate("x");
  const GiNaC::ex t = s.variables().time();
  const FrameId spin = s.add_frame("spin", s.inertial_frame(), Rotation::principal(3, 0.7 * t));
  const FrameId b = s.add_frame("b", spin, Rotation::principal(1, q.q));
  const PointId pivot = s.add_point("pivot", s.origin(), Vector(spin, 0.2 * GiNaC::sin(3 * t), 0, 0.1));
  GiNaC::matrix J(3, 3);
  J(0, 0) = 0.02, J(1, 1) = 0.03, J(2, 2) = 0.04;
  const PointId centre = s.add_point("centre", pivot, Vector(b, 0.1, 0.05, -0.5));
  s.add_rigid_body("rod", 1.2, centre, b, J);
  s.add_particle("slider", 0.4, s.add_point("slider_point", centre, Vector(b, 0, x.q, 0)));
  s.set_gravity(Vector(s.inertial_frame(), 0, 0, -9.81));
  return model;
}

}  // namespace eomgen::testing
