#include "eomgen/derivation/numeric_evaluation.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "eomgen/base/error.hpp"
#include "support/expect_throw.hpp"
#include "support/test_models.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;

// bob of mass m on a rod of length l, theta from the downward vertical a1
Model simple_pendulum() {
  Model model;
  model.name = "pendulum";
  MechanicalSystem& s = model.system;
  const Coordinate theta = s.add_coordinate("theta");
  const ex m = s.add_parameter("m", 2.0, "kg"), l = s.add_parameter("l", 1.5, "m");
  const ex g = s.add_parameter("g", 9.81, "m/s^2");
  const FrameId b = s.add_frame("b", s.inertial_frame(), Rotation::principal(3, theta.q));
  s.add_particle("bob", m, s.add_point("p", s.origin(), Vector(b, l, 0, 0)));
  s.set_gravity(Vector(s.inertial_frame(), g, 0, 0));
  s.add_generalized_force(0, s.add_input("torque"));
  model.outputs.push_back(Output{"height", {-l * GiNaC::cos(theta.q)}, {"height"}, {}});
  return model;
}

Model double_pendulum() { return testing::double_pendulum_model(); }

Model cartesian_pendulum() { return testing::cartesian_pendulum_model(); }

// free rigid body with a scalar-last quaternion and its norm constraint; M is singular
// (qd along q does not change the attitude) but the KKT matrix is regular
Model quaternion_body() {
  Model model;
  model.name = "quaternion_body";
  MechanicalSystem& s = model.system;
  const Coordinate e1 = s.add_coordinate("e1"), e2 = s.add_coordinate("e2"), e3 = s.add_coordinate("e3");
  const Coordinate eta = s.add_coordinate("eta");
  const FrameId b = s.add_frame("b", s.inertial_frame(),
                                Rotation::quaternion(GiNaC::matrix(3, 1, GiNaC::lst{e1.q, e2.q, e3.q}), eta.q));
  GiNaC::matrix J(3, 3);
  J(0, 0) = 1.0;
  J(1, 1) = 2.0;
  J(2, 2) = 3.0;
  s.add_rigid_body("body", 2.0, s.add_point("c", s.origin(), Vector(b, 0.2, 0.1, 0.3)), b, J);
  s.set_gravity(Vector(s.inertial_frame(), 0, 0, -9.81));
  s.add_holonomic_constraint("unit_norm", e1.q * e1.q + e2.q * e2.q + e3.q * e3.q + eta.q * eta.q - 1);
  return model;
}

NumericEquations evaluate(const Model& model, const NamedValues& values) {
  return evaluate_equations(model, derive_equations(model), values);
}

TEST(NumericEvaluation, DoublePendulumMatchesTheHandClosedForm) {
  const double q1 = 0.3, q2 = -0.7, w1 = 0.4, w2 = -1.1, m1 = 1.5, m2 = 1.0, l1 = 1.0, l2 = 0.8, g = 9.81;
  const NumericEquations eq =
      evaluate(double_pendulum(), {{"q1", q1}, {"q2", q2}, {"q1_dot", w1}, {"q2_dot", w2}, {"m1", m1}, {"l2", l2}});
  const double c2 = std::cos(q2), s2 = std::sin(q2);
  Eigen::Matrix2d M;
  M << (m1 + m2) * l1 * l1 + m2 * l2 * l2 + 2 * m2 * l1 * l2 * c2, m2 * l2 * l2 + m2 * l1 * l2 * c2,
      m2 * l2 * l2 + m2 * l1 * l2 * c2, m2 * l2 * l2;
  const Eigen::Vector2d F(m2 * l1 * l2 * s2 * (2 * w1 * w2 + w2 * w2) - (m1 + m2) * g * l1 * std::sin(q1) -
                              m2 * g * l2 * std::sin(q1 + q2),
                          -m2 * l1 * l2 * s2 * w1 * w1 - m2 * g * l2 * std::sin(q1 + q2));
  EXPECT_LT((eq.mass_matrix - M).norm(), 1e-13) << eq.mass_matrix;
  EXPECT_LT((eq.forcing - F).norm(), 1e-13) << eq.forcing.transpose();
  EXPECT_NEAR(eq.kinetic_energy,
              0.5 * (m1 + m2) * l1 * l1 * w1 * w1 + 0.5 * m2 * l2 * l2 * (w1 + w2) * (w1 + w2) +
                  m2 * l1 * l2 * c2 * w1 * (w1 + w2),
              1e-13);
  EXPECT_NEAR(eq.potential_energy, -(m1 + m2) * g * l1 * std::cos(q1) - m2 * g * l2 * std::cos(q1 + q2), 1e-13);
  EXPECT_EQ(eq.constraint_jacobian.rows(), 0);
  EXPECT_EQ(eq.constraint_jacobian.cols(), 2);

  const AccelerationSolution sol = solve_accelerations(eq);
  EXPECT_LT((M * sol.qdd - F).norm(), 1e-12);
  EXPECT_EQ(sol.lambda.size(), 0);
}

TEST(NumericEvaluation, MissingValuesDefaultToZeroAndParameterDefaults) {
  const NumericEquations eq = evaluate(double_pendulum(), {});
  EXPECT_NEAR(eq.potential_energy, -(1.0 + 1.0) * 9.81 - 9.81, 1e-13);
  EXPECT_EQ(eq.kinetic_energy, 0.0);
  EXPECT_LT(eq.forcing.norm(), 1e-15);
}

TEST(NumericEvaluation, InputsOutputsAndTheSimplePendulum) {
  const double theta = 0.4, m = 2.0, l = 1.5, g = 9.81, torque = 0.7;
  const NumericEquations eq = evaluate(simple_pendulum(), {{"theta", theta}, {"torque", torque}, {"t", 3.0}});
  EXPECT_NEAR(eq.mass_matrix(0, 0), m * l * l, 1e-13);
  EXPECT_NEAR(eq.forcing(0), -m * g * l * std::sin(theta) + torque, 1e-13);
  ASSERT_EQ(eq.outputs.size(), 1u);
  EXPECT_EQ(eq.outputs[0].first, "height");
  EXPECT_NEAR(eq.outputs[0].second, -l * std::cos(theta), 1e-15);
  EXPECT_NEAR(solve_accelerations(eq).qdd(0), -g / l * std::sin(theta) + torque / (m * l * l), 1e-13);
}

TEST(NumericEvaluation, UnknownNameIsAnErrorListingTheAcceptedNames) {
  EXPECT_THROW_MESSAGE(
      evaluate(double_pendulum(), {{"q3", 1.0}}), Error,
      "evaluating at a state: unknown name 'q3'; accepted names: t, q1, q1_dot, q2, q2_dot, m1, m2, l1, l2, g");
  EXPECT_THROW_MESSAGE(evaluate(double_pendulum(), {{"q1_ddot", 1.0}}), Error,
                       "evaluating at a state: accelerations are solved for, not given: 'q1_ddot'; accepted names: t, "
                       "q1, q1_dot, q2, q2_dot, m1, m2, l1, l2, g");
}

TEST(NumericEvaluation, PoleIsAnErrorNamingTheEntry) {
  Model model;
  MechanicalSystem& s = model.system;
  const Coordinate x = s.add_coordinate("x");
  s.add_particle("bob", 1.0, s.add_point("p", s.origin(), Vector(s.inertial_frame(), x.q, 0, 0)));
  s.add_potential("inverse", 1 / x.q);
  EXPECT_THROW_MESSAGE(evaluate(model, {{"x", 0.0}}), Error,
                       "evaluating F[1] at this state: the result is not finite (a division by zero, or a root or "
                       "logarithm of a negative number)");
  EXPECT_NEAR(evaluate(model, {{"x", 2.0}}).forcing(0), 1.0 / 4.0, 1e-15);  // -dV/dx = 1/x^2
}

TEST(KktSolution, CartesianPendulumGivesTheRodTensionAndTheAnglePendulumAcceleration) {
  const double m = 2.0, l = 1.5, g = 9.81, theta = 0.6, omega = -0.9;
  // x along gravity (down), y across: x = l cos(theta), y = l sin(theta)
  const double x = l * std::cos(theta), y = l * std::sin(theta);
  const double xd = -l * std::sin(theta) * omega, yd = l * std::cos(theta) * omega;
  const NumericEquations eq = evaluate(cartesian_pendulum(), {{"x", x}, {"y", y}, {"x_dot", xd}, {"y_dot", yd}});
  EXPECT_NEAR(eq.holonomic_residuals(0), 0.0, 1e-14);
  EXPECT_NEAR(eq.constraint_jacobian(0, 0), 2 * x, 1e-15);
  EXPECT_NEAR(eq.constraint_acceleration_term(0), 2 * (xd * xd + yd * yd), 1e-14);
  const AccelerationSolution sol = solve_accelerations(eq);

  // the rod pulls the bob towards the pivot with N = m (g cos(theta) + l omega^2); the
  // constraint force Xi^T lambda = 2 lambda (x, y) = -N (x, y) / l
  const double tension = m * (g * std::cos(theta) + l * omega * omega);
  ASSERT_EQ(sol.lambda.size(), 1);
  EXPECT_NEAR(sol.lambda(0), -tension / (2 * l), 1e-12);

  // the same motion in the angle: theta_dd = -g/l sin(theta), from the unconstrained model
  const Model angle = simple_pendulum();
  const double theta_dd = solve_accelerations(evaluate(angle, {{"theta", theta}, {"theta_dot", omega}})).qdd(0);
  EXPECT_NEAR(theta_dd, -g / l * std::sin(theta), 1e-12);
  const double xdd = -l * std::cos(theta) * omega * omega - l * std::sin(theta) * theta_dd;
  const double ydd = -l * std::sin(theta) * omega * omega + l * std::cos(theta) * theta_dd;
  EXPECT_NEAR(sol.qdd(0), xdd, 1e-12);
  EXPECT_NEAR(sol.qdd(1), ydd, 1e-12);
}

TEST(KktSolution, QuaternionBodyWithSingularMassMatrixSolves) {
  // a unit quaternion and a rate tangent to the unit sphere
  Eigen::Vector4d q(0.3, -0.2, 0.5, 0.0), qd(0.4, 0.1, -0.3, 0.2);
  q(3) = std::sqrt(1 - q.head<3>().squaredNorm());
  qd -= q * q.dot(qd);
  NamedValues state;
  const char* names[] = {"e1", "e2", "e3", "eta"};
  for (int i = 0; i < 4; ++i) {
    state[names[i]] = q(i);
    state[std::string(names[i]) + "_dot"] = qd(i);
  }
  const NumericEquations eq = evaluate(quaternion_body(), state);
  // M q = 0: a rate along q leaves the attitude unchanged
  EXPECT_LT((eq.mass_matrix * q).norm(), 1e-12 * eq.mass_matrix.norm());
  NumericEquations unconstrained = eq;
  unconstrained.constraint_jacobian.resize(0, 4);
  unconstrained.constraint_acceleration_term.resize(0);
  EXPECT_THROW_MESSAGE(solve_accelerations(unconstrained), Error,
                       "solving M qdd = F: the mass matrix is not positive definite at this state (redundant "
                       "coordinates need a constraint)");

  const AccelerationSolution sol = solve_accelerations(eq);
  const Eigen::MatrixXd& Xi = eq.constraint_jacobian;
  EXPECT_LT((eq.mass_matrix * sol.qdd - eq.forcing - Xi.transpose() * sol.lambda).norm(), 1e-10);
  EXPECT_LT((Xi * sol.qdd + eq.constraint_acceleration_term).norm(), 1e-12);
  // second derivative of |q|^2 = 1: q . qdd = -|qd|^2
  EXPECT_NEAR(q.dot(sol.qdd), -qd.squaredNorm(), 1e-12);
  // the norm constraint transmits no force in Kane's form (equations_of_motion.hpp)
  EXPECT_NEAR(sol.lambda(0), 0.0, 1e-10);
}

TEST(KktSolution, SingularKktMatrixIsAnError) {
  NumericEquations eq;
  eq.mass_matrix = Eigen::Matrix2d::Identity();
  eq.forcing = Eigen::Vector2d(1.0, 2.0);
  eq.constraint_jacobian.resize(2, 2);
  eq.constraint_jacobian << 0.0, 0.0, 0.0, 0.0;  // no row has a direction: none to keep
  eq.constraint_acceleration_term = Eigen::Vector2d::Zero();
  EXPECT_THROW_MESSAGE(solve_accelerations(eq), Error,
                       "solving the KKT system [[M, -Xi^T], [-Xi, 0]]: the matrix is singular at this state (rank 2 of "
                       "4): the constraints are dependent, or M is singular on the directions they allow");
}

}  // namespace
}  // namespace eomgen
