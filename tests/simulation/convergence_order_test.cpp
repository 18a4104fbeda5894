// Measured convergence orders of the integrators on the double pendulum (a nonlinear shipped
// model), against a reference from Dormand-Prince at rtol 1e-13: error ratios for halved steps
// give order about 1 for Euler and 4 for RK4; for the adaptive Dormand-Prince the error falls
// as (number of steps)^-5.
#include <gtest/gtest.h>

#include <cmath>

#include "double_pendulum.hpp"
#include "simulation/simulation_helpers.hpp"

namespace eomrt::testing {
namespace {

using Model = eomgen_models::double_pendulum::Model;

State<Model> start() { return make_state<Model>({1.2, -0.5}, {0.0, 1.0}); }

State<Model> reference_end() {
  SimulationOptions<double> o = adaptive(1.0, 1e-13);
  o.adaptive.atol = 1e-15;
  const SimulationResult<Model, double> r = run<Model>(start(), o).result;
  EXPECT_EQ(r.status, SimulationStatus::ok);
  return r.x;
}

double fixed_step_error(Integrator method, double h, const State<Model>& reference) {
  SimulationOptions<double> o = fixed(method, 1.0, h);
  o.sample_interval = 0;
  const SimulationResult<Model, double> r = run<Model>(start(), o).result;
  EXPECT_EQ(r.status, SimulationStatus::ok);
  EXPECT_EQ(r.t, 1.0);
  return (r.x - reference).norm();
}

TEST(ConvergenceOrder, EulerIsFirstOrderAndRk4FourthOrder) {
  const State<Model> reference = reference_end();
  const double e1 = fixed_step_error(Integrator::euler, 1e-3, reference);
  const double e2 = fixed_step_error(Integrator::euler, 5e-4, reference);
  const double euler_order = std::log2(e1 / e2);
  EXPECT_NEAR(euler_order, 1.0, 0.1);

  const double r1 = fixed_step_error(Integrator::rk4, 0.02, reference);
  const double r2 = fixed_step_error(Integrator::rk4, 0.01, reference);
  const double r3 = fixed_step_error(Integrator::rk4, 0.005, reference);
  EXPECT_NEAR(std::log2(r1 / r2), 4.0, 0.25);
  EXPECT_NEAR(std::log2(r2 / r3), 4.0, 0.25);
  RecordProperty("euler_order", std::to_string(euler_order));
  RecordProperty("rk4_order", std::to_string(std::log2(r2 / r3)));
}

TEST(ConvergenceOrder, DormandPrinceErrorFallsWithTheFifthPowerOfTheStepCount) {
  const State<Model> reference = reference_end();
  std::vector<double> log_steps, log_errors;
  for (const double rtol : {1e-6, 1e-7, 1e-8, 1e-9, 1e-10}) {
    SimulationOptions<double> o = adaptive(1.0, rtol);
    o.adaptive.atol = rtol;
    o.sample_interval = 0;
    const SimulationResult<Model, double> r = run<Model>(start(), o).result;
    ASSERT_EQ(r.status, SimulationStatus::ok);
    log_steps.push_back(std::log(static_cast<double>(r.steps)));
    log_errors.push_back(std::log((r.x - reference).norm()));
  }
  // least-squares slope of log(error) against log(steps)
  const double n = static_cast<double>(log_steps.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < log_steps.size(); ++i) {
    sx += log_steps[i];
    sy += log_errors[i];
    sxx += log_steps[i] * log_steps[i];
    sxy += log_steps[i] * log_errors[i];
  }
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  EXPECT_NEAR(-slope, 5.0, 0.6);
  RecordProperty("dp5_order", std::to_string(-slope));
}

}  // namespace
}  // namespace eomrt::testing
