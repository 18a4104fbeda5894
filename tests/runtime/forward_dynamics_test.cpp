// Tests for the forward-dynamics solves (dynamics_kkt.hpp, dynamics_null_space.hpp,
// dynamics_unconstrained.hpp) and the constraint stabilization (stabilization.hpp), on
// hand-written models whose answers are known in closed form.

#include "runtime/no_malloc.hpp"  // first: it configures Eigen

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "eomrt/eomrt.hpp"
#include "runtime/scalar_types.hpp"
#include "support/expect_throw.hpp"
#include "runtime/handwritten_models.hpp"

namespace eomrt {
namespace {

using testing::ScalarName;
using testing::Scalars;

using testing::CartesianPendulum;
using testing::Oscillator;
using testing::RedundantMass;

template <class Model>
SpeedPartition<Model> independent_speeds(const std::array<int, Model::nq - Model::nc>& indices) {
  return SpeedPartition<Model>(indices);
}

const SpeedPartition<CartesianPendulum>& x_independent_partition() {
  static const SpeedPartition<CartesianPendulum> partition = independent_speeds<CartesianPendulum>({{0}});
  return partition;
}

template <class Scalar>
using PendulumTypes = ModelTypes<CartesianPendulum, Scalar>;

/// A state of the Cartesian pendulum on its constraint, at angle theta from the downward
/// vertical with rate theta_dot.
template <class Scalar>
void pendulum_state(Scalar theta, Scalar theta_dot, const typename PendulumTypes<Scalar>::Parameters& p,
                    typename PendulumTypes<Scalar>::Coordinates& q,
                    typename PendulumTypes<Scalar>::Coordinates& qd) {
  using std::cos;
  using std::sin;
  q << p.l * sin(theta), -p.l * cos(theta);
  qd << p.l * cos(theta) * theta_dot, p.l * sin(theta) * theta_dot;
}

template <class Scalar>
class ForwardDynamicsOverScalars : public ::testing::Test {};
TYPED_TEST_SUITE(ForwardDynamicsOverScalars, Scalars, ScalarName);

// theta'' = -g/l sin(theta); the rod tension m (g cos(theta) + l theta'^2) pulls the bob to
// the pivot, and Xi^T lambda = 2 lambda (x, y) is that force, so lambda = -tension / (2 l)
TYPED_TEST(ForwardDynamicsOverScalars, KktAndNullSpaceGiveThePendulumAccelerationAndRodTension) {
  using Scalar = TypeParam;
  using std::cos;
  using std::sin;
  const typename PendulumTypes<Scalar>::Parameters p;
  const typename PendulumTypes<Scalar>::Inputs u;
  const Scalar theta = Scalar(0.7), theta_dot = Scalar(-1.3);
  typename PendulumTypes<Scalar>::Coordinates q, qd;
  pendulum_state(theta, theta_dot, p, q, qd);
  const Scalar theta_ddot = -p.g / p.l * sin(theta);
  const Scalar xdd = p.l * (cos(theta) * theta_ddot - sin(theta) * theta_dot * theta_dot);
  const Scalar ydd = p.l * (sin(theta) * theta_ddot + cos(theta) * theta_dot * theta_dot);
  const Scalar tension = p.m * (p.g * cos(theta) + p.l * theta_dot * theta_dot);
  const Scalar tol = 64 * std::numeric_limits<Scalar>::epsilon() * 100;

  DynamicsWorkspace<CartesianPendulum, Scalar> ws;
  ASSERT_EQ(forward_dynamics_kkt<CartesianPendulum>(p, ws, Scalar(0), q, qd, u), DynamicsStatus::ok);
  EXPECT_NEAR(ws.qdd(0), xdd, tol);
  EXPECT_NEAR(ws.qdd(1), ydd, tol);
  EXPECT_NEAR(ws.lambda(0), -tension / (2 * p.l), tol);

  ASSERT_EQ(forward_dynamics_null_space<CartesianPendulum>(p, ws, Scalar(0), q, qd, u),
            DynamicsStatus::ok);
  EXPECT_NEAR(ws.qdd(0), xdd, tol);
  EXPECT_NEAR(ws.qdd(1), ydd, tol);
  EXPECT_NEAR(ws.lambda(0), -tension / (2 * p.l), tol);
  // the basis spans the null space of Xi with orthonormal columns
  EXPECT_NEAR((ws.Xi * ws.solvers.upsilon).norm(), Scalar(0), tol);
  EXPECT_NEAR(ws.solvers.upsilon.norm(), Scalar(1), tol);

  const SpeedPartition<CartesianPendulum> x_independent = independent_speeds<CartesianPendulum>({{0}});
  ASSERT_EQ(forward_dynamics_null_space<CartesianPendulum>(p, ws, Scalar(0), q, qd, u, {}, &x_independent),
            DynamicsStatus::ok);
  EXPECT_NEAR(ws.qdd(0), xdd, tol);
  EXPECT_NEAR(ws.qdd(1), ydd, tol);
  EXPECT_NEAR(ws.lambda(0), -tension / (2 * p.l), tol);
  // Upsilon = [1; -Xi_y^{-1} Xi_x] = [1; -x/y]
  EXPECT_EQ(ws.solvers.upsilon(0, 0), Scalar(1));
  EXPECT_NEAR(ws.solvers.upsilon(1, 0), -q(0) / q(1), tol);
}

TYPED_TEST(ForwardDynamicsOverScalars, SingularMassMatrixIsSolvedThroughTheConstraints) {
  using Scalar = TypeParam;
  using Model = RedundantMass<true>;
  const typename Model::template Parameters<Scalar> p;
  const typename ModelTypes<Model, Scalar>::Inputs u;
  typename ModelTypes<Model, Scalar>::Coordinates q, qd;
  q << Scalar(0.25), Scalar(0.25);
  qd << Scalar(-0.5), Scalar(-0.5);
  // m s'' = -k s with s = x1 + x2 split evenly; the constraint transmits no force
  const Scalar expected = -p.k * (q(0) + q(1)) / (2 * p.m);
  const Scalar tol = 1000 * std::numeric_limits<Scalar>::epsilon();
  DynamicsWorkspace<Model, Scalar> ws;
  ASSERT_EQ(forward_dynamics_kkt<Model>(p, ws, Scalar(0), q, qd, u), DynamicsStatus::ok);
  EXPECT_NEAR(ws.qdd(0), expected, tol);
  EXPECT_NEAR(ws.qdd(1), expected, tol);
  EXPECT_NEAR(ws.lambda(0), Scalar(0), tol);
  ASSERT_EQ(forward_dynamics_null_space<Model>(p, ws, Scalar(0), q, qd, u), DynamicsStatus::ok);
  EXPECT_NEAR(ws.qdd(0), expected, tol);
  EXPECT_NEAR(ws.qdd(1), expected, tol);
  EXPECT_NEAR(ws.lambda(0), Scalar(0), tol);
}

TEST(ForwardDynamics, UnconstrainedSingularMassMatrixIsReportedNotSolved) {
  using Model = RedundantMass<false>;
  const Model::Parameters<double> p;
  const ModelTypes<Model, double>::Inputs u;
  ModelTypes<Model, double>::Coordinates q(0.1, 0.2), qd(0.0, 0.0);
  DynamicsWorkspace<Model, double> ws;
  EXPECT_EQ(forward_dynamics_unconstrained<Model>(p, ws, 0.0, q, qd, u),
            DynamicsStatus::singular_mass_matrix);
  EXPECT_EQ(forward_dynamics_kkt<Model>(p, ws, 0.0, q, qd, u), DynamicsStatus::singular_mass_matrix);
  EXPECT_EQ(forward_dynamics_null_space<Model>(p, ws, 0.0, q, qd, u),
            DynamicsStatus::singular_mass_matrix);
}

TEST(ForwardDynamics, UnconstrainedOscillatorFollowsHookesLawWithItsInput) {
  const Oscillator::Parameters<double> p;
  ModelTypes<Oscillator, double>::Inputs u;
  u << 3.0;
  ModelTypes<Oscillator, double>::Coordinates q, qd;
  q << 0.5;
  qd << -2.0;
  DynamicsWorkspace<Oscillator, double> ws;
  ASSERT_EQ(forward_dynamics_unconstrained<Oscillator>(p, ws, 0.0, q, qd, u), DynamicsStatus::ok);
  EXPECT_DOUBLE_EQ(ws.qdd(0), (-8.0 * 0.5 + 3.0) / 2.0);
}

static_assert(has_forward_dynamics_v<testing::OscillatorWithForwardDynamics> && !has_forward_dynamics_v<Oscillator>);
static_assert(uses_forward_dynamics_v<testing::OscillatorWithForwardDynamics> && !uses_forward_dynamics_v<Oscillator>);
static_assert(has_forward_dynamics_v<testing::OscillatorPreferringMassMatrix> &&
              !uses_forward_dynamics_v<testing::OscillatorPreferringMassMatrix>);

// an oscillator (m = 2, k = 8) at q = 0.5, qd = -2 under u = 3, solved with ws.M marked -7
// beforehand, so a test sees whether the solve evaluated M
template <class Model>
DynamicsStatus solve_marked_oscillator(const typename Model::template Parameters<double>& p,
                                       DynamicsWorkspace<Model, double>& ws) {
  typename ModelTypes<Model, double>::Inputs u;
  u << 3.0;
  typename ModelTypes<Model, double>::Coordinates q, qd;
  q << 0.5;
  qd << -2.0;
  ws.M(0, 0) = -7.0;
  return forward_dynamics_unconstrained<Model>(p, ws, 0.0, q, qd, u);
}

// a model that has forward_dynamics() but prefers M and F is solved through M: ws.M is evaluated
TEST(ForwardDynamics, ModelPreferringTheMassMatrixIsSolvedThroughIt) {
  using Model = testing::OscillatorPreferringMassMatrix;
  DynamicsWorkspace<Model, double> ws;
  ASSERT_EQ(solve_marked_oscillator<Model>({}, ws), DynamicsStatus::ok);
  EXPECT_DOUBLE_EQ(ws.qdd(0), (-8.0 * 0.5 + 3.0) / 2.0);
  EXPECT_EQ(ws.M(0, 0), 2.0);  // m
}

// the model's forward_dynamics() replaces M and F and the Cholesky solve: ws.M is not touched
TEST(ForwardDynamics, UnconstrainedModelWithItsOwnForwardDynamicsUsesItAndReportsItsFailure) {
  using Model = testing::OscillatorWithForwardDynamics;
  Model::Parameters<double> p;
  DynamicsWorkspace<Model, double> ws;
  ASSERT_EQ(solve_marked_oscillator<Model>(p, ws), DynamicsStatus::ok);
  EXPECT_DOUBLE_EQ(ws.qdd(0), (-8.0 * 0.5 + 3.0) / 2.0);
  EXPECT_EQ(ws.M(0, 0), -7.0);
  p.m = -2.0;
  EXPECT_EQ(solve_marked_oscillator<Model>(p, ws), DynamicsStatus::singular_mass_matrix);
}

TEST(ForwardDynamics, PendulumAtThePivotHasDependentConstraintsAndEveryMethodSaysSo) {
  const CartesianPendulum::Parameters<double> p;
  const ModelTypes<CartesianPendulum, double>::Inputs u;
  ModelTypes<CartesianPendulum, double>::Coordinates q(0.0, 0.0), qd(0.0, 0.0);
  DynamicsWorkspace<CartesianPendulum, double> ws;
  EXPECT_EQ(forward_dynamics_kkt<CartesianPendulum>(p, ws, 0.0, q, qd, u),
            DynamicsStatus::singular_kkt_matrix);
  EXPECT_EQ(forward_dynamics_null_space<CartesianPendulum>(p, ws, 0.0, q, qd, u),
            DynamicsStatus::singular_constraint_jacobian);
  EXPECT_EQ(forward_dynamics_null_space<CartesianPendulum>(p, ws, 0.0, q, qd, u, {},
                                                         &x_independent_partition()),
            DynamicsStatus::singular_constraint_jacobian);
}

// y independent leaves x dependent, whose coefficient 2x vanishes with the bob below the pivot:
// the declared basis degenerates there, and the QR basis gives the same (basis-free) answer
TEST(ForwardDynamics, DegenerateDeclaredBasisFallsBackToQr) {
  const CartesianPendulum::Parameters<double> p;
  const ModelTypes<CartesianPendulum, double>::Inputs u;
  const SpeedPartition<CartesianPendulum> y_independent = independent_speeds<CartesianPendulum>({{1}});
  DynamicsWorkspace<CartesianPendulum, double> ws;
  for (const double x : {0.0, 1e-5, 0.3}) {
    SCOPED_TRACE(x);
    ModelTypes<CartesianPendulum, double>::Coordinates q(x, -std::sqrt(0.64 - x * x)), qd(0.7, 0.0);
    qd(1) = -q(0) * qd(0) / q(1);  // tangent
    ASSERT_EQ(forward_dynamics_kkt<CartesianPendulum>(p, ws, 0.0, q, qd, u), DynamicsStatus::ok);
    const auto qdd = ws.qdd;
    const auto lambda = ws.lambda;
    ASSERT_EQ(forward_dynamics_null_space<CartesianPendulum>(p, ws, 0.0, q, qd, u, {}, &y_independent),
              DynamicsStatus::ok);
    EXPECT_EQ(ws.declared_basis_used, x == 0.3);
    EXPECT_NEAR((ws.qdd - qdd).norm(), 0.0, 1e-12);
    EXPECT_NEAR(ws.lambda(0), lambda(0), 1e-12);
  }
}

TEST(ForwardDynamics, NonFiniteStateIsReported) {
  const CartesianPendulum::Parameters<double> p;
  const ModelTypes<CartesianPendulum, double>::Inputs u;
  ModelTypes<CartesianPendulum, double>::Coordinates q(std::nan(""), -0.8), qd(0.0, 0.0);
  DynamicsWorkspace<CartesianPendulum, double> ws;
  EXPECT_EQ(forward_dynamics_kkt<CartesianPendulum>(p, ws, 0.0, q, qd, u), DynamicsStatus::non_finite);
}

TEST(SpeedPartition, RejectsRepeatedAndOutOfRangeIndices) {
  using Model = RedundantMass<false>;  // nq = 2, nc = 0: two independent speeds
  EXPECT_THROW_MESSAGE(independent_speeds<Model>({{0, 0}}), std::invalid_argument,
                       "SpeedPartition: independent speeds expected distinct indices in [0, 2), got 0 twice");
  EXPECT_THROW_MESSAGE(independent_speeds<Model>({{0, 2}}), std::invalid_argument,
                       "SpeedPartition: independent speeds expected distinct indices in [0, 2), got 2");
  EXPECT_THROW_MESSAGE(independent_speeds<Model>({{-1, 1}}), std::invalid_argument,
                       "SpeedPartition: independent speeds expected distinct indices in [0, 2), got -1");
  const SpeedPartition<CartesianPendulum> ok = independent_speeds<CartesianPendulum>({{1}});
  EXPECT_EQ(ok.dependent[0], 0);
}

// With Baumgarte terms the solve enforces Xi qdd + b + 2 alpha (Xi qd + Xi_t) + beta^2 phi = 0
TEST(Baumgarte, AccelerationsSatisfyTheStabilizedConstraint) {
  const CartesianPendulum::Parameters<double> p;
  const ModelTypes<CartesianPendulum, double>::Inputs u;
  ModelTypes<CartesianPendulum, double>::Coordinates q(0.3, -0.75), qd(0.4, 0.2);  // off the manifold
  const Baumgarte<double> stab{5.0, 7.0};
  DynamicsWorkspace<CartesianPendulum, double> ws;
  for (bool null_space : {false, true}) {
    const DynamicsStatus status =
        null_space ? forward_dynamics_null_space<CartesianPendulum>(p, ws, 0.0, q, qd, u, stab)
                   : forward_dynamics_kkt<CartesianPendulum>(p, ws, 0.0, q, qd, u, stab);
    ASSERT_EQ(status, DynamicsStatus::ok);
    const double phi = q.squaredNorm() - p.l * p.l;
    const double rate = 2 * q.dot(qd);
    const double accel = 2 * q.dot(ws.qdd) + 2 * qd.squaredNorm();
    EXPECT_NEAR(accel + 2 * stab.alpha * rate + stab.beta * stab.beta * phi, 0.0, 1e-12)
        << (null_space ? "null space" : "kkt");
  }
}

TYPED_TEST(ForwardDynamicsOverScalars, ProjectionLandsOnTheNearestPointOfTheCircleWithTangentRates) {
  using Scalar = TypeParam;
  const typename PendulumTypes<Scalar>::Parameters p;
  typename PendulumTypes<Scalar>::Coordinates q, qd;
  q << Scalar(0.3), Scalar(-0.9);
  qd << Scalar(0.5), Scalar(0.7);
  const typename PendulumTypes<Scalar>::Coordinates direction = q.normalized();
  DynamicsWorkspace<CartesianPendulum, Scalar> ws;
  ASSERT_EQ(project_onto_constraints<CartesianPendulum>(p, ws, Scalar(0), q, qd), DynamicsStatus::ok);
  const Scalar eps = std::numeric_limits<Scalar>::epsilon();
  EXPECT_NEAR((q - p.l * direction).norm(), Scalar(0), 16 * eps);
  const ConstraintResiduals<Scalar> r = constraint_residuals<CartesianPendulum>(p, ws, Scalar(0), q, qd);
  EXPECT_LE(r.position, 16 * eps);
  EXPECT_LE(r.velocity, 16 * eps);
  // the rate correction removes only the radial part: the tangential rate is kept
  const Scalar tangential = Scalar(0.5) * -direction(1) + Scalar(0.7) * direction(0);
  EXPECT_NEAR(qd(0) * -q(1) / p.l + qd(1) * q(0) / p.l, tangential, 16 * eps);
}

TEST(ForwardDynamics, SolvesWithoutHeapAllocation) {
  const CartesianPendulum::Parameters<double> p;
  const ModelTypes<CartesianPendulum, double>::Inputs u;
  ModelTypes<CartesianPendulum, double>::Coordinates q(0.3, -0.75), qd(0.4, 0.2);
  DynamicsWorkspace<CartesianPendulum, double> ws;
  const SpeedPartition<CartesianPendulum> x_independent = independent_speeds<CartesianPendulum>({{0}});
  eigen_assert_failures = 0;
  Eigen::internal::set_is_malloc_allowed(false);
  double checksum = 0;
  for (int i = 0; i < 1000; ++i) {
    q(0) = 0.3 + 1e-4 * i;
    checksum += static_cast<int>(forward_dynamics_kkt<CartesianPendulum>(p, ws, 0.0, q, qd, u, {1.0, 2.0}));
    checksum += static_cast<int>(forward_dynamics_null_space<CartesianPendulum>(p, ws, 0.0, q, qd, u));
    checksum += static_cast<int>(
        forward_dynamics_null_space<CartesianPendulum>(p, ws, 0.0, q, qd, u, {}, &x_independent));
    checksum += static_cast<int>(project_onto_constraints<CartesianPendulum>(p, ws, 0.0, q, qd));
  }
  Eigen::internal::set_is_malloc_allowed(true);
  EXPECT_EQ(eigen_assert_failures, 0);
  EXPECT_EQ(checksum, 0.0);  // every solve returned ok
}

}  // namespace
}  // namespace eomrt
