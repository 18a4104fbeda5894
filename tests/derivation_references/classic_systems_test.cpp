// Classic textbook systems built through the C++ API, checked against closed forms derived by
// hand (below, in comments), against the literal Lagrange derivation, and against physics that
// does not depend on the form of the equations: the energy balance and, for the heavy top,
// Euler's equations about the fixed pivot.
//
// Conventions (docs/conventions.md): v_b = C_ba v_a; C3(x) = [[c, s, 0], [-s, c, 0], [0, 0, 1]];
// Euler i-j-k: C_ba = Ck(t3) Cj(t2) Ci(t1); M(q) qdd = F(q, qd, t, u).
#include <Eigen/Dense>
#include <ginac/ginac.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <vector>

#include "eomgen/derivation/equations_of_motion.hpp"
#include "eomgen/mechanics/kinematics.hpp"
#include "eomgen/derivation/literal_lagrange.hpp"
#include "eomgen/mechanics/mechanical_system.hpp"
#include "eomgen/mechanics/rotation.hpp"
#include "support/symbolic_checks.hpp"

namespace {

using eomgen::EquationsOfMotion;
using eomgen::FrameId;
using eomgen::MechanicalSystem;
using eomgen::PointId;
using eomgen::Rotation;
using eomgen::Vector;
using eomgen::testing::matrices_agree_at;
using eomgen::testing::near_relative;
using eomgen::testing::random_state;
using eomgen::testing::value_at;
using GiNaC::cos;
using GiNaC::ex;
using GiNaC::exmap;
using GiNaC::matrix;
using GiNaC::pow;
using GiNaC::sin;

constexpr double kTol = 1e-10;
const std::vector<unsigned> kSeeds = {11, 23, 37, 41, 59};

/// A system together with what was derived for it by hand, in the model's own symbols.
struct Model {
  MechanicalSystem system;
  matrix M;            ///< mass matrix d2T/dqd2
  matrix F;            ///< forcing (everything but M qdd, on the right-hand side)
  ex T;                ///< kinetic energy
  ex V;                ///< potential energy
  ex input_power = 0;  ///< dE/dt = power of the non-conservative loads
};

ex sq(const ex& e) { return pow(e, 2); }

// ---------------------------------------------------------------------------------------------
// (a) Simple pendulum. Inertial frame a: a1 horizontal, a2 vertically UP, a3 out of the plane;
// gravity g = -g a2. Frame b = C3(theta) relative to a; the bob is at r = -l b2 from the pivot
// (the origin), so theta is measured from the downward vertical, positive about a3:
//   r_a = C_ab [0, -l, 0]^T = l [sin th, -cos th, 0]^T,   v_a = l th' [cos th, sin th, 0]^T.
//   T = 1/2 m l^2 th'^2,   V = -m g.r = -m g l cos th.
//   M = m l^2,   F = -dV/dth = -m g l sin th.
Model simple_pendulum() {
  Model md;
  MechanicalSystem& s = md.system;
  const auto th = s.add_coordinate("theta");
  const ex m = s.add_parameter("m", 1.3, "kg");
  const ex l = s.add_parameter("l", 0.7, "m");
  const ex g = s.add_parameter("g", 9.81, "m/s^2");
  const FrameId a = s.inertial_frame();
  const FrameId b = s.add_frame("b", a, Rotation::principal(3, th.q));
  const PointId bob = s.add_point("bob", s.origin(), Vector(b, 0, -l, 0));
  s.add_particle("mass", m, bob);
  s.set_gravity(Vector(a, 0, -g, 0));

  md.M = matrix{{m * l * l}};
  md.F = matrix{{-m * g * l * sin(th.q)}};
  md.T = m * l * l * sq(th.qd) / 2;
  md.V = -m * g * l * cos(th.q);
  return md;
}

// ---------------------------------------------------------------------------------------------
// (b) Planar double pendulum, ABSOLUTE angles th1, th2, each from the downward vertical. Axes
// and gravity as in (a). Frames b1 = C3(th1), b2 = C3(th2), both relative to a; mass m1 at
// -l1 b1 from the pivot, mass m2 at -l2 b2 from m1:
//   v1 = l1 th1' [c1, s1, 0],   v2 = v1 + l2 th2' [c2, s2, 0]
//   T = 1/2 (m1+m2) l1^2 th1'^2 + 1/2 m2 l2^2 th2'^2 + m2 l1 l2 cos(th1-th2) th1' th2'
//   V = -(m1+m2) g l1 cos th1 - m2 g l2 cos th2
//   M = [[(m1+m2) l1^2, m2 l1 l2 c12], [m2 l1 l2 c12, m2 l2^2]],  c12 = cos(th1-th2)
// d/dt dT/dth1' brings -m2 l1 l2 s12 (th1'-th2') th2', and dT/dth1 = -m2 l1 l2 s12 th1' th2':
//   F1 = -m2 l1 l2 s12 th2'^2 - (m1+m2) g l1 sin th1
// d/dt dT/dth2' brings -m2 l1 l2 s12 (th1'-th2') th1', and dT/dth2 = +m2 l1 l2 s12 th1' th2':
//   F2 = +m2 l1 l2 s12 th1'^2 - m2 g l2 sin th2
Model double_pendulum() {
  Model md;
  MechanicalSystem& s = md.system;
  const auto q1 = s.add_coordinate("theta1");
  const auto q2 = s.add_coordinate("theta2");
  const ex m1 = s.add_parameter("m1", 1.2, "kg");
  const ex m2 = s.add_parameter("m2", 0.8, "kg");
  const ex l1 = s.add_parameter("l1", 0.9, "m");
  const ex l2 = s.add_parameter("l2", 0.6, "m");
  const ex g = s.add_parameter("g", 9.81, "m/s^2");
  const FrameId a = s.inertial_frame();
  const FrameId b1 = s.add_frame("b1", a, Rotation::principal(3, q1.q));
  const FrameId b2 = s.add_frame("b2", a, Rotation::principal(3, q2.q));
  const PointId p1 = s.add_point("p1", s.origin(), Vector(b1, 0, -l1, 0));
  const PointId p2 = s.add_point("p2", p1, Vector(b2, 0, -l2, 0));
  s.add_particle("mass1", m1, p1);
  s.add_particle("mass2", m2, p2);
  s.set_gravity(Vector(a, 0, -g, 0));

  const ex c12 = cos(q1.q - q2.q), s12 = sin(q1.q - q2.q);
  md.M = matrix{{(m1 + m2) * l1 * l1, m2 * l1 * l2 * c12}, {m2 * l1 * l2 * c12, m2 * l2 * l2}};
  md.F = matrix{{-m2 * l1 * l2 * s12 * sq(q2.qd) - (m1 + m2) * g * l1 * sin(q1.q)},
                {m2 * l1 * l2 * s12 * sq(q1.qd) - m2 * g * l2 * sin(q2.q)}};
  md.T = (m1 + m2) * l1 * l1 * sq(q1.qd) / 2 + m2 * l2 * l2 * sq(q2.qd) / 2 +
         m2 * l1 * l2 * c12 * q1.qd * q2.qd;
  md.V = -(m1 + m2) * g * l1 * cos(q1.q) - m2 * g * l2 * cos(q2.q);
  return md;
}

// ---------------------------------------------------------------------------------------------
// (c) Cart-pole. Axes and gravity as in (a). Cart: particle of mass mc at x a1 on the rail,
// pushed by the input force u a1 (add_force). Pole: uniform rod of LENGTH 2l (mass centre at l
// from the pivot on the cart), mass mp, frame b = C3(theta) relative to a, rod along +b2, so
// theta = 0 is UPRIGHT and positive theta tips the pole towards -a1. Inertia about the mass
// centre in b: diag(mp l^2/3, Ja, mp l^2/3), with (2l)^2/12 = l^2/3; the axial Ja (a thin rod
// has none, but the API wants J positive definite) must not appear in the planar equations.
//   r_c = [x - l sin th, l cos th, 0],   v_c = [x' - l cos th th', -l sin th th', 0]
//   T = 1/2 (mc+mp) x'^2 - mp l cos th x' th' + 1/2 (4/3) mp l^2 th'^2,  V = mp g l cos th
//   M = [[mc+mp, -mp l cos th], [-mp l cos th, 4/3 mp l^2]]
//   x:  d/dt dT/dx' = M row qdd + mp l sin th th'^2, Q_x = u    => F1 = u - mp l sin th th'^2
//   th: d/dt dT/dth' = M row qdd + mp l sin th x' th', dT/dth = mp l sin th x' th',
//       -dV/dth = mp g l sin th                              => F2 = mp g l sin th
//   The force does work at the rate u x' (the only non-conservative power).
Model cart_pole() {
  Model md;
  MechanicalSystem& s = md.system;
  const auto x = s.add_coordinate("x");
  const auto th = s.add_coordinate("theta");
  const ex mc = s.add_parameter("mc", 1.5, "kg");
  const ex mp = s.add_parameter("mp", 0.4, "kg");
  const ex l = s.add_parameter("l", 0.5, "m");
  const ex Ja = s.add_parameter("Ja", 1e-3, "kg m^2");
  const ex g = s.add_parameter("g", 9.81, "m/s^2");
  const ex u = s.add_input("u");
  const FrameId a = s.inertial_frame();
  const FrameId b = s.add_frame("b", a, Rotation::principal(3, th.q));
  const PointId cart = s.add_point("cart", s.origin(), Vector(a, x.q, 0, 0));
  const PointId centre = s.add_point("pole_centre", cart, Vector(b, 0, l, 0));
  s.add_particle("cart_mass", mc, cart);
  const ex Jt = mp * l * l / 3;
  s.add_rigid_body("pole", mp, centre, b, matrix{{Jt, 0, 0}, {0, Ja, 0}, {0, 0, Jt}});
  s.set_gravity(Vector(a, 0, -g, 0));
  s.add_force(cart, Vector(a, u, 0, 0));

  const ex c = cos(th.q), sn = sin(th.q);
  md.M = matrix{{mc + mp, -mp * l * c}, {-mp * l * c, ex(4) / 3 * mp * l * l}};
  md.F = matrix{{u - mp * l * sn * sq(th.qd)}, {mp * g * l * sn}};
  md.T = (mc + mp) * sq(x.qd) / 2 - mp * l * c * x.qd * th.qd + ex(2) / 3 * mp * l * l * sq(th.qd);
  md.V = mp * g * l * c;
  md.input_power = u * x.qd;
  return md;
}

// ---------------------------------------------------------------------------------------------
// (d) Spherical pendulum. Inertial frame a with a3 vertically UP; gravity g = -g a3. Two
// principal rotations: f = C3(phi) relative to a (azimuth), b = C1(theta) relative to f; the
// bob is at -l b3 from the pivot, so theta is the polar angle from the downward vertical:
//   r_a = C_af C_fb [0, 0, -l]^T = l [-sin th sin ph, sin th cos ph, -cos th]^T
//   T = 1/2 m l^2 (th'^2 + sin^2 th ph'^2),   V = -m g l cos th;  q = (theta, phi)
//   M = diag(m l^2, m l^2 sin^2 th)
//   th: -dT/dth - dV/dth moved right:  F1 = m l^2 sin th cos th ph'^2 - m g l sin th
//   ph: d/dt (m l^2 sin^2 th ph') = M22 ph'' + 2 m l^2 sin th cos th th' ph'
//                                      => F2 = -2 m l^2 sin th cos th th' ph'
Model spherical_pendulum() {
  Model md;
  MechanicalSystem& s = md.system;
  const auto th = s.add_coordinate("theta");
  const auto ph = s.add_coordinate("phi");
  const ex m = s.add_parameter("m", 1.1, "kg");
  const ex l = s.add_parameter("l", 0.9, "m");
  const ex g = s.add_parameter("g", 9.81, "m/s^2");
  const FrameId a = s.inertial_frame();
  const FrameId f = s.add_frame("f", a, Rotation::principal(3, ph.q));
  const FrameId b = s.add_frame("b", f, Rotation::principal(1, th.q));
  const PointId bob = s.add_point("bob", s.origin(), Vector(b, 0, 0, -l));
  s.add_particle("mass", m, bob);
  s.set_gravity(Vector(a, 0, 0, -g));

  const ex c = cos(th.q), sn = sin(th.q);
  md.M = matrix{{m * l * l, 0}, {0, m * l * l * sn * sn}};
  md.F = matrix{{m * l * l * sn * c * sq(ph.qd) - m * g * l * sn},
                {-2 * m * l * l * sn * c * th.qd * ph.qd}};
  md.T = m * l * l * (sq(th.qd) + sn * sn * sq(ph.qd)) / 2;
  md.V = -m * g * l * c;
  return md;
}

// ---------------------------------------------------------------------------------------------
// (e) Heavy symmetric top, 3-1-3 Euler angles q = (psi, theta, phi): b relative to a is
// C_ba = C3(phi) C1(theta) C3(psi). Pivot fixed at the origin, mass centre at l b3, inertia
// about the mass centre diag(I1, I1, I3) in b, gravity -g a3. Body angular velocity:
//   omega_b = C3(ph) C1(th) 1_3 ps' + C3(ph) 1_1 th' + 1_3 ph'
//           = [ps' sth sph + th' cph, ps' sth cph - th' sph, ps' cth + ph']
// v_c = omega x l b3 gives 1/2 m l^2 (omega1^2 + omega2^2); with I1' = I1 + m l^2 (about the
// pivot) and W = ph' + ps' cos th (the spin):
//   T = 1/2 I1' (th'^2 + ps'^2 sin^2 th) + 1/2 I3 W^2,   V = m g l cos th
//   M = [[I1' s^2 + I3 c^2, 0, I3 c], [0, I1', 0], [I3 c, 0, I3]]
//   p_ps = I1' s^2 ps' + I3 c W: d/dt at qdd = 0 gives 2 I1' s c th' ps' - I3 s th' W - I3 s c th' ps'
//     => F_ps = -2 I1' s c th' ps' + I3 s th' W + I3 s c th' ps'
//   p_th = I1' th'; dL/dth = I1' s c ps'^2 - I3 s ps' W + m g l s
//     => F_th = I1' s c ps'^2 - I3 s ps' W + m g l s
//   p_ph = I3 W: d/dt at qdd = 0 gives -I3 s th' ps'   => F_ph = I3 s th' ps'
struct HeavyTop {
  Model model;
  FrameId body;
  ex m, g, l, I1, I3;
  eomgen::Coordinate psi, theta, phi;
};

HeavyTop heavy_top() {
  HeavyTop top;
  MechanicalSystem& s = top.model.system;
  top.psi = s.add_coordinate("psi");
  top.theta = s.add_coordinate("theta");
  top.phi = s.add_coordinate("phi");
  top.m = s.add_parameter("m", 0.8, "kg");
  top.g = s.add_parameter("g", 9.81, "m/s^2");
  top.l = s.add_parameter("l", 0.3, "m");
  top.I1 = s.add_parameter("I1", 0.02, "kg m^2");
  top.I3 = s.add_parameter("I3", 0.035, "kg m^2");
  const FrameId a = s.inertial_frame();
  top.body = s.add_frame("b", a, Rotation::euler(eomgen::EulerSequence::parse("3-1-3"), top.psi.q,
                                                 top.theta.q, top.phi.q));
  const PointId centre = s.add_point("c", s.origin(), Vector(top.body, 0, 0, top.l));
  s.add_rigid_body("top", top.m, centre, top.body,
                   matrix{{top.I1, 0, 0}, {0, top.I1, 0}, {0, 0, top.I3}});
  s.set_gravity(Vector(a, 0, 0, -top.g));

  const ex &m = top.m, &g = top.g, &l = top.l, &I3 = top.I3;
  const ex I1p = top.I1 + m * l * l;
  const ex c = cos(top.theta.q), sn = sin(top.theta.q);
  const ex psd = top.psi.qd, thd = top.theta.qd, phd = top.phi.qd;
  const ex W = phd + psd * c;
  Model& md = top.model;
  md.M = matrix{{I1p * sn * sn + I3 * c * c, 0, I3 * c}, {0, I1p, 0}, {I3 * c, 0, I3}};
  md.F = matrix{{-2 * I1p * sn * c * thd * psd + I3 * sn * thd * W + I3 * sn * c * thd * psd},
                {I1p * sn * c * psd * psd - I3 * sn * psd * W + m * g * l * sn},
                {I3 * sn * thd * psd}};
  md.T = I1p * (sq(thd) + sq(psd) * sn * sn) / 2 + I3 * sq(W) / 2;
  md.V = m * g * l * c;
  return top;
}

// ---------------------------------------------------------------------------------------------
// The checks, shared by every system.

// 1. M and F equal the hand derivation.
void expect_hand_equations(const Model& md) {
  const EquationsOfMotion eom = eomgen::derive_equations(md.system);
  for (unsigned seed : kSeeds) {
    const exmap p = random_state(md.system, seed);
    EXPECT_TRUE(matrices_agree_at(eom.mass_matrix, eom.subexpressions, md.M, p, kTol)) << "M, seed " << seed;
    EXPECT_TRUE(matrices_agree_at(eom.forcing, eom.subexpressions, md.F, p, kTol)) << "F, seed " << seed;
  }
}

// 2. M is symmetric positive definite.
void expect_symmetric_positive_definite_mass_matrix(const Model& md) {
  const EquationsOfMotion eom = eomgen::derive_equations(md.system);
  for (unsigned seed : kSeeds) {
    const exmap all = eom.subexpressions.evaluate_all(random_state(md.system, seed));
    const Eigen::MatrixXd M = value_at(eom.mass_matrix, all);
    EXPECT_LE((M - M.transpose()).norm(), 1e-14 * M.norm()) << "seed " << seed;
    EXPECT_EQ(M.llt().info(), Eigen::Success) << "seed " << seed << "\n" << M;
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(M);
    EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0) << "seed " << seed << "\n" << M;
  }
}

// 3. The engine agrees with the literal differentiation of L.
void expect_literal_agreement(const Model& md) {
  const EquationsOfMotion eom = eomgen::derive_equations(md.system);
  const eomgen::LiteralLagrangeEquations lit = eomgen::derive_equations_literally(md.system);
  for (unsigned seed : kSeeds) {
    const exmap p = random_state(md.system, seed);
    EXPECT_TRUE(matrices_agree_at(eom.mass_matrix, eom.subexpressions, lit.mass_matrix, p, kTol)) << "M, seed " << seed;
    EXPECT_TRUE(matrices_agree_at(eom.forcing, eom.subexpressions, lit.forcing, p, kTol)) << "F, seed " << seed;
  }
}

// Accelerations from M qdd = F, solved numerically.
Eigen::VectorXd solve_accelerations(const EquationsOfMotion& eom, const exmap& point) {
  const exmap all = eom.subexpressions.evaluate_all(point);
  return value_at(eom.mass_matrix, all).llt().solve(value_at(eom.forcing, all));
}

// 4(i). Energy balance: with qdd from M qdd = F, dE/dt = grad_q E . qd + grad_qd E . qdd + dE/dt
// (E = T + V of the engine, written out) equals the power of the non-conservative loads.
void expect_energy_rate_equals_input_power(const Model& md) {
  const EquationsOfMotion eom = eomgen::derive_equations(md.system);
  const auto& vars = md.system.variables();
  const ex E = eom.subexpressions.expand(eom.kinetic_energy + eom.potential_energy);
  std::vector<ex> dE_dq, dE_dqd;
  for (const auto& c : vars.coordinates()) {
    dE_dq.push_back(E.diff(c.q));
    dE_dqd.push_back(E.diff(c.qd));
  }
  const ex dE_dt = E.diff(vars.time());
  for (unsigned seed : kSeeds) {
    const exmap p = random_state(md.system, seed);
    const Eigen::VectorXd qdd = solve_accelerations(eom, p);
    double rate = value_at(dE_dt, p), scale = std::fabs(rate);
    for (std::size_t k = 0; k < vars.coordinate_count(); ++k) {
      const double a = value_at(dE_dq[k], p) * value_at(vars.coordinates()[k].qd, p);
      const double b = value_at(dE_dqd[k], p) * qdd(static_cast<Eigen::Index>(k));
      rate += a + b;
      scale += std::fabs(a) + std::fabs(b);
    }
    const double power = value_at(md.input_power, p);
    // relative to the size of the terms that cancel
    EXPECT_LE(std::fabs(rate - power), kTol * std::max(1.0, scale))
        << "seed " << seed << ": dE/dt = " << rate << ", input power = " << power;
  }
}

// 5. T and V equal the hand derivation.
void expect_hand_energies(const Model& md) {
  const EquationsOfMotion eom = eomgen::derive_equations(md.system);
  for (unsigned seed : kSeeds) {
    const exmap p = random_state(md.system, seed);
    EXPECT_TRUE(matrices_agree_at(matrix{{eom.kinetic_energy}}, eom.subexpressions, matrix{{md.T}}, p, kTol))
        << "T, seed " << seed;
    EXPECT_TRUE(matrices_agree_at(matrix{{eom.potential_energy}}, eom.subexpressions, matrix{{md.V}}, p, kTol))
        << "V, seed " << seed;
  }
}

// ---------------------------------------------------------------------------------------------
// (a) simple pendulum

TEST(SimplePendulum, MassMatrixAndForcingMatchHandDerivation) { expect_hand_equations(simple_pendulum()); }
TEST(SimplePendulum, MassMatrixIsSymmetricPositiveDefinite) {
  expect_symmetric_positive_definite_mass_matrix(simple_pendulum());
}
TEST(SimplePendulum, AgreesWithLiteralLagrangeDerivation) { expect_literal_agreement(simple_pendulum()); }
TEST(SimplePendulum, ConservesEnergy) { expect_energy_rate_equals_input_power(simple_pendulum()); }
TEST(SimplePendulum, EnergiesMatchHandDerivation) { expect_hand_energies(simple_pendulum()); }

// (b) double pendulum

TEST(DoublePendulum, MassMatrixAndForcingMatchHandDerivation) { expect_hand_equations(double_pendulum()); }
TEST(DoublePendulum, MassMatrixIsSymmetricPositiveDefinite) {
  expect_symmetric_positive_definite_mass_matrix(double_pendulum());
}
TEST(DoublePendulum, AgreesWithLiteralLagrangeDerivation) { expect_literal_agreement(double_pendulum()); }
TEST(DoublePendulum, ConservesEnergy) { expect_energy_rate_equals_input_power(double_pendulum()); }
TEST(DoublePendulum, EnergiesMatchHandDerivation) { expect_hand_energies(double_pendulum()); }

// (c) cart-pole

TEST(CartPole, MassMatrixAndForcingMatchHandDerivation) { expect_hand_equations(cart_pole()); }
TEST(CartPole, MassMatrixIsSymmetricPositiveDefinite) { expect_symmetric_positive_definite_mass_matrix(cart_pole()); }
TEST(CartPole, AgreesWithLiteralLagrangeDerivation) { expect_literal_agreement(cart_pole()); }
TEST(CartPole, EnergyRateEqualsInputForcePower) { expect_energy_rate_equals_input_power(cart_pole()); }
TEST(CartPole, EnergiesMatchHandDerivation) { expect_hand_energies(cart_pole()); }

TEST(CartPole, AxialInertiaOfThePoleDoesNotEnterThePlanarEquations) {
  const Model md = cart_pole();
  const EquationsOfMotion eom = eomgen::derive_equations(md.system);
  const ex Ja = *md.system.variables().find("Ja");
  const matrix M = eom.subexpressions.expand(eom.mass_matrix), F = eom.subexpressions.expand(eom.forcing);
  for (unsigned i = 0; i < 2; ++i) {
    EXPECT_TRUE(GiNaC::expand(F(i, 0)).diff(GiNaC::ex_to<GiNaC::symbol>(Ja)).is_zero()) << F(i, 0);
    for (unsigned j = 0; j < 2; ++j)
      EXPECT_TRUE(GiNaC::expand(M(i, j)).diff(GiNaC::ex_to<GiNaC::symbol>(Ja)).is_zero()) << M(i, j);
  }
}

// (d) spherical pendulum

TEST(SphericalPendulum, MassMatrixAndForcingMatchHandDerivation) { expect_hand_equations(spherical_pendulum()); }
TEST(SphericalPendulum, MassMatrixIsSymmetricPositiveDefinite) {
  expect_symmetric_positive_definite_mass_matrix(spherical_pendulum());
}
TEST(SphericalPendulum, AgreesWithLiteralLagrangeDerivation) { expect_literal_agreement(spherical_pendulum()); }
TEST(SphericalPendulum, ConservesEnergy) { expect_energy_rate_equals_input_power(spherical_pendulum()); }
TEST(SphericalPendulum, EnergiesMatchHandDerivation) { expect_hand_energies(spherical_pendulum()); }

// (e) heavy symmetric top

TEST(HeavySymmetricTop, MassMatrixAndForcingMatchHandDerivation) { expect_hand_equations(heavy_top().model); }
TEST(HeavySymmetricTop, MassMatrixIsSymmetricPositiveDefinite) {
  expect_symmetric_positive_definite_mass_matrix(heavy_top().model);
}
TEST(HeavySymmetricTop, AgreesWithLiteralLagrangeDerivation) { expect_literal_agreement(heavy_top().model); }
TEST(HeavySymmetricTop, ConservesEnergy) { expect_energy_rate_equals_input_power(heavy_top().model); }
TEST(HeavySymmetricTop, EnergiesMatchHandDerivation) { expect_hand_energies(heavy_top().model); }

// 4(ii). Newton-Euler about the fixed pivot o, in the body frame:
//   J_o domega/dt + omega x J_o omega = r^{co} x (m g),   J_o = J_c - m r^x r^x,
// with omega_b from the kinematics (checked against the hand formula above), its rate
// d(omega_b)/dt (= the body components of the rate seen in a, since omega x omega = 0) by
// Variables::time_derivative with the accelerations of M qdd = F substituted.
TEST(HeavySymmetricTop, SolvedAccelerationsSatisfyEulerEquationsAboutThePivot) {
  const HeavyTop top = heavy_top();
  const MechanicalSystem& s = top.model.system;
  const auto& vars = s.variables();
  const EquationsOfMotion eom = eomgen::derive_equations(s);

  const matrix w = eomgen::resolve(s, eomgen::angular_velocity(s, top.body, s.inertial_frame()), top.body);
  const ex st = sin(top.theta.q), ct = cos(top.theta.q), sp = sin(top.phi.q), cp = cos(top.phi.q);
  const matrix w_hand{{top.psi.qd * st * sp + top.theta.qd * cp},
                      {top.psi.qd * st * cp - top.theta.qd * sp},
                      {top.psi.qd * ct + top.phi.qd}};
  matrix w_dot(3, 1);
  for (unsigned i = 0; i < 3; ++i) w_dot(i, 0) = vars.time_derivative(w(i, 0));
  const matrix r_co{{0}, {0}, {top.l}};
  const matrix J_c{{top.I1, 0, 0}, {0, top.I1, 0}, {0, 0, top.I3}};
  const matrix J_o = eomgen::parallel_axis(J_c, top.m, r_co);
  const matrix g_b = eomgen::dcm(s, top.body, s.inertial_frame()).mul(matrix{{0}, {0}, {-top.g}});

  for (unsigned seed : kSeeds) {
    exmap p = random_state(s, seed);
    EXPECT_TRUE(matrices_agree_at(w, eomgen::Subexpressions(), w_hand, p, kTol)) << "omega_b, seed " << seed;
    const Eigen::VectorXd qdd = solve_accelerations(eom, p);
    for (std::size_t k = 0; k < 3; ++k) p[vars.coordinates()[k].qdd] = qdd(static_cast<Eigen::Index>(k));
    const Eigen::Vector3d omega = value_at(w, p), alpha = value_at(w_dot, p);
    const Eigen::Matrix3d J = value_at(J_o, p);
    const Eigen::Vector3d r = value_at(r_co, p), weight = value_at(top.m, p) * value_at(g_b, p);
    const Eigen::Vector3d lhs = J * alpha + omega.cross(J * omega);
    const Eigen::Vector3d rhs = r.cross(weight);
    for (int i = 0; i < 3; ++i)
      EXPECT_TRUE(near_relative(lhs(i), rhs(i), kTol)) << "component " << i << ", seed " << seed;
  }
}

}  // namespace
