#include "eomgen/derivation/literal_lagrange.hpp"

#include <gtest/gtest.h>

#include "eomgen/symbolic/simplify.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;

TEST(LiteralLagrange, SimplePendulumClosedForm) {
  // bob at l b1, b = C3(theta) a, gravity g a1: m l^2 theta_ddot = -m g l sin(theta)
  MechanicalSystem s;
  const auto th = s.add_coordinate("theta");
  const ex m = s.add_parameter("m", 1), l = s.add_parameter("l", 1), g = s.add_parameter("g", 9.81);
  const auto b = s.add_frame("b", s.inertial_frame(), Rotation::principal(3, th.q));
  s.add_particle("bob", m, s.add_point("p", s.origin(), Vector(b, l, 0, 0)));
  s.set_gravity(Vector(s.inertial_frame(), g, 0, 0));
  const LiteralLagrangeEquations eq = derive_equations_literally(s);
  EXPECT_TRUE(simplify_for_display(eq.mass_matrix(0, 0) - m * l * l).is_zero());
  EXPECT_TRUE(simplify_for_display(eq.forcing(0, 0) + m * g * l * GiNaC::sin(th.q)).is_zero());
  EXPECT_TRUE(simplify_for_display(eq.potential_energy + m * g * l * GiNaC::cos(th.q)).is_zero());
}

TEST(LiteralLagrange, ViscousCoordinateDamperAndInputForce) {
  // unit mass on a line: x_ddot = -c x_dot + u
  MechanicalSystem s;
  const auto x = s.add_coordinate("x");
  const ex c = s.add_parameter("c", 0.5), u = s.add_input("u");
  const auto p = s.add_point("p", s.origin(), Vector(s.inertial_frame(), x.q, 0, 0));
  s.add_particle("mass", 1, p);
  s.add_coordinate_damper("friction", x.q, c);
  s.add_force(p, Vector(s.inertial_frame(), u, 0, 0));
  const LiteralLagrangeEquations eq = derive_equations_literally(s);
  EXPECT_TRUE(simplify_for_display(eq.forcing(0, 0) - (-c * x.qd + u)).is_zero());
}

}  // namespace
}  // namespace eomgen
