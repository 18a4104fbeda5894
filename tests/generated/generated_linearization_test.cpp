// The runtime's linearization (eomrt/linearization.hpp) of generated linearization_terms
// (eomgen generate --linearization) against two independent references: the generator's own
// linearize(), which evaluates the same derivatives through GiNaC in doubles, and central
// differences of the runtime's forward dynamics, which know nothing of derivatives.
// Constrained models are also checked against the reduced linear model: its eigenvalues must
// be eigenvalues of the full-state A the runtime gives.
#include "runtime/no_malloc.hpp"  // before Eigen

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <string>

#include "cart_pole.hpp"
#include "cartesian_pendulum.hpp"
#include "double_pendulum.hpp"
#include "eomgen/derivation/equations_of_motion.hpp"
#include "eomgen/derivation/linearization.hpp"
#include "eomgen/derivation/model_equations.hpp"
#include "eomgen/language/model_file.hpp"
#include "eomrt/dynamics_kkt.hpp"
#include "eomrt/linearization.hpp"
#include "heavy_top.hpp"
#include "rolling_coin.hpp"
#include "spacecraft_panel.hpp"
#include "support/numeric_checks.hpp"
#include "support/source_dir.hpp"

namespace {

using eomgen::NamedValues;
using eomgen::testing::matrices_near_relative;

template <class Model>
struct OperatingPoint {
  typename Model::template Vector<double> q, qd;
  typename Model::template Inputs<double> u;
};

// the point in the header's vectors; names missing from `values` are 0
template <class Model>
OperatingPoint<Model> at(const NamedValues& values) {
  const auto get = [&](const std::string& name) {
    const auto it = values.find(name);
    return it == values.end() ? 0.0 : it->second;
  };
  OperatingPoint<Model> x;
  for (int k = 0; k < Model::nq; ++k) {
    x.q(k) = get(Model::coordinate_names[static_cast<std::size_t>(k)]);
    x.qd(k) = get(std::string(Model::coordinate_names[static_cast<std::size_t>(k)]) + "_dot");
  }
  for (int k = 0; k < Model::nu; ++k) x.u(k) = get(Model::input_names[static_cast<std::size_t>(k)]);
  return x;
}

struct Generated {
  Eigen::MatrixXd A, B;
};

template <class Model>
Generated generated_linearization(const OperatingPoint<Model>& x) {
  eomrt::LinearizationWorkspace<Model, double> ws;
  EXPECT_EQ(eomrt::linearization<Model>({}, ws, 0.0, x.q, x.qd, x.u), eomrt::DynamicsStatus::ok);
  return {ws.A, ws.B};
}

eomgen::Model shipped(const std::string& name) {
  return eomgen::load_model(eomgen::testing::shipped_model_path(name));
}

eomgen::LinearModel generator_linearization(const std::string& name, const NamedValues& point) {
  const eomgen::Model model = shipped(name);
  const eomgen::ModelEquations eom = eomgen::derive_equations(model);
  return eomgen::linearize(model, eom, eomgen::linearize_symbolic(model, eom), point);
}

// [A B] of the runtime's accelerations by central differences: KKT for constrained models
// (defined on and off the constraint manifold), Cholesky otherwise
template <class Model>
Generated central_differences(const OperatingPoint<Model>& x) {
  constexpr int nq = Model::nq, nu = Model::nu;
  const typename Model::template Parameters<double> p{};
  eomrt::DynamicsWorkspace<Model, double> ws;
  // qdd as a function of z = [q; qd; u]
  const auto qdd = [&](const Eigen::VectorXd& z) {
    const typename Model::template Vector<double> q = z.head(nq), qd = z.segment(nq, nq);
    const typename Model::template Inputs<double> u = z.tail(nu);
    EXPECT_EQ(eomrt::forward_dynamics_kkt(p, ws, 0.0, q, qd, u), eomrt::DynamicsStatus::ok);
    return Eigen::VectorXd(ws.qdd);
  };
  Eigen::VectorXd z(2 * nq + nu);
  z << x.q, x.qd, x.u;
  Eigen::MatrixXd jacobian(nq, z.size());
  for (Eigen::Index k = 0; k < z.size(); ++k) {
    const double h = 1e-6 * std::max(1.0, std::abs(z(k)));
    Eigen::VectorXd plus = z, minus = z;
    plus(k) += h;
    minus(k) -= h;
    jacobian.col(k) = (qdd(plus) - qdd(minus)) / (2 * h);
  }
  Generated d{Eigen::MatrixXd::Zero(2 * nq, 2 * nq), Eigen::MatrixXd::Zero(2 * nq, nu)};
  d.A.topRightCorner(nq, nq).setIdentity();
  d.A.bottomRows(nq) = jacobian.leftCols(2 * nq);
  d.B.bottomRows(nq) = jacobian.rightCols(nu);
  return d;
}

template <class Model>
void expect_matches_references(const std::string& name, const NamedValues& point) {
  SCOPED_TRACE(name);
  const OperatingPoint<Model> x = at<Model>(point);
  const Generated generated = generated_linearization(x);
  const Generated differences = central_differences(x);
  EXPECT_TRUE(matrices_near_relative(generated.A, differences.A, 1e-6)) << "A against central differences";
  EXPECT_TRUE(matrices_near_relative(generated.B, differences.B, 1e-6)) << "B against central differences";
  if (Model::nc == 0) {
    const eomgen::LinearModel lin = generator_linearization(name, point);
    EXPECT_TRUE(matrices_near_relative(generated.A, lin.A, 1e-12)) << "A against linearize()";
    EXPECT_TRUE(matrices_near_relative(generated.B, lin.B, 1e-12)) << "B against linearize()";
  }
}

// the generator's full-state A and B come from the same numerics (eomrt::first_order_form and
// the one KKT solve) applied to its own evaluation of the terms; it takes points on the
// constraints only
template <class Model>
void expect_matches_generator_full_state(const std::string& name, const NamedValues& point) {
  SCOPED_TRACE(name);
  const Generated generated = generated_linearization(at<Model>(point));
  const eomgen::LinearModel lin = generator_linearization(name, point);
  EXPECT_TRUE(matrices_near_relative(generated.A, lin.A_full, 1e-12)) << "A against linearize()";
  EXPECT_TRUE(matrices_near_relative(generated.B, lin.B_full, 1e-12)) << "B against linearize()";
}

TEST(GeneratedLinearization, MatchesTheGeneratorAndFiniteDifferencesAwayFromEquilibrium) {
  expect_matches_references<eomgen_models::cart_pole::Model>(
      "cart_pole", {{"x", 0.3}, {"theta", 0.7}, {"x_dot", -0.4}, {"theta_dot", 1.3}, {"u", 0.8}});
  expect_matches_references<eomgen_models::double_pendulum::Model>(
      "double_pendulum", {{"theta1", 0.4}, {"theta2", -1.1}, {"theta1_dot", 0.9}, {"theta2_dot", -0.5}});
  expect_matches_references<eomgen_models::spacecraft_panel::Model>(
      "spacecraft_panel", {{"gamma", 0.2}, {"theta", -0.6}, {"gamma_dot", 0.3}, {"theta_dot", 0.8},
                           {"tau_b", 0.1}, {"tau_p", -0.2}});
  // spinning fast: qdd0 is not zero, and dM/dq qdd0 is part of K
  expect_matches_references<eomgen_models::heavy_top::Model>(
      "heavy_top", {{"psi", 0.2}, {"theta", 0.6}, {"phi", 0.1}, {"psi_dot", 1.0}, {"theta_dot", 0.3}, {"phi_dot", 40.0}});
}

TEST(GeneratedLinearization, ConstrainedModelsMatchFiniteDifferencesOfTheKktAccelerations) {
  const double angle = 0.4, rate = 1.2, l = 0.5;
  expect_matches_references<eomgen_models::cartesian_pendulum::Model>(
      "cartesian_pendulum", {{"x", l * std::sin(angle)}, {"y", -l * std::cos(angle)},
                             {"x_dot", l * std::cos(angle) * rate}, {"y_dot", l * std::sin(angle) * rate}});
  expect_matches_references<eomgen_models::rolling_coin::Model>(
      "rolling_coin", {{"psi", 0.3}, {"theta", 0.2}, {"phi", 0.5}, {"psi_dot", 0.7}, {"theta_dot", -0.4},
                       {"phi_dot", 30.0}, {"x_dot", 0.1}, {"y_dot", 0.2}});
}

TEST(GeneratedLinearization, ConstrainedModelsMatchTheGeneratorsFullStateLinearization) {
  const double angle = 0.4, rate = 1.2, l = 0.5;
  expect_matches_generator_full_state<eomgen_models::cartesian_pendulum::Model>(
      "cartesian_pendulum", {{"x", l * std::sin(angle)}, {"y", -l * std::cos(angle)},
                             {"x_dot", l * std::cos(angle) * rate}, {"y_dot", l * std::sin(angle) * rate}});
  // the coin rolling upright (radius r), below and above its critical speed sqrt(g r / 3) / r
  const double r = 12.9e-3;
  for (const double w : {10.0, 30.0})
    expect_matches_generator_full_state<eomgen_models::rolling_coin::Model>("rolling_coin",
                                                                            {{"phi_dot", w}, {"y_dot", -r * w}});
  // an unconstrained model's full state is linearize()'s when nothing is dropped
  expect_matches_generator_full_state<eomgen_models::heavy_top::Model>(
      "heavy_top", {{"theta", 0.6}, {"psi_dot", 1.0}, {"phi_dot", 40.0}});
}

// every eigenvalue of the reduced model (independent coordinates and speeds) is one of the
// full state's: the tangent space of the constraint manifold is invariant under A
template <class Model>
void expect_reduced_spectrum_inside(const std::string& name, const NamedValues& point) {
  SCOPED_TRACE(name);
  const Generated full = generated_linearization(at<Model>(point));
  const eomgen::LinearModel reduced = generator_linearization(name, point);
  const Eigen::VectorXcd full_eigenvalues = full.A.eigenvalues();
  const Eigen::VectorXcd reduced_eigenvalues = reduced.A.eigenvalues();
  for (Eigen::Index i = 0; i < reduced_eigenvalues.size(); ++i) {
    double nearest = 1e300;
    for (Eigen::Index j = 0; j < full_eigenvalues.size(); ++j)
      nearest = std::min(nearest, std::abs(full_eigenvalues(j) - reduced_eigenvalues(i)));
    EXPECT_LT(nearest, 1e-6 * std::max(1.0, std::abs(reduced_eigenvalues(i)))) << reduced_eigenvalues(i);
  }
}

TEST(GeneratedLinearization, ReducedEigenvaluesAreEigenvaluesOfTheFullStateMatrix) {
  // the Cartesian pendulum hanging: +-sqrt(g/l) i, as the angle pendulum
  expect_reduced_spectrum_inside<eomgen_models::cartesian_pendulum::Model>("cartesian_pendulum", {{"y", -0.5}});
  const Generated hanging = generated_linearization(at<eomgen_models::cartesian_pendulum::Model>({{"y", -0.5}}));
  const Eigen::VectorXcd eigenvalues = hanging.A.eigenvalues();
  double nearest = 1e300;
  for (Eigen::Index j = 0; j < eigenvalues.size(); ++j)
    nearest = std::min(nearest, std::abs(eigenvalues(j) - std::complex<double>(0, std::sqrt(9.81 / 0.5))));
  EXPECT_LT(nearest, 1e-9);
  // the coin rolling upright at twice the critical speed sqrt(g r / 3)
  const double r = 12.9e-3, w = 2 * std::sqrt(9.81 * r / 3) / r;
  expect_reduced_spectrum_inside<eomgen_models::rolling_coin::Model>("rolling_coin",
                                                                     {{"phi_dot", w}, {"y_dot", -r * w}});
}

TEST(GeneratedLinearization, SecondOrderFormOfTheCartPoleUprightIsTheClosedForm) {
  // cart mass mc, pole of mass mp and length l (inertia mp l^2 / 3 about the hinge, radius
  // neglected up to rp^2 terms): K and B_u of the notes' section 5.5 at the upright position
  using Model = eomgen_models::cart_pole::Model;
  const Model::Parameters<double> p{};
  const OperatingPoint<Model> x = at<Model>({});
  eomrt::LinearizationWorkspace<Model, double> ws;
  ASSERT_EQ(eomrt::second_order_linearization<Model>(p, ws, 0.0, x.q, x.qd, x.u), eomrt::DynamicsStatus::ok);
  const Model::MassMatrix<double>& M = ws.dynamics.M;
  const Model::MassMatrix<double>& D = ws.terms.D;
  const Model::MassMatrix<double>& K = ws.terms.K;
  const Model::InputMatrix<double>& B_u = ws.terms.B_u;
  const eomgen::LinearModel lin = generator_linearization("cart_pole", {});
  EXPECT_TRUE(matrices_near_relative(M, lin.M, 1e-14)) << "M";
  EXPECT_TRUE(matrices_near_relative(D, lin.D, 1e-14)) << "D";
  EXPECT_TRUE(matrices_near_relative(K, lin.K, 1e-14)) << "K";
  EXPECT_TRUE(matrices_near_relative(B_u, lin.B_u, 1e-14)) << "B_u";
  EXPECT_NEAR(K(1, 1), -p.mp * p.g * p.l / 2, 1e-14);  // gravity destabilizes the pole
  EXPECT_EQ(K(0, 0), 0.0);
  EXPECT_EQ(D.cwiseAbs().maxCoeff(), 0.0);  // no damping, and at rest no gyroscopic terms
  EXPECT_EQ(B_u(0, 0), 1.0);
}

TEST(GeneratedLinearization, AllocatesNothing) {
  const auto x = at<eomgen_models::rolling_coin::Model>({{"theta", 0.2}, {"phi_dot", 30.0}});
  const auto y = at<eomgen_models::heavy_top::Model>({{"theta", 0.6}, {"phi_dot", 40.0}});
  eomrt::LinearizationWorkspace<eomgen_models::rolling_coin::Model, double> coin_ws;
  eomrt::LinearizationWorkspace<eomgen_models::heavy_top::Model, double> top_ws;
  eigen_assert_failures = 0;
  Eigen::internal::set_is_malloc_allowed(false);
  const auto coin = eomrt::linearization<eomgen_models::rolling_coin::Model>({}, coin_ws, 0.0, x.q, x.qd, x.u);
  const auto top = eomrt::linearization<eomgen_models::heavy_top::Model>({}, top_ws, 0.0, y.q, y.qd, y.u);
  Eigen::internal::set_is_malloc_allowed(true);
  EXPECT_EQ(coin, eomrt::DynamicsStatus::ok);
  EXPECT_EQ(top, eomrt::DynamicsStatus::ok);
  EXPECT_EQ(eigen_assert_failures, 0);
}

// an MPC's stacked matrices: A and B written into blocks of larger ones, the rest untouched,
// the numbers those of ws.A and ws.B, and nothing allocated
template <class Model>
void expect_blocks_written(const OperatingPoint<Model>& x) {
  constexpr int n = 2 * Model::nq, nu = Model::nu;
  const typename Model::template Parameters<double> p{};
  eomrt::LinearizationWorkspace<Model, double> ws, blocks_ws;
  ASSERT_EQ(eomrt::linearization<Model>(p, ws, 0.0, x.q, x.qd, x.u), eomrt::DynamicsStatus::ok);
  Eigen::Matrix<double, n + 3, 2 * n + 1> stacked = Eigen::Matrix<double, n + 3, 2 * n + 1>::Constant(7.0);
  Eigen::Matrix<double, n + 2, nu + 2> inputs = Eigen::Matrix<double, n + 2, nu + 2>::Constant(7.0);
  eigen_assert_failures = 0;
  Eigen::internal::set_is_malloc_allowed(false);
  const auto status = eomrt::linearization<Model>(p, blocks_ws, 0.0, x.q, x.qd, x.u,
                                                  stacked.template block<n, n>(2, n + 1),
                                                  inputs.template block<n, nu>(1, 2));
  Eigen::internal::set_is_malloc_allowed(true);
  EXPECT_EQ(status, eomrt::DynamicsStatus::ok);
  EXPECT_EQ(eigen_assert_failures, 0);
  EXPECT_EQ(Eigen::MatrixXd(stacked.template block<n, n>(2, n + 1)), Eigen::MatrixXd(ws.A)) << Model::name;
  EXPECT_EQ(Eigen::MatrixXd(inputs.template block<n, nu>(1, 2)), Eigen::MatrixXd(ws.B)) << Model::name;
  // everything outside the blocks keeps its 7
  stacked.template block<n, n>(2, n + 1).setConstant(7.0);
  inputs.template block<n, nu>(1, 2).setConstant(7.0);
  EXPECT_TRUE((stacked.array() == 7.0).all()) << Model::name;
  EXPECT_TRUE((inputs.array() == 7.0).all()) << Model::name;
}

TEST(GeneratedLinearization, WritesIntoBlocksOfACallersMatrices) {
  expect_blocks_written(at<eomgen_models::cart_pole::Model>({{"theta", 0.4}, {"theta_dot", 1.0}, {"u", 2.0}}));
  expect_blocks_written(at<eomgen_models::rolling_coin::Model>({{"theta", 0.2}, {"phi_dot", 30.0}}));
}

// the runtime's algorithms take the Constants as they take the Parameters, with the same numbers
template <class Model>
void expect_same_through_constants(const OperatingPoint<Model>& x) {
  const typename Model::template Parameters<double> p{};
  const typename Model::template Constants<double> c(p);
  eomrt::LinearizationWorkspace<Model, double> by_parameters, by_constants;
  ASSERT_EQ(eomrt::linearization<Model>(p, by_parameters, 0.0, x.q, x.qd, x.u), eomrt::DynamicsStatus::ok);
  ASSERT_EQ(eomrt::linearization<Model>(c, by_constants, 0.0, x.q, x.qd, x.u), eomrt::DynamicsStatus::ok);
  EXPECT_EQ(by_parameters.A, by_constants.A) << Model::name;
  EXPECT_EQ(by_parameters.B, by_constants.B) << Model::name;
  EXPECT_EQ(by_parameters.dynamics.qdd, by_constants.dynamics.qdd) << Model::name;
}

TEST(GeneratedLinearization, TheConstantsGiveWhatTheParametersGive) {
  expect_same_through_constants(at<eomgen_models::cart_pole::Model>({{"theta", 0.7}, {"theta_dot", 1.3}, {"u", 0.8}}));
  expect_same_through_constants(at<eomgen_models::rolling_coin::Model>({{"theta", 0.2}, {"phi_dot", 30.0}}));
}

TEST(GeneratedLinearization, SingularMassMatrixIsReported) {
  // 3-1-3 angles are singular with the top upright (theta = 0)
  using Model = eomgen_models::heavy_top::Model;
  const OperatingPoint<Model> x = at<Model>({{"phi_dot", 40.0}});
  eomrt::LinearizationWorkspace<Model, double> ws;
  EXPECT_EQ(eomrt::linearization<Model>({}, ws, 0.0, x.q, x.qd, x.u), eomrt::DynamicsStatus::singular_mass_matrix);
}

TEST(GeneratedLinearization, FloatInstantiationAgreesWithDouble) {
  using Model = eomgen_models::cart_pole::Model;
  const OperatingPoint<Model> x = at<Model>({{"theta", 0.7}, {"theta_dot", 1.3}, {"u", 0.8}});
  eomrt::LinearizationWorkspace<Model, float> ws;
  ASSERT_EQ(eomrt::linearization<Model>({}, ws, 0.0f, x.q.cast<float>().eval(), x.qd.cast<float>().eval(),
                                        x.u.cast<float>().eval()),
            eomrt::DynamicsStatus::ok);
  const Generated reference = generated_linearization(x);
  EXPECT_TRUE(matrices_near_relative(ws.A.cast<double>(), reference.A, 1e-5)) << "A in float";
  EXPECT_TRUE(matrices_near_relative(ws.B.cast<double>(), reference.B, 1e-5)) << "B in float";
}

}  // namespace
