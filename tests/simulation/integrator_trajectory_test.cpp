// Trajectories of shipped models under each integrator, recorded from simulate() before the
// integrators became a registry and the adaptive stepper a generic embedded-pair stepper: the
// same method must still take the same steps and end in the same state.
//
// The end states are compared to 1e-10 rather than bit for bit, so that a compiler that
// contracts a*b+c into one rounding still passes; a change of the method (a coefficient, the
// controller's exponent, the dense output) moves them by about the tolerance, 1e-6, instead.
// The step counts are compared exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "double_pendulum.hpp"
#include "rolling_coin.hpp"
#include "simulation/simulation_helpers.hpp"

namespace eomrt::testing {
namespace {

namespace m = eomgen_models;

struct Recorded {
  std::vector<double> x;  // the state at t_end
  long long steps, rejected_steps, evaluations;
  std::size_t samples;
};

template <class Model>
void expect_recorded(const State<Model>& x0, const SimulationOptions<double>& options, const Recorded& recorded) {
  const Trajectory<Model> tr = run<Model>(x0, options);
  ASSERT_EQ(tr.result.status, SimulationStatus::ok) << to_string(tr.result.status);
  EXPECT_EQ(tr.result.t, options.t_end);
  EXPECT_EQ(tr.result.steps, recorded.steps);
  EXPECT_EQ(tr.result.rejected_steps, recorded.rejected_steps);
  EXPECT_EQ(tr.result.evaluations, recorded.evaluations);
  EXPECT_EQ(tr.t.size(), recorded.samples);
  EXPECT_EQ(static_cast<std::size_t>(tr.result.x.size()), recorded.x.size());
  for (std::size_t i = 0; i < recorded.x.size() && i < static_cast<std::size_t>(tr.result.x.size()); ++i)
    EXPECT_NEAR(tr.result.x(static_cast<Eigen::Index>(i)), recorded.x[i], 1e-10 * std::max(1.0, std::abs(recorded.x[i])))
        << "x(" << i << ")";
  if (!::testing::Test::HasFailure()) return;
  // what this run recorded, in the form of the calls below
  std::printf("recorded: {{");
  for (Eigen::Index i = 0; i < tr.result.x.size(); ++i) std::printf("%s%.17g", i ? ", " : "", tr.result.x(i));
  std::printf("}, %lld, %lld, %lld, %zu}\n", tr.result.steps, tr.result.rejected_steps, tr.result.evaluations,
              tr.t.size());
}

SimulationOptions<double> with(Integrator method, double t_end, double step) {
  SimulationOptions<double> o = fixed(method, t_end, step);
  o.adaptive.rtol = 1e-6;
  o.adaptive.atol = 1e-8;
  return o;
}

State<m::double_pendulum::Model> swinging() { return make_state<m::double_pendulum::Model>({1.8, -0.6}, {0.5, 2.0}); }

// rolling and leaning, so the projection onto the constraints acts after every step
State<m::rolling_coin::Model> rolling() {
  return make_state<m::rolling_coin::Model>({0.0, 0.0, 0.0, 0.3, 0.0}, {0.0, 0.0, 2.0, 0.0, 5.0});
}

TEST(IntegratorTrajectory, DoublePendulumUnderEuler) {
  expect_recorded<m::double_pendulum::Model>(
      swinging(), with(Integrator::euler, 1.0, 1e-3),
      {{-1.5137874642344906, -0.51103657325015872, -2.5831466334213342, 4.0448768812799276}, 1000, 0, 1000, 101});
}

// a step of 3 ms does not divide the 10 ms sample interval: each interval takes 4 steps
TEST(IntegratorTrajectory, DoublePendulumUnderRk4) {
  expect_recorded<m::double_pendulum::Model>(
      swinging(), with(Integrator::rk4, 2.0, 3e-3),
      {{1.3552703749336348, 0.40915621291769072, 2.9816934796828507, -0.92056301433574161}, 800, 0, 3200, 201});
}

// sampled after every step, not on a grid
TEST(IntegratorTrajectory, DoublePendulumUnderDormandPrince) {
  SimulationOptions<double> o = with(Integrator::dormand_prince, 2.0, 0);
  o.sample_interval = 0;
  expect_recorded<m::double_pendulum::Model>(
      swinging(), o,
      {{1.3552681198759766, 0.40916718510619293, 2.9816893985829829, -0.92053110662469129}, 73, 12, 512, 74});
}

// samples from the dense output, and the end of every step projected and restarted
TEST(IntegratorTrajectory, RollingCoinUnderDormandPrinceWithProjection) {
  expect_recorded<m::rolling_coin::Model>(
      rolling(), with(Integrator::dormand_prince, 2.0, 0),
      {{0.022643861602314155, -0.056906050019167535, 63.487555065764511, 0.40709565327201741, 70.295854955430997,
        -0.024944402544076334, -0.093756098597776588, 3.2339184504342042, -6.4948235227442428, 5.8621539312879092},
       495,
       157,
       4409,
       201});
}

}  // namespace
}  // namespace eomrt::testing
