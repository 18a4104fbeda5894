#include "chain_models.hpp"

#include <string>

namespace eomgen::bench {

namespace {

GiNaC::matrix diagonal(const GiNaC::ex& d1, const GiNaC::ex& d2, const GiNaC::ex& d3) {
  GiNaC::matrix J(3, 3);
  J(0, 0) = d1;
  J(1, 1) = d2;
  J(2, 2) = d3;
  return J;
}

}  // namespace

MechanicalSystem planar_chain(std::size_t n) {
  MechanicalSystem s;
  const GiNaC::ex m = s.add_parameter("m", 2.0, "kg");
  const GiNaC::ex l = s.add_parameter("l", 0.5, "m");
  const GiNaC::ex g = s.add_parameter("g", 9.81, "m/s^2");
  const FrameId a = s.inertial_frame();
  s.set_gravity(Vector(a, g, 0, 0));

  const GiNaC::matrix J = diagonal(m * l * l / 1200, m * l * l / 12, m * l * l / 12);
  FrameId previous_frame = a;
  PointId previous_joint = s.origin();
  for (std::size_t i = 1; i <= n; ++i) {
    const std::string k = std::to_string(i);
    const Coordinate q = s.add_coordinate("q" + k);
    const FrameId b = s.add_frame("b" + k, previous_frame, Rotation::principal(3, q.q));
    const PointId centre = s.add_point("mc" + k, previous_joint, Vector(b, l / 2, 0, 0));
    s.add_rigid_body("rod" + k, m, centre, b, J);
    if (i < n) previous_joint = s.add_point("j" + k, previous_joint, Vector(b, l, 0, 0));
    previous_frame = b;
  }
  return s;
}

MechanicalSystem universal_joint_chain(std::size_t n) {
  MechanicalSystem s;
  const GiNaC::ex m = s.add_parameter("m", 2.0, "kg");
  const GiNaC::ex l = s.add_parameter("l", 0.5, "m");
  const GiNaC::ex h = s.add_parameter("h", 0.05, "m");
  const GiNaC::ex g = s.add_parameter("g", 9.81, "m/s^2");
  const FrameId a = s.inertial_frame();
  s.set_gravity(Vector(a, 0, 0, -g));

  const GiNaC::ex transverse = m * (l * l + h * h) / 12;
  const GiNaC::matrix J = diagonal(transverse, transverse, m * h * h / 6);
  FrameId previous_frame = a;
  PointId previous_joint = s.origin();
  for (std::size_t i = 1; i <= n; ++i) {
    const std::string k = std::to_string(i);
    const Coordinate u = s.add_coordinate("u" + k);
    const Coordinate v = s.add_coordinate("v" + k);
    const FrameId c = s.add_frame("c" + k, previous_frame, Rotation::principal(1, u.q));
    const FrameId b = s.add_frame("b" + k, c, Rotation::principal(2, v.q));
    const PointId centre = s.add_point("mc" + k, previous_joint, Vector(b, 0, 0, -l / 2));
    s.add_rigid_body("body" + k, m, centre, b, J);
    if (i < n) previous_joint = s.add_point("j" + k, previous_joint, Vector(b, 0, 0, -l));
    previous_frame = b;
  }
  return s;
}

}  // namespace eomgen::bench
