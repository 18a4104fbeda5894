// Linearization and stability (linearization.hpp) against closed forms: the pendulum hanging
// and inverted, the cart-pole upright, the notes' Example A.20, the sleeping top's classical
// threshold, and finite differences of the nonlinear right-hand side away from equilibrium.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <string>

#include "eomgen/base/error.hpp"
#include "eomgen/derivation/linearization.hpp"
#include "eomgen/derivation/model_equations.hpp"
#include "eomgen/language/model_file.hpp"
#include "eomgen/derivation/numeric_evaluation.hpp"
#include "support/expect_throw.hpp"
#include "support/numeric_checks.hpp"
#include "support/source_dir.hpp"

namespace eomgen {
namespace {

using testing::matrices_near;

Model shipped(const std::string& name) {
  return load_model(eomgen::testing::shipped_model_path(name));
}

LinearModel linearize_at(const Model& model, const NamedValues& point, bool drop_cyclic = false) {
  const ModelEquations eom = derive_equations(model);
  LinearizeOptions options;
  options.drop_cyclic = drop_cyclic;
  return linearize(model, eom, linearize_symbolic(model, eom), point, options);
}

TEST(Linearization, HangingPendulumOscillatesAtSqrtGOverLAndTheIndirectMethodCannotConclude) {
  const Model model = shipped("simple_pendulum");  // l = 0.5, g = 9.81
  const LinearModel lin = linearize_at(model, {});
  Eigen::MatrixXd A(2, 2);
  A << 0, 1, -9.81 / 0.5, 0;
  EXPECT_TRUE(matrices_near(lin.A, A, 1e-12));
  const StabilityReport report = assess_stability(lin.A);
  const double omega = std::sqrt(9.81 / 0.5);
  EXPECT_NEAR(report.eigenvalues(0).real(), 0.0, 1e-12);
  EXPECT_NEAR(report.eigenvalues(0).imag(), omega, 1e-12);
  EXPECT_NEAR(report.eigenvalues(1).imag(), -omega, 1e-12);
  EXPECT_EQ(report.linear, LinearStability::stable);
  EXPECT_EQ(report.nonlinear, LyapunovVerdict::no_conclusion);
}

TEST(Linearization, InvertedPendulumIsUnstableWithRateSqrtGOverL) {
  const LinearModel lin = linearize_at(shipped("simple_pendulum"), {{"theta", M_PI}});
  const StabilityReport report = assess_stability(lin.A);
  EXPECT_NEAR(report.eigenvalues(0).real(), std::sqrt(9.81 / 0.5), 1e-9);
  EXPECT_NEAR(report.eigenvalues(0).imag(), 0.0, 1e-12);
  EXPECT_EQ(report.linear, LinearStability::unstable);
  EXPECT_EQ(report.nonlinear, LyapunovVerdict::unstable);
}

// T = (mc + mp) xd^2 / 2 - mp (l/2) cos(theta) xd thetad + (mp l^2/4 + Jc) thetad^2 / 2 and
// V = mp g (l/2) cos(theta) (theta = 0 upright) give at the top M = [[mc + mp, -mp l/2],
// [-mp l/2, mp l^2/4 + Jc]], K = diag(0, -mp g l/2), D = 0 and B_u = [1; 0]
TEST(Linearization, CartPoleUprightEqualsTheClosedForm) {
  const double mc = 1.0, mp = 0.1, l = 1.0, rp = 0.01, g = 9.81;
  const double Jc = mp * (l * l / 12 + rp * rp / 4);
  Eigen::Matrix2d M, K;
  M << mc + mp, -mp * l / 2, -mp * l / 2, mp * l * l / 4 + Jc;
  K << 0, 0, 0, -mp * g * l / 2;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(4, 4), B = Eigen::MatrixXd::Zero(4, 1);
  A.topRightCorner(2, 2).setIdentity();
  A.bottomLeftCorner(2, 2) = -M.inverse() * K;
  B.bottomRows(2) = M.inverse() * Eigen::Vector2d(1, 0);

  const LinearModel lin = linearize_at(shipped("cart_pole"), {});
  EXPECT_TRUE(matrices_near(lin.M, M, 1e-14));
  EXPECT_TRUE(matrices_near(lin.K, K, 1e-14));
  EXPECT_TRUE(matrices_near(lin.D, Eigen::MatrixXd::Zero(2, 2), 0));
  EXPECT_TRUE(matrices_near(lin.A, A, 1e-12));
  EXPECT_TRUE(matrices_near(lin.B, B, 1e-12));
  EXPECT_EQ(lin.state_names, (std::vector<std::string>{"x", "theta", "x_dot", "theta_dot"}));

  // x appears nowhere in M and F: dropped on request, its row and column go
  const LinearModel reduced = linearize_at(shipped("cart_pole"), {}, true);
  EXPECT_EQ(reduced.dropped, (std::vector<std::string>{"x"}));
  Eigen::MatrixXd A3(3, 3);
  A3 << A.block(1, 1, 1, 3), A.block(2, 1, 2, 3);
  EXPECT_TRUE(matrices_near(reduced.A, A3, 1e-12));
}

// Example A.20: m q'' + d q' + (k1 + k2 q^2) q = 0 about its only equilibrium 0 gives
// A = [[0, 1], [-k1/m, -d/m]]; away from it the cubic spring stiffens to k1 + 3 k2 q^2
TEST(Linearization, SpringMassDamperReproducesExampleA20) {
  const Model model = shipped("spring_mass_damper");  // m = 1, d = 0.4, k1 = 10, k2 = 50
  const LinearModel lin = linearize_at(model, {});
  Eigen::MatrixXd A(2, 2);
  A << 0, 1, -10.0, -0.4;
  EXPECT_TRUE(matrices_near(lin.A, A, 1e-13));
  const StabilityReport report = assess_stability(lin.A);
  EXPECT_EQ(report.linear, LinearStability::asymptotically_stable);
  EXPECT_EQ(report.nonlinear, LyapunovVerdict::asymptotically_stable);
  EXPECT_NEAR(report.eigenvalues(0).real(), -0.2, 1e-12);

  const LinearModel displaced = linearize_at(model, {{"q", 0.3}, {"k2", 50.0}});
  EXPECT_NEAR(displaced.qdd0(0), -(10 + 50 * 0.09) * 0.3, 1e-12);
  EXPECT_NEAR(displaced.A(1, 0), -(10 + 3 * 50 * 0.09), 1e-12);
}

// A symmetric top on a pivot described by 1-2-3 angles, regular where it stands upright
const char* const sleeping_top = R"(model sleeping_top "symmetric top, Cardan angles"
parameter m = 0.5 [kg]
parameter l = 0.05 [m]
parameter J1 = 2.2e-4 [kg m^2]
parameter J3 = 4.0e-4 [kg m^2]
parameter g = 9.81 [m/s^2]
coordinate alpha, beta, gamma
frame f1 = rotate(a, 1, alpha)
frame f2 = rotate(f1, 2, beta)
frame b = rotate(f2, 3, gamma)
point centre = w + l*b.3
body top(mass = m, centre = centre, frame = b, inertia = diag(J1, J1, J3))
gravity = -g*a.3
)";

// Spinning upright at rate w, small tilts obey I1^2 s^4 + (I3^2 w^2 - 2 I1 m g l) s^2 +
// (m g l)^2 = 0 with I1 = J1 + m l^2 about the pivot: s = +-i (I3 w +- sqrt(I3^2 w^2 -
// 4 I1 m g l)) / (2 I1), purely imaginary exactly when I3^2 w^2 > 4 I1 m g l
TEST(Linearization, SleepingTopIsStableExactlyAboveTheClassicalThreshold) {
  const Model model = parse_model(sleeping_top, "sleeping_top.eom");
  const double m = 0.5, l = 0.05, J1 = 2.2e-4, J3 = 4.0e-4, g = 9.81;
  const double I1 = J1 + m * l * l, mgl = m * g * l;
  const double w_critical = std::sqrt(4 * I1 * mgl) / J3;
  const ModelEquations eom = derive_equations(model);
  const SymbolicLinearization symbolic = linearize_symbolic(model, eom);
  EXPECT_EQ(symbolic.cyclic, (std::vector<bool>{false, false, true}));
  LinearizeOptions drop;
  drop.drop_cyclic = true;

  for (const double factor : {1.02, 1.5, 0.98, 0.5}) {
    SCOPED_TRACE(factor);
    const double w = factor * w_critical;
    const LinearModel lin = linearize(model, eom, symbolic, {{"gamma_dot", w}}, drop);
    EXPECT_EQ(lin.dropped, (std::vector<std::string>{"gamma"}));
    EXPECT_LT(lin.qdd0.norm(), 1e-12);  // a steady motion
    const StabilityReport report = assess_stability(lin.A);
    const std::complex<double> root = std::sqrt(std::complex<double>(J3 * J3 * w * w - 4 * I1 * mgl));
    // the four tilt eigenvalues (the fifth, 0, is the spin rate's)
    for (const std::complex<double> s : {std::complex<double>(0, 1) * (J3 * w + root) / (2 * I1),
                                         std::complex<double>(0, 1) * (J3 * w - root) / (2 * I1)}) {
      for (const std::complex<double> expected : {s, -s, std::conj(s), -std::conj(s)}) {
        double nearest = 1e300;
        for (Eigen::Index i = 0; i < report.eigenvalues.size(); ++i)
          nearest = std::min(nearest, std::abs(report.eigenvalues(i) - expected));
        EXPECT_LT(nearest, 1e-8 * std::abs(s)) << expected;
      }
    }
    if (factor > 1) {
      EXPECT_EQ(report.linear, LinearStability::stable);
      EXPECT_EQ(report.nonlinear, LyapunovVerdict::no_conclusion);
    } else {
      EXPECT_EQ(report.linear, LinearStability::unstable);
      EXPECT_EQ(report.nonlinear, LyapunovVerdict::unstable);
    }
  }
}

// away from equilibrium (qdd0 != 0) A must still be the Jacobian of [qd; M^-1 F]: compared
// with central differences of the nonlinear right-hand side of the double pendulum
TEST(Linearization, EqualsTheJacobianOfTheNonlinearRightHandSideAwayFromEquilibrium) {
  const Model model = shipped("double_pendulum");
  const NamedValues point{{"theta1", 0.7}, {"theta2", -1.1}, {"theta1_dot", 1.3}, {"theta2_dot", -0.4}};
  const ModelEquations eom = derive_equations(model);
  const LinearModel lin = linearize(model, eom, linearize_symbolic(model, eom), point);
  EXPECT_GT(lin.qdd0.norm(), 1.0);
  const std::vector<std::string> names{"theta1", "theta2", "theta1_dot", "theta2_dot"};
  const auto rhs = [&](const NamedValues& at) {
    const NumericEquations e = evaluate_equations(model, eom, at);
    Eigen::VectorXd f(4);
    f << at.at("theta1_dot"), at.at("theta2_dot"), e.mass_matrix.llt().solve(e.forcing);
    return f;
  };
  Eigen::MatrixXd J(4, 4);
  const double h = 1e-6;
  for (int k = 0; k < 4; ++k) {
    NamedValues plus = point, minus = point;
    plus[names[k]] += h;
    minus[names[k]] -= h;
    J.col(k) = (rhs(plus) - rhs(minus)) / (2 * h);
  }
  EXPECT_TRUE(matrices_near(lin.A, J, 1e-7));
}

// x = l sin(theta) with y dependent: about the bottom, x'' = -(g/l) x exactly as the angle
// pendulum, with no multiplier and no dependent state left
TEST(Linearization, CartesianPendulumReducesToTheAnglePendulum) {
  const Model model = shipped("cartesian_pendulum");  // l = 0.5
  const LinearModel lin = linearize_at(model, {{"y", -0.5}});
  EXPECT_EQ(lin.state_names, (std::vector<std::string>{"x", "x_dot"}));
  EXPECT_EQ(lin.dependent, (std::vector<std::string>{"y", "y_dot"}));
  Eigen::MatrixXd A(2, 2);
  A << 0, 1, -9.81 / 0.5, 0;
  EXPECT_TRUE(matrices_near(lin.A, A, 1e-12));
  const StabilityReport report = assess_stability(lin.A);
  EXPECT_NEAR(report.eigenvalues(0).imag(), std::sqrt(9.81 / 0.5), 1e-12);
  EXPECT_THROW_MESSAGE(linearize_at(model, {}), Error,
                       "linearizing cartesian_pendulum: no state near the point satisfies the constraint "
                       "'rod_length': the nearest the search came, with every value free to move, leaves phi = -0.25 "
                       "(given: none); check the model's dimensions, or give values near an assembly");  // (0, 0):
                                                                                         // no gradient
}

// Rolling upright and straight at speed v = r w, a thin disk's lean obeys (Euler's equations
// about the centre, the contact force from Newton's law for the centre)
//   (B + m r^2) theta_ddot = m g r theta - (A + m r^2) w psi_dot,   B psi_ddot = A w theta_dot,
// A = m r^2 / 2, B = m r^2 / 4, the spin constant: besides zeros, s^2 = (4/5)(g/r - 3 w^2):
// unstable below v_c = sqrt(g r / 3), oscillating above it
TEST(Linearization, RollingCoinUprightIsStableExactlyAboveTheCriticalSpeed) {
  const Model model = shipped("rolling_coin");  // r = 12.9 mm, g = 9.81
  const double r = 12.9e-3, g = 9.81;
  const double v_critical = std::sqrt(g * r / 3);
  const ModelEquations eom = derive_equations(model);
  const SymbolicLinearization symbolic = linearize_symbolic(model, eom);
  LinearizeOptions drop;
  drop.drop_cyclic = true;
  for (const double factor : {0.9, 1.1, 2.0}) {
    SCOPED_TRACE(factor);
    const double w = factor * v_critical / r;
    // rolling along -a.2 (psi = 0): y_dot = -r w
    const LinearModel lin = linearize(model, eom, symbolic, {{"phi_dot", w}, {"y_dot", -r * w}}, drop);
    // the spin's perturbation changes nothing to first order about upright rolling: dropped too
    EXPECT_EQ(lin.state_names, (std::vector<std::string>{"theta", "psi_dot", "theta_dot"}));
    EXPECT_EQ(lin.dropped, (std::vector<std::string>{"x", "y", "psi", "phi", "phi_dot"}));
    EXPECT_LT(lin.qdd0.norm(), 1e-9);
    const StabilityReport report = assess_stability(lin.A);
    const std::complex<double> s = std::sqrt(std::complex<double>(0.8 * (g / r - 3 * w * w)));
    for (const std::complex<double> expected : {s, -s}) {
      double nearest = 1e300;
      for (Eigen::Index i = 0; i < report.eigenvalues.size(); ++i)
        nearest = std::min(nearest, std::abs(report.eigenvalues(i) - expected));
      EXPECT_LT(nearest, 1e-6 * std::abs(s)) << expected;
    }
    EXPECT_EQ(report.nonlinear, factor < 1 ? LyapunovVerdict::unstable : LyapunovVerdict::no_conclusion);
  }
}

TEST(Linearization, SingularMassMatrixAtThePointIsAnError) {
  // the 3-1-3 angles of the shipped top are singular upright
  const Model model = shipped("heavy_top");
  const ModelEquations eom = derive_equations(model);
  EXPECT_THROW_MESSAGE(linearize(model, eom, linearize_symbolic(model, eom), {{"phi_dot", 50.0}}), Error,
                       "linearizing heavy_top: the mass matrix is singular at this state but not near it: a "
                       "coordinate singularity (as the gimbal lock of Euler angles) in psi, phi, which describe fewer "
                       "independent motions here than elsewhere; evaluate away from it, or describe the rotation "
                       "without one (a quaternion)");
}

TEST(Equilibrium, NewtonFindsTheEquilibriaOfTheShippedModelsFromNearbyGuesses) {
  const auto solve = [](const std::string& name, const NamedValues& guess) {
    const Model model = shipped(name);
    const ModelEquations eom = derive_equations(model);
    return find_equilibrium(model, eom, linearize_symbolic(model, eom), guess);
  };
  // Example A.20: the only real equilibrium of the hardening spring is 0
  const Equilibrium spring = solve("spring_mass_damper", {{"q", 0.7}});
  EXPECT_NEAR(spring.point.at("q"), 0.0, 1e-12);
  EXPECT_GT(spring.iterations, 2);
  // the pendulum from near the top goes to the top, not the bottom
  EXPECT_NEAR(solve("simple_pendulum", {{"theta", 2.9}}).point.at("theta"), M_PI, 1e-12);
  // the cart may stand anywhere: the minimum-norm step leaves it where the guess put it
  const Equilibrium cart = solve("cart_pole", {{"x", 2.0}, {"theta", 0.3}});
  EXPECT_NEAR(cart.point.at("theta"), 0.0, 1e-12);
  EXPECT_NEAR(cart.point.at("x"), 2.0, 1e-12);
  // the Cartesian pendulum hangs at (0, -l), held by its rod: tension m g = -2 l lambda
  const Equilibrium hanging = solve("cartesian_pendulum", {{"x", 0.1}, {"y", -0.4}});
  EXPECT_NEAR(hanging.point.at("x"), 0.0, 1e-12);
  EXPECT_NEAR(hanging.point.at("y"), -0.5, 1e-12);
  EXPECT_NEAR(hanging.lambda(0), -1.0 * 9.81 / (2 * 0.5), 1e-10);
  EXPECT_THROW_MESSAGE(solve("knife_edge", {{"x_dot", 1.0}, {"tau", 1.0}}), Error,
                       "finding an equilibrium of knife_edge: Newton's method stopped after 0 iterations with residual "
                       "1 (the forces do not balance: F + Xi^T lambda = 1 on theta); try another guess");  // a steady
                                                                                                          // torque
}

TEST(Stability, RepeatedEigenvalueWithoutEnoughEigenvectorsIsUnstableForTheLinearSystem) {
  Eigen::MatrixXd double_integrator(2, 2);
  double_integrator << 0, 1, 0, 0;  // a Jordan block at 0: x = x0 + v0 t grows
  EXPECT_EQ(assess_stability(double_integrator).linear, LinearStability::unstable);
  EXPECT_EQ(assess_stability(double_integrator).nonlinear, LyapunovVerdict::no_conclusion);
  const Eigen::MatrixXd zero = Eigen::MatrixXd::Zero(2, 2);  // two eigenvectors: stable
  EXPECT_EQ(assess_stability(zero).linear, LinearStability::stable);
}

}  // namespace
}  // namespace eomgen
