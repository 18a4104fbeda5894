// The generated forward_dynamics_derivatives of the linearized models, compiled: against central
// differences of the runtime's forward dynamics (which knows nothing of derivatives), and
// against eomrt::linearization's bottom rows computed without it. With constraints the header
// composes them of the KKT system's solve (kkt_derivatives), and its companion
// multiplier_derivatives gives those of lambda: both against differences of the runtime's
// forward_dynamics_kkt, and against the runtime's own KKT path of the linearization.
#include "runtime/no_malloc.hpp"  // before Eigen

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "cart_pole.hpp"
#include "cartesian_pendulum.hpp"
#include "double_pendulum.hpp"
#include "eomrt/dynamics_kkt.hpp"
#include "eomrt/dynamics_unconstrained.hpp"
#include "eomrt/linearization.hpp"
#include "four_bar.hpp"
#include "heavy_top.hpp"
#include "knife_edge.hpp"
#include "planar_3rrr.hpp"
#include "quaternion_rigid_body.hpp"
#include "rolling_coin.hpp"
#include "spacecraft_panel.hpp"
#include "two_wheeled_robot.hpp"
#include "whipple_bicycle.hpp"

namespace {

template <class Model>
struct Point {
  typename Model::template Vector<double> q, qd;
  typename Model::template Inputs<double> u;
};

// a generic point from a fixed seed; for a constrained model off its constraints, where the KKT
// accelerations and their derivatives are defined as well
template <class Model>
Point<Model> generic_point(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-0.8, 0.8);
  Point<Model> x;
  for (int k = 0; k < Model::nq; ++k) x.q(k) = value(rng), x.qd(k) = 2 * value(rng);
  for (int k = 0; k < Model::nu; ++k) x.u(k) = value(rng);
  return x;
}

// [qdd; lambda] of the runtime's forward dynamics (KKT with constraints)
template <class Model>
Eigen::VectorXd accelerations_and_multipliers(double t, const Point<Model>& x) {
  const typename Model::template Parameters<double> p{};
  eomrt::DynamicsWorkspace<Model, double> ws;
  eomrt::DynamicsStatus status;
  if constexpr (Model::nc == 0)
    status = eomrt::forward_dynamics_unconstrained<Model>(p, ws, t, x.q, x.qd, x.u);
  else
    status = eomrt::forward_dynamics_kkt<Model>(p, ws, t, x.q, x.qd, x.u);
  EXPECT_EQ(status, eomrt::DynamicsStatus::ok);
  Eigen::VectorXd out(Model::nq + Model::nc);
  out.head(Model::nq) = ws.qdd;
  if constexpr (Model::nc > 0) out.tail(Model::nc) = ws.lambda;
  return out;
}

// d[qdd; lambda]/d[q, qd, u] by central differences
template <class Model>
Eigen::MatrixXd central_differences(double t, const Point<Model>& x) {
  constexpr int nq = Model::nq, nu = Model::nu;
  Eigen::MatrixXd d(nq + Model::nc, 2 * nq + nu);
  for (int k = 0; k < 2 * nq + nu; ++k) {
    Point<Model> plus = x, minus = x;
    double& up = k < nq ? plus.q(k) : k < 2 * nq ? plus.qd(k - nq) : plus.u(k - 2 * nq);
    double& down = k < nq ? minus.q(k) : k < 2 * nq ? minus.qd(k - nq) : minus.u(k - 2 * nq);
    const double h = 1e-6 * std::max(1.0, std::abs(up));
    up += h;
    down -= h;
    d.col(k) = (accelerations_and_multipliers<Model>(t, plus) - accelerations_and_multipliers<Model>(t, minus)) / (2 * h);
  }
  return d;
}

bool near(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double tol) {
  return (a - b).cwiseAbs().maxCoeff() <= tol * (1 + b.cwiseAbs().maxCoeff());
}

template <class Model>
void expect_derivatives_match() {
  constexpr int nq = Model::nq, nu = Model::nu, nc = Model::nc;
  const typename Model::template Parameters<double> p{};
  const typename Model::template Constants<double> c(p);
  const double t = 0.3;
  for (unsigned seed : {3u, 4u, 5u}) {
    const Point<Model> x = generic_point<Model>(seed);
    Eigen::Matrix<double, nq, nq> by_q, by_qd;
    Eigen::Matrix<double, nq, nu> by_u;
    ASSERT_TRUE(Model::forward_dynamics_derivatives(t, x.q, x.qd, x.u, c, by_q, by_qd, by_u)) << Model::name;
    Eigen::MatrixXd ours(nq + nc, 2 * nq + nu);
    ours.topRows(nq) << by_q, by_qd, by_u;
    if constexpr (nc > 0) {
      Eigen::Matrix<double, nc, nq> l_q, l_qd;
      Eigen::Matrix<double, nc, nu> l_u;
      ASSERT_TRUE(Model::multiplier_derivatives(t, x.q, x.qd, x.u, p, l_q, l_qd, l_u)) << Model::name;
      ours.bottomRows(nc) << l_q, l_qd, l_u;
    }
    if constexpr (nc == 0) {
      // the overload that writes qdd too, with Constants and with Parameters: the same numbers,
      // and the qdd of the runtime's forward dynamics
      for (const bool from_parameters : {false, true}) {
        typename Model::template Vector<double> qdd;
        Eigen::Matrix<double, nq, nq> with_q, with_qd;
        Eigen::Matrix<double, nq, nu> with_u;
        ASSERT_TRUE(from_parameters ? Model::forward_dynamics_derivatives(t, x.q, x.qd, x.u, p, qdd, with_q, with_qd, with_u)
                                    : Model::forward_dynamics_derivatives(t, x.q, x.qd, x.u, c, qdd, with_q, with_qd, with_u))
            << Model::name;
        EXPECT_TRUE(near(qdd, accelerations_and_multipliers<Model>(t, x), 1e-12)) << Model::name << ", seed " << seed;
        EXPECT_EQ(Eigen::MatrixXd(with_q), Eigen::MatrixXd(by_q)) << Model::name;
        EXPECT_EQ(Eigen::MatrixXd(with_qd), Eigen::MatrixXd(by_qd)) << Model::name;
        EXPECT_EQ(Eigen::MatrixXd(with_u), Eigen::MatrixXd(by_u)) << Model::name;
      }
    }
    EXPECT_TRUE(near(ours, central_differences<Model>(t, x), 1e-6))
        << Model::name << ", seed " << seed << "\n" << ours << "\n\n" << central_differences<Model>(t, x);
    // the linearization's bottom rows: for a constrained model the runtime's own KKT path
    static eomrt::LinearizationWorkspace<Model, double> ws;
    ASSERT_EQ(eomrt::linearization<Model>(c, ws, t, x.q, x.qd, x.u), eomrt::DynamicsStatus::ok);
    Eigen::MatrixXd bottom(nq, 2 * nq + nu);
    bottom << ws.A.template bottomRows<nq>(), ws.B.template bottomRows<nq>();
    EXPECT_TRUE(near(ours.topRows(nq), bottom, 1e-12)) << Model::name << ", seed " << seed;
    // and the point's own accelerations, which a step's stages read there
    EXPECT_TRUE(near(ws.dynamics.qdd, accelerations_and_multipliers<Model>(t, x).head(nq), 1e-12)) << Model::name;
  }
}

TEST(GeneratedForwardDynamicsDerivatives, MatchDifferencesOfTheForwardDynamicsAndTheLinearization) {
  expect_derivatives_match<eomgen_models::cart_pole::Model>();
  expect_derivatives_match<eomgen_models::double_pendulum::Model>();
  expect_derivatives_match<eomgen_models::heavy_top::Model>();
  expect_derivatives_match<eomgen_models::spacecraft_panel::Model>();
}

TEST(GeneratedForwardDynamicsDerivatives, ConstrainedModelsAndTheirMultipliersMatchDifferencesOfTheKktSolve) {
  expect_derivatives_match<eomgen_models::cartesian_pendulum::Model>();
  expect_derivatives_match<eomgen_models::four_bar::Model>();
  expect_derivatives_match<eomgen_models::knife_edge::Model>();
  expect_derivatives_match<eomgen_models::planar_3rrr::Model>();
  expect_derivatives_match<eomgen_models::quaternion_rigid_body::Model>();
  expect_derivatives_match<eomgen_models::whipple_bicycle::Model>();
  expect_derivatives_match<eomgen_models::rolling_coin::Model>();
}

TEST(GeneratedForwardDynamicsDerivatives, AllocateNothingAndWriteIntoBlocks) {
  using Model = eomgen_models::rolling_coin::Model;
  const Model::Constants<double> c{Model::Parameters<double>{}};
  const Point<Model> x = generic_point<Model>(9);
  Eigen::Matrix<double, Model::nq, 2 * Model::nq + Model::nu + 1> stacked;
  stacked.setConstant(7.0);
  Eigen::Matrix<double, Model::nq, Model::nq> by_q, by_qd;
  Eigen::Matrix<double, Model::nq, Model::nu> by_u;
  Eigen::internal::set_is_malloc_allowed(false);
  const bool into_blocks = Model::forward_dynamics_derivatives(
      0.0, x.q, x.qd, x.u, c, stacked.leftCols<Model::nq>(), stacked.middleCols<Model::nq>(Model::nq),
      stacked.middleCols<Model::nu>(2 * Model::nq));
  const bool into_matrices = Model::forward_dynamics_derivatives(0.0, x.q, x.qd, x.u, c, by_q, by_qd, by_u);
  Eigen::internal::set_is_malloc_allowed(true);
  ASSERT_TRUE(into_blocks && into_matrices);
  EXPECT_EQ(Eigen::MatrixXd(stacked.leftCols<Model::nq>()), Eigen::MatrixXd(by_q));
  EXPECT_EQ(Eigen::MatrixXd(stacked.middleCols<Model::nq>(Model::nq)), Eigen::MatrixXd(by_qd));
  EXPECT_TRUE((stacked.rightCols<1>().array() == 7.0).all());
}

// a singular M (no mass at all), and a singular KKT matrix (the pendulum's bob without mass:
// [[0, -Xi^T], [-Xi, 0]] of two coordinates and one row), are reported, not returned as numbers
TEST(GeneratedForwardDynamicsDerivatives, ASingularMassOrKktMatrixIsReported) {
  {
    using Model = eomgen_models::cart_pole::Model;
    Model::Parameters<double> p{};
    p.mc = 0;
    p.mp = 0;
    const Point<Model> x = generic_point<Model>(2);
    Eigen::Matrix<double, Model::nq, Model::nq> by_q, by_qd;
    Eigen::Matrix<double, Model::nq, Model::nu> by_u;
    EXPECT_FALSE(Model::forward_dynamics_derivatives(0.0, x.q, x.qd, x.u, p, by_q, by_qd, by_u));
  }
  using Model = eomgen_models::cartesian_pendulum::Model;
  Model::Parameters<double> p{};
  p.m = 0;
  const Point<Model> x = generic_point<Model>(2);
  Eigen::Matrix<double, Model::nq, Model::nq> by_q, by_qd;
  Eigen::Matrix<double, Model::nq, Model::nu> by_u;
  EXPECT_FALSE(Model::forward_dynamics_derivatives(0.0, x.q, x.qd, x.u, p, by_q, by_qd, by_u));
  Eigen::Matrix<double, Model::nc, Model::nq> l_q, l_qd;
  Eigen::Matrix<double, Model::nc, Model::nu> l_u;
  EXPECT_FALSE(Model::multiplier_derivatives(0.0, x.q, x.qd, x.u, p, l_q, l_qd, l_u));
}

// The two-wheeled robot's four rolling rows have rank three: the header's KKT solve has no rule
// for a redundant set and says so, where the runtime's linearization (which sets the redundant
// rows' multipliers to zero, kkt_system.hpp) still answers
TEST(GeneratedForwardDynamicsDerivatives, ARedundantSetOfConstraintsIsRefusedWhereTheRuntimeAnswers) {
  using Model = eomgen_models::two_wheeled_robot::Model;
  const Model::Constants<double> c{Model::Parameters<double>{}};
  const Point<Model> x = generic_point<Model>(3);
  Eigen::Matrix<double, Model::nq, Model::nq> by_q, by_qd;
  Eigen::Matrix<double, Model::nq, Model::nu> by_u;
  EXPECT_FALSE(Model::forward_dynamics_derivatives(0.3, x.q, x.qd, x.u, c, by_q, by_qd, by_u));
  static eomrt::LinearizationWorkspace<Model, double> ws;
  EXPECT_EQ(eomrt::linearization<Model>(c, ws, 0.3, x.q, x.qd, x.u), eomrt::DynamicsStatus::ok);
  EXPECT_TRUE(ws.A.allFinite());
}

}  // namespace
