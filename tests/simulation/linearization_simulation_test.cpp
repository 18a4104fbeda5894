// The linear model against the nonlinear one: a small perturbation of an equilibrium,
// simulated both ways, must agree to 1e-3 of the perturbation's size over a few seconds
// (the neglected terms are of second order in it).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "cart_pole.hpp"
#include "double_pendulum.hpp"
#include "eomgen/derivation/linearization.hpp"
#include "eomgen/derivation/model_equations.hpp"
#include "eomgen/language/model_file.hpp"
#include "simulation/simulation_helpers.hpp"
#include "support/source_dir.hpp"

namespace eomrt::testing {
namespace {


eomgen::LinearModel linear_model(const std::string& name, const eomgen::NamedValues& point) {
  const eomgen::Model model =
      eomgen::load_model(eomgen::testing::shipped_model_path(name));
  const eomgen::ModelEquations eom = eomgen::derive_equations(model);
  return eomgen::linearize(model, eom, eomgen::linearize_symbolic(model, eom), point);
}

/// dx' = A dx + B du(t) from dx0, sampled on `grid`
template <class Input>
std::vector<Eigen::VectorXd> simulate_linear(const eomgen::LinearModel& lin, const Eigen::VectorXd& dx0,
                                             const std::vector<double>& grid, Input du) {
  std::vector<Eigen::VectorXd> out;
  AdaptiveOptions<double> o;
  o.rtol = 1e-12;
  o.atol = 1e-18;
  const auto f = [&](double t, const Eigen::VectorXd& x, Eigen::VectorXd& dxdt) {
    dxdt = lin.A * x + lin.B * du(t);
  };
  const auto result = integrate_adaptive(dormand_prince54, f, 0.0, dx0, grid, o, [&](double, const Eigen::VectorXd& x) { out.push_back(x); });
  EXPECT_EQ(result.status, AdaptiveStatus::ok);
  return out;
}

template <class Model, class Input>
double worst_relative_gap(const eomgen::LinearModel& lin, const State<Model>& equilibrium, const State<Model>& dx0,
                          Input du, double seconds) {
  SimulationOptions<double> o = adaptive(seconds, 1e-12);
  o.adaptive.atol = 1e-18;
  o.sample_interval = 0.05;
  std::vector<State<Model>> nonlinear;
  const auto input = [&](double t, const State<Model>&, auto& u) {
    const Eigen::VectorXd v = du(t);
    for (int i = 0; i < u.size(); ++i) u(i) = v(i);
  };
  const auto r = simulate<Model>(Parameters<Model>{}, equilibrium + dx0, o, input,
                                 [&](const Sample<Model, double>& s) {
                                   State<Model> x;
                                   x << s.q, s.qd;
                                   nonlinear.push_back(x);
                                 });
  EXPECT_EQ(r.status, SimulationStatus::ok);
  std::vector<double> grid;
  for (std::size_t k = 0; k < nonlinear.size(); ++k) grid.push_back(std::min(0.05 * static_cast<double>(k), seconds));
  const std::vector<Eigen::VectorXd> linear = simulate_linear(lin, Eigen::VectorXd(dx0), grid, du);
  EXPECT_EQ(linear.size(), nonlinear.size());
  double worst = 0;
  for (std::size_t k = 0; k < std::min(linear.size(), nonlinear.size()); ++k)
    worst = std::max(worst, (nonlinear[k] - equilibrium - linear[k]).cwiseAbs().maxCoeff());
  return worst / dx0.cwiseAbs().maxCoeff();
}

TEST(LinearVersusNonlinear, DoublePendulumNearItsHangingEquilibrium) {
  using Model = eomgen_models::double_pendulum::Model;
  const eomgen::LinearModel lin = linear_model("double_pendulum", {});
  const double eps = 1e-5;
  const State<Model> dx0 = eps * make_state<Model>({0.3, -0.2}, {0.1, 0.4});
  const auto no_input = [](double) { return Eigen::VectorXd::Zero(0); };
  const double gap = worst_relative_gap<Model>(lin, State<Model>::Zero(), dx0, no_input, 4.0);
  EXPECT_LT(gap, 1e-3);
  RecordProperty("relative_gap", ::testing::PrintToString(gap));
}

// the hanging cart-pole driven by a small force: B carries the input into the linear model
TEST(LinearVersusNonlinear, CartPoleHangingDrivenByASmallForce) {
  using Model = eomgen_models::cart_pole::Model;
  const eomgen::LinearModel lin = linear_model("cart_pole", {{"theta", M_PI}});
  const double eps = 1e-5;
  const State<Model> equilibrium = make_state<Model>({0.0, M_PI}, {0.0, 0.0});
  const State<Model> dx0 = eps * make_state<Model>({0.2, 0.5}, {-0.3, 0.1});
  const auto push = [eps](double t) {
    Eigen::VectorXd u(1);
    u << eps * std::sin(3 * t);
    return u;
  };
  const double gap = worst_relative_gap<Model>(lin, equilibrium, dx0, push, 4.0);
  EXPECT_LT(gap, 1e-3);
  RecordProperty("relative_gap", ::testing::PrintToString(gap));
}

}  // namespace
}  // namespace eomrt::testing
