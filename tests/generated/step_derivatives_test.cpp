// eomrt::step_derivatives (step_derivatives.hpp) of the generated models with linearization
// terms, against independent references: central differences of the runtime's own rk_step
// driven by the forward dynamics (which knows nothing of derivatives), the runtime's step
// itself, Euler's closed form I + h A, and at an equilibrium RK4's stability polynomial in hA.
// Constrained models included: their right-hand side is the KKT accelerations on the full state.
#include "runtime/no_malloc.hpp"  // before Eigen

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "cart_pole.hpp"
#include "cartesian_pendulum.hpp"
#include "double_pendulum.hpp"
#include "eomrt/dynamics_kkt.hpp"
#include "eomrt/dynamics_unconstrained.hpp"
#include "eomrt/rk_fixed.hpp"
#include "eomrt/step_derivatives.hpp"
#include "heavy_top.hpp"
#include "rolling_coin.hpp"
#include "spacecraft_panel.hpp"

namespace {

template <class Model>
using State = typename eomrt::ModelTypes<Model, double>::State;
template <class Model>
using Inputs = typename eomrt::ModelTypes<Model, double>::Inputs;

/// x_next by the runtime's own rk_step, f = [qd; qdd] from the forward dynamics
template <class Model, std::size_t S>
State<Model> runtime_step(const eomrt::ButcherTableau<S>& tableau, double t, double h, const State<Model>& x,
                          const Inputs<Model>& u) {
  constexpr int nq = Model::nq;
  const typename Model::template Parameters<double> p{};
  eomrt::DynamicsWorkspace<Model, double> ws;
  const auto f = [&](double time, const State<Model>& state, State<Model>& dxdt) {
    const typename Model::template Vector<double> q = state.template head<nq>(), qd = state.template tail<nq>();
    eomrt::DynamicsStatus status;
    if constexpr (Model::nc == 0)
      status = eomrt::forward_dynamics_unconstrained<Model>(p, ws, time, q, qd, u);
    else
      status = eomrt::forward_dynamics_kkt<Model>(p, ws, time, q, qd, u);
    dxdt << qd, ws.qdd;
    return status == eomrt::DynamicsStatus::ok;
  };
  State<Model> next = x;
  eomrt::RkWorkspace<State<Model>, S> rk(2 * nq);
  EXPECT_TRUE(eomrt::rk_step(tableau, f, t, next, h, rk));
  return next;
}

/// a state away from every equilibrium: coordinates and rates from a fixed seed
template <class Model>
State<Model> generic_state(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> angle(-0.8, 0.8), rate(-1.5, 1.5);
  State<Model> x;
  for (int k = 0; k < Model::nq; ++k) x(k) = angle(rng), x(Model::nq + k) = rate(rng);
  return x;
}

template <class Model, std::size_t S>
void expect_matches_differences_of_the_step(const eomrt::ButcherTableau<S>& tableau, const char* method) {
  constexpr int nq = Model::nq, nu = Model::nu;
  const typename Model::template Parameters<double> p{};
  for (unsigned seed : {1u, 2u, 3u}) {
    const State<Model> x = generic_state<Model>(seed);
    Inputs<Model> u;
    for (int k = 0; k < nu; ++k) u(k) = 0.3 * (k + 1);
    const double t = 0.1, h = 0.02;
    eomrt::StepDerivativesWorkspace<Model, S, double> ws;
    ASSERT_EQ(eomrt::step_derivatives<Model>(tableau, p, ws, t, h, x, u), eomrt::DynamicsStatus::ok)
        << Model::name << " " << method;
    // the step itself is the integrator's
    const State<Model> next = runtime_step<Model>(tableau, t, h, x, u);
    EXPECT_LE((ws.x_next - next).cwiseAbs().maxCoeff(), 1e-13 * (1 + next.cwiseAbs().maxCoeff()))
        << Model::name << " " << method;
    // central differences of the step in each entry of x and u
    Eigen::MatrixXd Phi(2 * nq, 2 * nq), Gamma(2 * nq, nu);
    for (int k = 0; k < 2 * nq; ++k) {
      const double d = 1e-6 * std::max(1.0, std::abs(x(k)));
      State<Model> plus = x, minus = x;
      plus(k) += d;
      minus(k) -= d;
      Phi.col(k) = (runtime_step<Model>(tableau, t, h, plus, u) - runtime_step<Model>(tableau, t, h, minus, u)) / (2 * d);
    }
    for (int k = 0; k < nu; ++k) {
      const double d = 1e-6 * std::max(1.0, std::abs(u(k)));
      Inputs<Model> plus = u, minus = u;
      plus(k) += d;
      minus(k) -= d;
      Gamma.col(k) = (runtime_step<Model>(tableau, t, h, x, plus) - runtime_step<Model>(tableau, t, h, x, minus)) / (2 * d);
    }
    const double scale_phi = 1 + Phi.cwiseAbs().maxCoeff();
    EXPECT_LE((ws.Phi - Phi).cwiseAbs().maxCoeff(), 1e-6 * scale_phi) << Model::name << " " << method << "\n"
                                                                       << ws.Phi << "\n\n" << Phi;
    if constexpr (nu > 0) {
      const double scale_gamma = 1e-3 + Gamma.cwiseAbs().maxCoeff();
      EXPECT_LE((ws.Gamma - Gamma).cwiseAbs().maxCoeff(), 1e-6 * scale_gamma) << Model::name << " " << method;
    }
  }
}

template <std::size_t S>
void expect_every_model_matches(const eomrt::ButcherTableau<S>& tableau, const char* method) {
  expect_matches_differences_of_the_step<eomgen_models::cart_pole::Model>(tableau, method);
  expect_matches_differences_of_the_step<eomgen_models::double_pendulum::Model>(tableau, method);
  expect_matches_differences_of_the_step<eomgen_models::heavy_top::Model>(tableau, method);
  expect_matches_differences_of_the_step<eomgen_models::spacecraft_panel::Model>(tableau, method);
  expect_matches_differences_of_the_step<eomgen_models::cartesian_pendulum::Model>(tableau, method);
  expect_matches_differences_of_the_step<eomgen_models::rolling_coin::Model>(tableau, method);
}

TEST(StepDerivatives, EulerMatchesCentralDifferencesOfTheRuntimesStep) {
  expect_every_model_matches(eomrt::euler, "euler");
}

TEST(StepDerivatives, Rk4MatchesCentralDifferencesOfTheRuntimesStep) {
  expect_every_model_matches(eomrt::rk4, "rk4");
}

TEST(StepDerivatives, EulerIsTheIdentityPlusTheStepTimesTheLinearization) {
  using Model = eomgen_models::cart_pole::Model;
  const typename Model::template Parameters<double> p{};
  const State<Model> x = generic_state<Model>(4);
  const Inputs<Model> u = Inputs<Model>::Constant(0.7);
  const double h = 0.01;
  eomrt::StepDerivativesWorkspace<Model, 1, double> ws;
  ASSERT_EQ(eomrt::step_derivatives<Model>(eomrt::euler, p, ws, 0.0, h, x, u), eomrt::DynamicsStatus::ok);
  eomrt::LinearizationWorkspace<Model, double> lin;
  ASSERT_EQ(eomrt::linearization<Model>(p, lin, 0.0, x.head<Model::nq>().eval(), x.tail<Model::nq>().eval(), u),
            eomrt::DynamicsStatus::ok);
  using StateMatrix = eomrt::StateMatrix<double, Model::nq>;
  EXPECT_LE((ws.Phi - (StateMatrix::Identity() + h * lin.A)).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LE((ws.Gamma - h * lin.B).cwiseAbs().maxCoeff(), 1e-15);
}

// At an equilibrium every stage sits at the point, so each A_i is the same A and RK4's Phi is
// its stability polynomial: I + hA + (hA)^2/2 + (hA)^3/6 + (hA)^4/24, and
// Gamma = h (I + hA/2 + (hA)^2/6 + (hA)^3/24) B.
TEST(StepDerivatives, Rk4AtAnEquilibriumIsTheStabilityPolynomialOfTheLinearization) {
  using Model = eomgen_models::cart_pole::Model;
  const typename Model::template Parameters<double> p{};
  const State<Model> x = State<Model>::Zero();  // the pole upright, at rest: an equilibrium
  const Inputs<Model> u = Inputs<Model>::Zero();
  const double h = 0.05;
  eomrt::StepDerivativesWorkspace<Model, 4, double> ws;
  ASSERT_EQ(eomrt::step_derivatives<Model>(eomrt::rk4, p, ws, 0.0, h, x, u), eomrt::DynamicsStatus::ok);
  eomrt::LinearizationWorkspace<Model, double> lin;
  ASSERT_EQ(eomrt::linearization<Model>(p, lin, 0.0, x.head<Model::nq>().eval(), x.tail<Model::nq>().eval(), u),
            eomrt::DynamicsStatus::ok);
  using StateMatrix = eomrt::StateMatrix<double, Model::nq>;
  const StateMatrix I = StateMatrix::Identity(), hA = h * lin.A;
  const StateMatrix expected_phi = I + hA + hA * hA / 2 + hA * hA * hA / 6 + hA * hA * hA * hA / 24;
  const auto expected_gamma = (h * (I + hA / 2 + hA * hA / 6 + hA * hA * hA / 24) * lin.B).eval();
  EXPECT_LE((ws.Phi - expected_phi).cwiseAbs().maxCoeff(), 1e-14 * (1 + expected_phi.cwiseAbs().maxCoeff()));
  EXPECT_LE((ws.Gamma - expected_gamma).cwiseAbs().maxCoeff(), 1e-14 * (1 + expected_gamma.cwiseAbs().maxCoeff()));
  EXPECT_EQ(ws.x_next, x);
}

TEST(StepDerivatives, AllocatesNothing) {
  using Model = eomgen_models::rolling_coin::Model;
  const typename Model::template Parameters<double> p{};
  const State<Model> x = generic_state<Model>(5);
  const Inputs<Model> u = Inputs<Model>::Zero();
  eomrt::StepDerivativesWorkspace<Model, 4, double> ws;
  eigen_assert_failures = 0;
  Eigen::internal::set_is_malloc_allowed(false);
  const auto status = eomrt::step_derivatives<Model>(eomrt::rk4, p, ws, 0.0, 0.01, x, u);
  Eigen::internal::set_is_malloc_allowed(true);
  EXPECT_EQ(status, eomrt::DynamicsStatus::ok);
  EXPECT_EQ(eigen_assert_failures, 0);
}

TEST(StepDerivatives, ASingularStageIsReported) {
  // the Cartesian pendulum's bob on its pivot: no constraint has a direction, the KKT matrix is
  // singular at the first stage
  using Model = eomgen_models::cartesian_pendulum::Model;
  const typename Model::template Parameters<double> p{};
  eomrt::StepDerivativesWorkspace<Model, 4, double> ws;
  const auto status =
      eomrt::step_derivatives<Model>(eomrt::rk4, p, ws, 0.0, 0.01, State<Model>::Zero(), Inputs<Model>::Zero());
  EXPECT_EQ(status, eomrt::DynamicsStatus::singular_kkt_matrix);
}

}  // namespace
