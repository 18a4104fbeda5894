// derive_equations: constraint terms against hand derivations, a rheonomic system, and every
// kind of load against the independent literal Lagrange derivation.
#include "eomgen/derivation/equations_of_motion.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <gtest/gtest.h>

#include "eomgen/derivation/literal_lagrange.hpp"
#include "eomgen/symbolic/simplify.hpp"
#include "support/symbolic_checks.hpp"

namespace eomgen {
namespace {

using GiNaC::cos;
using GiNaC::ex;
using GiNaC::matrix;
using GiNaC::sin;
using testing::equal_after_simplification;

matrix diag(const ex& a, const ex& b, const ex& c) { return matrix(3, 3, GiNaC::lst{a, 0, 0, 0, b, 0, 0, 0, c}); }

// M, F, T and V of the engine against the literal derivation at several random states
void expect_agrees_with_literal_lagrange(const MechanicalSystem& s, double tol = 1e-10) {
  const EquationsOfMotion eom = derive_equations(s);
  const LiteralLagrangeEquations lit = derive_equations_literally(s);
  Subexpressions none;
  for (unsigned seed = 11; seed < 14; ++seed) {
    const GiNaC::exmap x = testing::random_state(s, seed);
    EXPECT_TRUE(testing::matrices_agree_at(eom.mass_matrix, eom.subexpressions, lit.mass_matrix, x, tol));
    EXPECT_TRUE(testing::matrices_agree_at(eom.forcing, eom.subexpressions, lit.forcing, x, tol));
    EXPECT_TRUE(testing::matrices_agree_at(matrix(1, 1, GiNaC::lst{eom.kinetic_energy}), eom.subexpressions,
                                           matrix(1, 1, GiNaC::lst{lit.kinetic_energy}), x, tol));
    EXPECT_TRUE(testing::matrices_agree_at(matrix(1, 1, GiNaC::lst{eom.potential_energy}), eom.subexpressions,
                                           matrix(1, 1, GiNaC::lst{lit.potential_energy}), x, tol));
  }
}

TEST(Constraints, CartesianPendulumLengthConstraintGivesJacobianAndAccelerationTerm) {
  MechanicalSystem s;
  const auto x = s.add_coordinate("x"), y = s.add_coordinate("y");
  const ex l = s.add_parameter("l", 1.0), m = s.add_parameter("m", 1.0);
  s.add_particle("bob", m, s.add_point("p", s.origin(), Vector(s.inertial_frame(), x.q, y.q, 0)));
  s.add_holonomic_constraint("length", x.q * x.q + y.q * y.q - l * l);
  const EquationsOfMotion eom = derive_equations(s);
  ASSERT_EQ(eom.constraint_count, 1u);
  EXPECT_TRUE(equal_after_simplification(eom.constraint_jacobian(0, 0), 2 * x.q));
  EXPECT_TRUE(equal_after_simplification(eom.constraint_jacobian(0, 1), 2 * y.q));
  EXPECT_TRUE(eom.constraint_rate_term(0, 0).is_zero());
  // d/dt(2 x xd + 2 y yd) = 2 x xdd + 2 y ydd + 2 xd^2 + 2 yd^2
  EXPECT_TRUE(equal_after_simplification(eom.constraint_acceleration_term(0, 0), 2 * x.qd * x.qd + 2 * y.qd * y.qd));
  EXPECT_TRUE(equal_after_simplification(eom.holonomic_residuals(0, 0), x.q * x.q + y.q * y.q - l * l));
  // M = m 1 for a free particle in the plane
  EXPECT_TRUE(equal_after_simplification(eom.subexpressions.expand(eom.mass_matrix(0, 0)), m));
  EXPECT_TRUE(equal_after_simplification(eom.subexpressions.expand(eom.mass_matrix(0, 1)), 0));
}

TEST(Constraints, RheonomicHolonomicConstraintHasTimeTerms) {
  MechanicalSystem s;
  const auto x = s.add_coordinate("x"), y = s.add_coordinate("y");
  const ex A = s.add_parameter("A", 0.5);
  const ex t = s.variables().time();
  s.add_particle("particle", 1, s.add_point("p", s.origin(), Vector(s.inertial_frame(), x.q, y.q, 0)));
  s.add_holonomic_constraint("prescribed", x.q * y.q - A * sin(t));
  const EquationsOfMotion eom = derive_equations(s);
  EXPECT_TRUE(equal_after_simplification(eom.constraint_jacobian(0, 0), y.q));
  EXPECT_TRUE(equal_after_simplification(eom.constraint_jacobian(0, 1), x.q));
  EXPECT_TRUE(equal_after_simplification(eom.constraint_rate_term(0, 0), -A * cos(t)));
  // d/dt(y xd + x yd - A cos t) without accelerations = 2 xd yd + A sin t
  EXPECT_TRUE(equal_after_simplification(eom.constraint_acceleration_term(0, 0), 2 * x.qd * y.qd + A * sin(t)));
}

TEST(Constraints, KnifeEdgeNonholonomicConstraint) {
  MechanicalSystem s;
  const auto x = s.add_coordinate("x"), y = s.add_coordinate("y"), th = s.add_coordinate("theta");
  const ex m = s.add_parameter("m", 2.0), J = s.add_parameter("J", 0.1);
  const auto b = s.add_frame("b", s.inertial_frame(), Rotation::principal(3, th.q));
  s.add_rigid_body("blade", m, s.add_point("c", s.origin(), Vector(s.inertial_frame(), x.q, y.q, 0)), b,
                   diag(J, J, J));
  // no velocity across the blade: -xd sin(theta) + yd cos(theta) = 0
  s.add_nonholonomic_constraint("no_side_slip", -x.qd * sin(th.q) + y.qd * cos(th.q));
  const EquationsOfMotion eom = derive_equations(s);
  EXPECT_TRUE(equal_after_simplification(eom.constraint_jacobian(0, 0), -sin(th.q)));
  EXPECT_TRUE(equal_after_simplification(eom.constraint_jacobian(0, 1), cos(th.q)));
  EXPECT_TRUE(equal_after_simplification(eom.constraint_jacobian(0, 2), 0));
  EXPECT_TRUE(eom.constraint_rate_term(0, 0).is_zero());
  EXPECT_TRUE(equal_after_simplification(eom.constraint_acceleration_term(0, 0),
                                         -x.qd * cos(th.q) * th.qd - y.qd * sin(th.q) * th.qd));
  EXPECT_EQ(eom.holonomic_residuals.rows(), 0u);
  expect_agrees_with_literal_lagrange(s);
}

TEST(Rheonomic, BeadOnHoopTurningAtConstantRate) {
  // hoop turns about the vertical a3 at rate Omega (angle Omega t); the bead sits at angle
  // theta from the bottom: r = R (sin theta h1 - cos theta h3); gravity -g a3.
  // Hand derivation: T = m/2 R^2 (theta_dot^2 + Omega^2 sin^2 theta), V = -m g R cos theta,
  // m R^2 theta_ddot = m R^2 Omega^2 sin theta cos theta - m g R sin theta.
  MechanicalSystem s;
  const auto th = s.add_coordinate("theta");
  const ex m = s.add_parameter("m", 0.2), R = s.add_parameter("R", 0.5), g = s.add_parameter("g", 9.81);
  const ex W = s.add_parameter("Omega", 3.0);
  const auto hoop = s.add_frame("hoop", s.inertial_frame(), Rotation::principal(3, W * s.variables().time()));
  s.add_particle("bead", m, s.add_point("bead_position", s.origin(), Vector(hoop, R * sin(th.q), 0, -R * cos(th.q))));
  s.set_gravity(Vector(s.inertial_frame(), 0, 0, -g));
  const EquationsOfMotion eom = derive_equations(s);
  const auto& z = eom.subexpressions;
  EXPECT_TRUE(equal_after_simplification(z.expand(eom.mass_matrix(0, 0)), m * R * R));
  EXPECT_TRUE(equal_after_simplification(z.expand(eom.forcing(0, 0)),
                                         m * R * R * W * W * sin(th.q) * cos(th.q) - m * g * R * sin(th.q)));
  EXPECT_TRUE(equal_after_simplification(z.expand(eom.kinetic_energy),
                                         m * R * R * (th.qd * th.qd + W * W * GiNaC::pow(sin(th.q), 2)) / 2));
  EXPECT_TRUE(equal_after_simplification(z.expand(eom.potential_energy), -m * g * R * cos(th.q)));
  expect_agrees_with_literal_lagrange(s);
}

// A rigid body on a 3-2-1 joint carried by a slider, with every kind of load at once.
MechanicalSystem loaded_system() {
  MechanicalSystem s("a", "w");
  const auto x = s.add_coordinate("x");
  const auto q1 = s.add_coordinate("q1"), q2 = s.add_coordinate("q2"), q3 = s.add_coordinate("q3");
  const ex m = s.add_parameter("m", 1.7), l = s.add_parameter("l", 0.8), k = s.add_parameter("k", 30.0);
  const ex c = s.add_parameter("c", 0.7), g = s.add_parameter("g", 9.81), L0 = s.add_parameter("L0", 0.4);
  const ex u1 = s.add_input("u1"), u2 = s.add_input("u2");
  const ex t = s.variables().time();
  const auto a = s.inertial_frame();
  const auto b = s.add_frame("b", a, Rotation::euler(EulerSequence::parse("3-2-1"), q1.q, q2.q, q3.q));
  const auto slider = s.add_point("slider", s.origin(), Vector(a, x.q, 0, 0.1 * sin(t)));  // rheonomic
  const auto centre = s.add_point("centre", slider, Vector(b, 0, 0, l / 2));
  const auto tip = s.add_point("tip", slider, Vector(b, 0.1, 0, l));
  const auto anchor = s.add_point("anchor", s.origin(), Vector(a, 0.3, 0.5, 1.0));
  s.add_rigid_body("body", m, centre, b, matrix(3, 3, GiNaC::lst{0.3, 0.01, 0.02, 0.01, 0.25, 0.03, 0.02, 0.03, 0.1}));
  s.add_particle("tip_mass", 0.2, tip);
  s.set_gravity(Vector(a, 0, 0, -g));
  s.add_spring("tether", tip, anchor, k, L0);
  s.add_damper("dashpot", tip, anchor, c);
  s.add_force(tip, Vector(b, u1, 0.5, -0.2 * q2.qd));
  s.add_moment(b, Vector(a, 0, 0, u2));
  s.add_torsional_spring("wrist", q3.q, 2.0, 0.1);
  s.add_coordinate_damper("rail_friction", x.q, 0.4);
  s.add_generalized_force(0, -u1);
  s.add_potential("magnet", 0.5 * x.q * x.q * cos(q1.q));
  return s;
}

TEST(Derivation, EveryLoadKindAgreesWithLiteralLagrange) { expect_agrees_with_literal_lagrange(loaded_system()); }

TEST(Derivation, MassMatrixIsSymmetricPositiveDefiniteAtRandomStates) {
  const MechanicalSystem s = loaded_system();
  const EquationsOfMotion eom = derive_equations(s);
  const std::size_t n = eom.coordinate_count;
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const GiNaC::exmap values = eom.subexpressions.evaluate_all(testing::random_state(s, seed));
    Eigen::MatrixXd M(n, n);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) M(i, j) = testing::to_double(eom.mass_matrix(i, j).subs(values));
    EXPECT_LT((M - M.transpose()).norm(), 1e-14);
    EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(M).info(), Eigen::Success);
  }
}

TEST(Derivation, QuaternionAttitudeDiffersFromLiteralLagrangeOnlyAlongTheNormConstraint) {
  // Free rigid body, quaternion attitude, omega = 2 (eta 1 - eps^x) deps - 2 eps deta. That rate
  // relation is Poisson's equation only on |q| = 1, so Kane's form and literal Lagrange agree in M
  // everywhere but in F only up to a multiple of the constraint gradient q on the manifold: the
  // accelerations from the KKT system are the same, only lambda differs.
  MechanicalSystem s;
  const auto e1 = s.add_coordinate("e1"), e2 = s.add_coordinate("e2"), e3 = s.add_coordinate("e3");
  const auto eta = s.add_coordinate("eta");
  const auto b = s.add_frame("b", s.inertial_frame(),
                             Rotation::quaternion(matrix(3, 1, GiNaC::lst{e1.q, e2.q, e3.q}), eta.q));
  s.add_rigid_body("body", 2.0, s.add_point("c", s.origin(), Vector(b, 0.2, 0.1, 0.3)), b, diag(1.0, 2.0, 3.0));
  s.set_gravity(Vector(s.inertial_frame(), 0, 0, -9.81));
  s.add_moment(b, Vector(b, 0.1, s.add_input("tau"), 0));
  s.add_holonomic_constraint("unit_norm", e1.q * e1.q + e2.q * e2.q + e3.q * e3.q + eta.q * eta.q - 1);
  const EquationsOfMotion eom = derive_equations(s);
  const LiteralLagrangeEquations lit = derive_equations_literally(s);
  const std::vector<Coordinate>& c = s.variables().coordinates();
  for (unsigned seed = 1; seed <= 4; ++seed) {
    // a state on the manifold: unit q and q . qd = 0
    GiNaC::exmap x = testing::random_state(s, seed);
    Eigen::Vector4d q, qd;
    for (int i = 0; i < 4; ++i) {
      q[i] = testing::to_double(x[c[i].q]);
      qd[i] = testing::to_double(x[c[i].qd]);
    }
    q.normalize();
    qd -= q * q.dot(qd);
    for (int i = 0; i < 4; ++i) {
      x[c[i].q] = q[i];
      x[c[i].qd] = qd[i];
    }
    EXPECT_TRUE(testing::matrices_agree_at(eom.mass_matrix, eom.subexpressions, lit.mass_matrix, x, 1e-10));
    const GiNaC::exmap all = eom.subexpressions.evaluate_all(x);
    Eigen::Vector4d difference;
    for (int i = 0; i < 4; ++i)
      difference[i] = testing::to_double(eom.forcing(i, 0).subs(all)) - testing::to_double(lit.forcing(i, 0).subs(x));
    const Eigen::Vector4d across = difference - q * q.dot(difference);
    EXPECT_LT(across.norm(), 1e-10 * (1 + difference.norm())) << "difference " << difference.transpose();
  }
}

TEST(Derivation, UniversalJointChainAgreesWithLiteralLagrange) {
  MechanicalSystem s;
  FrameId parent = s.inertial_frame();
  PointId joint = s.origin();
  s.set_gravity(Vector(s.inertial_frame(), 0, 0, -9.81));
  for (int i = 1; i <= 2; ++i) {
    const auto qa = s.add_coordinate("a" + std::to_string(i)), qb = s.add_coordinate("b" + std::to_string(i));
    const auto f1 = s.add_frame("f" + std::to_string(i), parent, Rotation::principal(1, qa.q));
    const auto f2 = s.add_frame("g" + std::to_string(i), f1, Rotation::principal(2, qb.q));
    const auto c = s.add_point("c" + std::to_string(i), joint, Vector(f2, 0, 0, -0.5));
    s.add_rigid_body("link" + std::to_string(i), 1.0 + i, c, f2, diag(0.1, 0.12, 0.02));
    joint = s.add_point("o" + std::to_string(i), joint, Vector(f2, 0, 0, -1.0));
    parent = f2;
  }
  expect_agrees_with_literal_lagrange(s);
}

TEST(Derivation, EquationsOnlyReferToEarlierIntermediates) {
  const MechanicalSystem s = loaded_system();
  const EquationsOfMotion eom = derive_equations(s);
  const auto& defs = eom.subexpressions.definitions();
  for (std::size_t i = 0; i < defs.size(); ++i)
    for (std::size_t j = i; j < defs.size(); ++j) ASSERT_FALSE(defs[i].value.has(defs[j].symbol)) << i << " uses " << j;
}

}  // namespace
}  // namespace eomgen
