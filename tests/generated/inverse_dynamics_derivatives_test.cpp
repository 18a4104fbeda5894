// eomrt::inverse_dynamics_derivatives (inverse_dynamics_derivatives.hpp) against central
// differences of the generated inverse_dynamics (tau = M qdd - F, an independent function of
// the header; with constraints its split into the least tau and Xi^T lambda) in q and qd, at
// generic states and accelerations.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "cart_pole.hpp"
#include "cartesian_pendulum.hpp"
#include "double_pendulum.hpp"
#include "eomrt/inverse_dynamics_derivatives.hpp"
#include "heavy_top.hpp"
#include "rolling_coin.hpp"
#include "spacecraft_panel.hpp"

namespace {

template <class Model>
void expect_matches_differences_of_the_inverse_dynamics() {
  constexpr int nq = Model::nq, nu = Model::nu;
  using Vector = typename Model::template Vector<double>;
  using Matrix = Eigen::Matrix<double, nq, nq>;
  const typename Model::template Parameters<double> p{};
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> value(-0.8, 0.8);
  for (int trial = 0; trial < 3; ++trial) {
    Vector q, qd, qdd;
    for (int k = 0; k < nq; ++k) q(k) = value(rng), qd(k) = 2 * value(rng), qdd(k) = 3 * value(rng);
    typename Model::template Inputs<double> u;
    for (int k = 0; k < nu; ++k) u(k) = value(rng);
    const double t = 0.2;
    Matrix dq = Matrix::Zero(), dqd = Matrix::Zero();
    ASSERT_EQ(eomrt::inverse_dynamics_derivatives<Model>(p, t, q, qd, qdd, u, dq, dqd), eomrt::DynamicsStatus::ok);
    const auto tau = [&](const Vector& at_q, const Vector& at_qd) {
      Vector out;
      Model::inverse_dynamics(t, at_q, at_qd, qdd, u, p, out);
      return out;
    };
    Matrix fd_q, fd_qd;
    for (int k = 0; k < nq; ++k) {
      const double h = 1e-6 * std::max(1.0, std::abs(q(k)));
      Vector plus = q, minus = q;
      plus(k) += h;
      minus(k) -= h;
      fd_q.col(k) = (tau(plus, qd) - tau(minus, qd)) / (2 * h);
      const double g = 1e-6 * std::max(1.0, std::abs(qd(k)));
      plus = qd, minus = qd;
      plus(k) += g;
      minus(k) -= g;
      fd_qd.col(k) = (tau(q, plus) - tau(q, minus)) / (2 * g);
    }
    EXPECT_LE((dq - fd_q).cwiseAbs().maxCoeff(), 1e-6 * (1 + fd_q.cwiseAbs().maxCoeff())) << Model::name;
    EXPECT_LE((dqd - fd_qd).cwiseAbs().maxCoeff(), 1e-6 * (1 + fd_qd.cwiseAbs().maxCoeff())) << Model::name;
  }
}

TEST(InverseDynamicsDerivatives, MatchCentralDifferencesOfTheGeneratedInverseDynamics) {
  expect_matches_differences_of_the_inverse_dynamics<eomgen_models::cart_pole::Model>();
  expect_matches_differences_of_the_inverse_dynamics<eomgen_models::double_pendulum::Model>();
  expect_matches_differences_of_the_inverse_dynamics<eomgen_models::heavy_top::Model>();
  expect_matches_differences_of_the_inverse_dynamics<eomgen_models::spacecraft_panel::Model>();
}

TEST(InverseDynamicsDerivatives, WriteIntoBlocksOfACallersMatrix) {
  using Model = eomgen_models::double_pendulum::Model;
  const typename Model::template Parameters<double> p{};
  const Model::Vector<double> q(0.3, -0.4), qd(1.0, 0.5), qdd(-2.0, 1.5);
  const Model::Inputs<double> u = Model::Inputs<double>::Zero();
  Eigen::Matrix2d dq = Eigen::Matrix2d::Zero(), dqd = Eigen::Matrix2d::Zero();
  ASSERT_EQ(eomrt::inverse_dynamics_derivatives<Model>(p, 0.0, q, qd, qdd, u, dq, dqd), eomrt::DynamicsStatus::ok);
  Eigen::Matrix<double, 2, 5> stacked = Eigen::Matrix<double, 2, 5>::Constant(9.0);
  ASSERT_EQ(eomrt::inverse_dynamics_derivatives<Model>(p, 0.0, q, qd, qdd, u, stacked.leftCols<2>(),
                                                       stacked.rightCols<2>()),
            eomrt::DynamicsStatus::ok);
  EXPECT_EQ(Eigen::Matrix2d(stacked.leftCols<2>()), dq);
  EXPECT_EQ(Eigen::Matrix2d(stacked.rightCols<2>()), dqd);
  EXPECT_TRUE((stacked.col(2).array() == 9.0).all());
}

// tau and lambda of the generated inverse_dynamics of a constrained model
template <class Model>
struct Split {
  typename Model::template Vector<double> tau;
  Eigen::Matrix<double, Model::nc, 1> lambda;
};

template <class Model>
void expect_constrained_split_matches_differences() {
  constexpr int nq = Model::nq, nc = Model::nc, nu = Model::nu;
  using Vector = typename Model::template Vector<double>;
  const typename Model::template Parameters<double> p{};
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> value(-0.8, 0.8);
  for (int trial = 0; trial < 3; ++trial) {
    Vector q, qd, qdd;
    for (int k = 0; k < nq; ++k) q(k) = value(rng), qd(k) = 2 * value(rng), qdd(k) = 3 * value(rng);
    typename Model::template Inputs<double> u;
    for (int k = 0; k < nu; ++k) u(k) = value(rng);
    const double t = 0.2;
    Eigen::Matrix<double, nq, nq> dq, dqd;
    Eigen::Matrix<double, nc, nq> dl_q, dl_qd;
    ASSERT_EQ(eomrt::inverse_dynamics_derivatives<Model>(p, t, q, qd, qdd, u, dq, dqd, dl_q, dl_qd),
              eomrt::DynamicsStatus::ok);
    Eigen::Matrix<double, nq, nq> dq_alone, dqd_alone;
    ASSERT_EQ(eomrt::inverse_dynamics_derivatives<Model>(p, t, q, qd, qdd, u, dq_alone, dqd_alone),
              eomrt::DynamicsStatus::ok);
    EXPECT_EQ(dq, dq_alone);
    EXPECT_EQ(dqd, dqd_alone);
    const auto split = [&](const Vector& at_q, const Vector& at_qd) {
      Split<Model> s;
      Model::inverse_dynamics(t, at_q, at_qd, qdd, u, p, s.tau, s.lambda);
      return s;
    };
    Eigen::Matrix<double, nq, nq> fd_q, fd_qd;
    Eigen::Matrix<double, nc, nq> fdl_q, fdl_qd;
    for (int k = 0; k < nq; ++k) {
      const double h = 1e-6 * std::max(1.0, std::abs(q(k)));
      Vector plus = q, minus = q;
      plus(k) += h;
      minus(k) -= h;
      Split<Model> a = split(plus, qd), b = split(minus, qd);
      fd_q.col(k) = (a.tau - b.tau) / (2 * h);
      fdl_q.col(k) = (a.lambda - b.lambda) / (2 * h);
      const double g = 1e-6 * std::max(1.0, std::abs(qd(k)));
      plus = qd, minus = qd;
      plus(k) += g;
      minus(k) -= g;
      a = split(q, plus), b = split(q, minus);
      fd_qd.col(k) = (a.tau - b.tau) / (2 * g);
      fdl_qd.col(k) = (a.lambda - b.lambda) / (2 * g);
    }
    const auto near = [](const auto& x, const auto& y) {
      return (x - y).cwiseAbs().maxCoeff() <= 1e-6 * (1 + y.cwiseAbs().maxCoeff());
    };
    EXPECT_TRUE(near(dq, fd_q)) << Model::name << "\n" << dq << "\n\n" << fd_q;
    EXPECT_TRUE(near(dqd, fd_qd)) << Model::name << "\n" << dqd << "\n\n" << fd_qd;
    EXPECT_TRUE(near(dl_q, fdl_q)) << Model::name << "\n" << dl_q << "\n\n" << fdl_q;
    EXPECT_TRUE(near(dl_qd, fdl_qd)) << Model::name << "\n" << dl_qd << "\n\n" << fdl_qd;
  }
}

// the split's derivatives: the least tau's and lambda's, of a holonomic and a rolling model
TEST(InverseDynamicsDerivatives, ConstrainedSplitMatchesCentralDifferences) {
  expect_constrained_split_matches_differences<eomgen_models::cartesian_pendulum::Model>();
  expect_constrained_split_matches_differences<eomgen_models::rolling_coin::Model>();
}

}  // namespace
