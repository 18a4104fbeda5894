// The generated linearization() (eomgen generate --linearization) against two independent
// references: the generator's own linearize(), which evaluates the same derivatives through
// GiNaC in doubles, and central differences of the runtime's forward dynamics, which know
// nothing of derivatives. Constrained models are also checked against the reduced linear
// model: its eigenvalues must be eigenvalues of the full-state A the header gives.
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
  typename Model::template StateMatrix<double> A;
  typename Model::template StateInputMatrix<double> B;
  EXPECT_TRUE(Model::linearization(0.0, x.q, x.qd, x.u, typename Model::template Parameters<double>{}, A, B));
  return {A, B};
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
  Model::MassMatrix<double> M, D, K;
  Model::InputMatrix<double> B_u;
  ASSERT_TRUE(Model::second_order_linearization(0.0, x.q, x.qd, x.u, p, M, D, K, B_u));
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
  eomgen_models::rolling_coin::Model::StateMatrix<double> A;
  eomgen_models::rolling_coin::Model::StateInputMatrix<double> B;
  eomgen_models::heavy_top::Model::StateMatrix<double> A_top;
  eomgen_models::heavy_top::Model::StateInputMatrix<double> B_top;
  eigen_assert_failures = 0;
  Eigen::internal::set_is_malloc_allowed(false);
  const bool coin = eomgen_models::rolling_coin::Model::linearization(0.0, x.q, x.qd, x.u, {}, A, B);
  const bool top = eomgen_models::heavy_top::Model::linearization(0.0, y.q, y.qd, y.u, {}, A_top, B_top);
  Eigen::internal::set_is_malloc_allowed(true);
  EXPECT_TRUE(coin);
  EXPECT_TRUE(top);
  EXPECT_EQ(eigen_assert_failures, 0);
}

TEST(GeneratedLinearization, SingularMassMatrixReturnsFalse) {
  // 3-1-3 angles are singular with the top upright (theta = 0)
  using Model = eomgen_models::heavy_top::Model;
  const OperatingPoint<Model> x = at<Model>({{"phi_dot", 40.0}});
  Model::StateMatrix<double> A;
  Model::StateInputMatrix<double> B;
  EXPECT_FALSE(Model::linearization(0.0, x.q, x.qd, x.u, Model::Parameters<double>{}, A, B));
}

TEST(GeneratedLinearization, FloatInstantiationAgreesWithDouble) {
  using Model = eomgen_models::cart_pole::Model;
  const OperatingPoint<Model> x = at<Model>({{"theta", 0.7}, {"theta_dot", 1.3}, {"u", 0.8}});
  Model::StateMatrix<float> A;
  Model::StateInputMatrix<float> B;
  ASSERT_TRUE(Model::linearization(0.0f, x.q.cast<float>().eval(), x.qd.cast<float>().eval(), x.u.cast<float>().eval(),
                                   Model::Parameters<float>{}, A, B));
  const Generated reference = generated_linearization(x);
  EXPECT_TRUE(matrices_near_relative(A.cast<double>(), reference.A, 1e-5)) << "A in float";
  EXPECT_TRUE(matrices_near_relative(B.cast<double>(), reference.B, 1e-5)) << "B in float";
}

}  // namespace
