// Derives and prints the equations of motion of a planar double pendulum through the C++ API.
//
// Two point masses m1, m2 hang from massless rods of lengths l1, l2. Frame b turns by q1 about
// a3 relative to the inertial frame a, frame c by q2 (relative angle) about b3; the rods lie
// along b1 and c1, and gravity g points along a1 (down), so q1 = q2 = 0 hangs straight down.
#include <eomgen/derivation/equations_of_motion.hpp>
#include <eomgen/symbolic/simplify.hpp>

#include <iostream>

int main() {
  using eomgen::Rotation;
  using eomgen::Vector;
  eomgen::MechanicalSystem system("a", "w");
  const auto q1 = system.add_coordinate("q1");
  const auto q2 = system.add_coordinate("q2");
  const GiNaC::ex m1 = system.add_parameter("m1", 1.0, "kg");
  const GiNaC::ex m2 = system.add_parameter("m2", 1.0, "kg");
  const GiNaC::ex l1 = system.add_parameter("l1", 1.0, "m");
  const GiNaC::ex l2 = system.add_parameter("l2", 1.0, "m");
  const GiNaC::ex g = system.add_parameter("g", 9.81, "m/s^2");

  const auto a = system.inertial_frame();
  const auto b = system.add_frame("b", a, Rotation::principal(3, q1.q));
  const auto c = system.add_frame("c", b, Rotation::principal(3, q2.q));
  const auto p1 = system.add_point("p1", system.origin(), Vector(b, l1, 0, 0));
  const auto p2 = system.add_point("p2", p1, Vector(c, l2, 0, 0));
  system.add_particle("bob1", m1, p1);
  system.add_particle("bob2", m2, p2);
  system.set_gravity(Vector(a, g, 0, 0));

  const eomgen::EquationsOfMotion eom = eomgen::derive_equations(system);
  const auto& z = eom.subexpressions;
  std::cout << "Planar double pendulum: M(q) qdd = F(q, qd)\n\n";
  const GiNaC::matrix M = eomgen::simplify_for_display(z.expand(eom.mass_matrix));
  const GiNaC::matrix F = eomgen::simplify_for_display(z.expand(eom.forcing));
  for (unsigned i = 0; i < 2; ++i)
    for (unsigned j = 0; j < 2; ++j) std::cout << "M(" << i + 1 << "," << j + 1 << ") = " << M(i, j) << "\n";
  std::cout << "\n";
  for (unsigned i = 0; i < 2; ++i) std::cout << "F(" << i + 1 << ") = " << F(i, 0) << "\n";
  std::cout << "\nT = " << eomgen::simplify_for_display(z.expand(eom.kinetic_energy)) << "\n";
  std::cout << "V = " << eomgen::simplify_for_display(z.expand(eom.potential_energy)) << "\n";
  std::cout << "\n(" << z.size() << " shared intermediates in the unexpanded derivation)\n";
  return 0;
}
