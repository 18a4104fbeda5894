// Tests for the runtime's linearization (linearization.hpp) on hand-written models that add
// linearization_terms by hand: the oscillator's closed form, the Cartesian pendulum's KKT
// derivatives against central differences of forward_dynamics_kkt and against the angle
// pendulum's eigenvalues, the statuses, and no allocation. The agreement with the generator's
// linearize() on shipped models is in tests/generated/generated_linearization_test.cpp.

#include "runtime/no_malloc.hpp"  // first: it configures Eigen

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <complex>
#include <limits>

#include "eomrt/eomrt.hpp"
#include "runtime/handwritten_models.hpp"
#include "runtime/scalar_types.hpp"

namespace eomrt {
namespace {

using testing::ScalarName;
using testing::Scalars;

/// m qdd = -k q + u: R = m qdd + k q - u, so K = k, D = 0, B_u = 1.
struct LinearizedOscillator : testing::Oscillator {
  template <class S>
  static void linearization_terms(const S&, const V<S>&, const V<S>&, const Eigen::Matrix<S, nu, 1>&,
                                  const Parameters<S>& p, const V<S>&, Eigen::Matrix<S, 1, 1>& K,
                                  Eigen::Matrix<S, 1, 1>& D, Eigen::Matrix<S, 1, 1>& B_u) {
    K(0, 0) = p.k;
    D(0, 0) = 0;
    B_u(0, 0) = 1;
  }
};

/// R = M qdd - F - Xi^T lambda = (m xdd - 2 x lambda, m ydd + m g - 2 y lambda) and
/// S = Xi qdd + b = 2 x xdd + 2 y ydd + 2 (xd^2 + yd^2).
struct LinearizedCartesianPendulum : testing::CartesianPendulum {
  template <class S>
  static void linearization_terms(const S&, const V<S>&, const V<S>& qd, const Eigen::Matrix<S, nu, 1>&,
                                  const Parameters<S>&, const V<S>& qdd, const Eigen::Matrix<S, nc, 1>& lambda,
                                  Eigen::Matrix<S, nq, nq>& K, Eigen::Matrix<S, nq, nq>& D,
                                  Eigen::Matrix<S, nq, nu>&, Eigen::Matrix<S, nc, nq>& S_q,
                                  Eigen::Matrix<S, nc, nq>& S_qd) {
    K = -2 * lambda(0) * Eigen::Matrix<S, nq, nq>::Identity();
    D.setZero();
    S_q = 2 * qdd.transpose();
    S_qd = 4 * qd.transpose();
  }
};

/// The same pendulum's M singular everywhere (the redundant mass without its constraint).
struct LinearizedRedundantMass : testing::RedundantMass<false> {
  template <class S>
  static void linearization_terms(const S&, const V<S>&, const V<S>&, const Eigen::Matrix<S, nu, 1>&,
                                  const Parameters<S>& p, const V<S>&, Eigen::Matrix<S, nq, nq>& K,
                                  Eigen::Matrix<S, nq, nq>& D, Eigen::Matrix<S, nq, nu>&) {
    K.setConstant(p.k);
    D.setZero();
  }
};

template <class Scalar>
class LinearizationOverScalars : public ::testing::Test {};
TYPED_TEST_SUITE(LinearizationOverScalars, Scalars, ScalarName);

TYPED_TEST(LinearizationOverScalars, OscillatorHasTheClosedForm) {
  using Scalar = TypeParam;
  using Model = LinearizedOscillator;
  const typename Model::template Parameters<Scalar> p;
  const typename ModelTypes<Model, Scalar>::Coordinates q(Scalar(0.3)), qd(Scalar(-1));
  const typename ModelTypes<Model, Scalar>::Inputs u(Scalar(2));
  LinearizationWorkspace<Model, Scalar> ws;
  ASSERT_EQ(linearization<Model>(p, ws, Scalar(0), q, qd, u), DynamicsStatus::ok);
  // A = [[0, 1], [-k/m, 0]], B = [0; 1/m], through a Cholesky factor sqrt(m)
  const Scalar tol = 8 * std::numeric_limits<Scalar>::epsilon();
  EXPECT_EQ(ws.A(0, 0), Scalar(0));
  EXPECT_EQ(ws.A(0, 1), Scalar(1));
  EXPECT_NEAR(ws.A(1, 0), -p.k / p.m, tol);
  EXPECT_EQ(ws.A(1, 1), Scalar(0));
  EXPECT_EQ(ws.B(0, 0), Scalar(0));
  EXPECT_NEAR(ws.B(1, 0), 1 / p.m, tol);
  ASSERT_EQ(second_order_linearization<Model>(p, ws, Scalar(0), q, qd, u), DynamicsStatus::ok);
  EXPECT_EQ(ws.dynamics.M(0, 0), p.m);
  EXPECT_EQ(ws.terms.K(0, 0), p.k);
  EXPECT_NEAR(ws.dynamics.qdd(0), (-p.k * q(0) + u(0)) / p.m, tol);  // qdd0
}

/// [A B] of forward_dynamics_kkt by central differences in (q, qd).
template <class Model>
Eigen::Matrix<double, 2 * Model::nq, 2 * Model::nq> kkt_differences(const typename ModelTypes<Model, double>::Coordinates& q,
                                                                   const typename ModelTypes<Model, double>::Coordinates& qd) {
  constexpr int nq = Model::nq;
  const typename Model::template Parameters<double> p;
  const typename ModelTypes<Model, double>::Inputs u;
  DynamicsWorkspace<Model, double> ws;
  Eigen::Matrix<double, 2 * nq, 1> z;
  z << q, qd;
  Eigen::Matrix<double, 2 * nq, 2 * nq> A = Eigen::Matrix<double, 2 * nq, 2 * nq>::Zero();
  A.template topRightCorner<nq, nq>().setIdentity();
  for (int k = 0; k < 2 * nq; ++k) {
    const double h = 1e-6;
    Eigen::Matrix<double, 2 * nq, 1> plus = z, minus = z;
    plus(k) += h;
    minus(k) -= h;
    EXPECT_EQ(forward_dynamics_kkt<Model>(p, ws, 0.0, plus.template head<nq>(), plus.template tail<nq>(), u),
              DynamicsStatus::ok);
    const auto qdd_plus = ws.qdd;
    EXPECT_EQ(forward_dynamics_kkt<Model>(p, ws, 0.0, minus.template head<nq>(), minus.template tail<nq>(), u),
              DynamicsStatus::ok);
    A.template bottomRows<nq>().col(k) = (qdd_plus - ws.qdd) / (2 * h);
  }
  return A;
}

TEST(Linearization, CartesianPendulumMatchesCentralDifferencesOfTheKktAccelerations) {
  using Model = LinearizedCartesianPendulum;
  const Model::Parameters<double> p;
  const double theta = 0.7, rate = -1.3;
  const ModelTypes<Model, double>::Coordinates q(p.l * std::sin(theta), -p.l * std::cos(theta)),
      qd(p.l * std::cos(theta) * rate, p.l * std::sin(theta) * rate);
  LinearizationWorkspace<Model, double> ws;
  ASSERT_EQ(linearization<Model>(p, ws, 0.0, q, qd, {}), DynamicsStatus::ok);
  const auto differences = kkt_differences<Model>(q, qd);
  EXPECT_LT((ws.A - differences).cwiseAbs().maxCoeff(), 1e-7 * std::max(1.0, differences.cwiseAbs().maxCoeff()));
  EXPECT_EQ(ws.B.cols(), 0);
}

TYPED_TEST(LinearizationOverScalars, HangingCartesianPendulumOscillatesAtTheAnglePendulumsFrequency) {
  using Scalar = TypeParam;
  using Model = LinearizedCartesianPendulum;
  const typename Model::template Parameters<Scalar> p;
  const typename ModelTypes<Model, Scalar>::Coordinates q(Scalar(0), -p.l), qd(Scalar(0), Scalar(0));
  LinearizationWorkspace<Model, Scalar> ws;
  ASSERT_EQ(linearization<Model>(p, ws, Scalar(0), q, qd, {}), DynamicsStatus::ok);
  // the rod holds the bob: lambda0 = -m g / (2 l), and x'' = -g/l x on the tangent
  EXPECT_NEAR(ws.dynamics.lambda(0), -p.m * p.g / (2 * p.l), 64 * std::numeric_limits<Scalar>::epsilon());
  using std::sqrt;
  EXPECT_NEAR(ws.A(2, 0), -p.g / p.l, 64 * std::numeric_limits<Scalar>::epsilon());
  const Eigen::VectorXcd eigenvalues = ws.A.template cast<double>().eigenvalues();
  double nearest = 1e300;
  for (Eigen::Index i = 0; i < eigenvalues.size(); ++i)
    nearest = std::min(nearest, std::abs(eigenvalues(i) - std::complex<double>(0, std::sqrt(double(p.g / p.l)))));
  EXPECT_LT(nearest, 1e-9);
}

TEST(Linearization, SingularDynamicsAreReportedNotSolved) {
  LinearizationWorkspace<LinearizedCartesianPendulum, double> pendulum;
  // the bob on the pivot: Xi = 0
  EXPECT_EQ(linearization<LinearizedCartesianPendulum>({}, pendulum, 0.0, {0.0, 0.0}, {0.0, 0.0}, {}),
            DynamicsStatus::singular_kkt_matrix);
  LinearizationWorkspace<LinearizedRedundantMass, double> redundant;
  EXPECT_EQ(linearization<LinearizedRedundantMass>({}, redundant, 0.0, {0.1, 0.2}, {0.0, 0.0}, {}),
            DynamicsStatus::singular_mass_matrix);
  EXPECT_EQ(second_order_linearization<LinearizedRedundantMass>({}, redundant, 0.0, {0.1, 0.2}, {0.0, 0.0}, {}),
            DynamicsStatus::singular_mass_matrix);
  LinearizationWorkspace<LinearizedOscillator, double> oscillator;
  const ModelTypes<LinearizedOscillator, double>::Coordinates nan(std::nan(""));
  EXPECT_EQ(linearization<LinearizedOscillator>({}, oscillator, 0.0, nan, nan, ModelTypes<LinearizedOscillator, double>::Inputs(0.0)),
            DynamicsStatus::non_finite);
}

TEST(Linearization, AllocatesNothing) {
  const ModelTypes<LinearizedCartesianPendulum, double>::Coordinates q(0.3, -0.74), qd(0.5, 0.2);
  const ModelTypes<LinearizedOscillator, double>::Inputs u(1.0);
  LinearizationWorkspace<LinearizedCartesianPendulum, double> pendulum;
  LinearizationWorkspace<LinearizedOscillator, double> oscillator;
  eigen_assert_failures = 0;
  Eigen::internal::set_is_malloc_allowed(false);
  const DynamicsStatus constrained = linearization<LinearizedCartesianPendulum>({}, pendulum, 0.0, q, qd, {});
  const DynamicsStatus unconstrained = linearization<LinearizedOscillator>({}, oscillator, 0.0, q.head<1>(), qd.head<1>(), u);
  Eigen::internal::set_is_malloc_allowed(true);
  EXPECT_EQ(constrained, DynamicsStatus::ok);
  EXPECT_EQ(unconstrained, DynamicsStatus::ok);
  EXPECT_EQ(eigen_assert_failures, 0);
}

}  // namespace
}  // namespace eomrt
