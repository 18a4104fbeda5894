// A simulation compiled with only the methods it runs (eomrt::simulate_with, OnlyMethods, what
// `eomgen simulate` builds) gives the bits simulate() gives, and refuses the methods it lacks
// instead of running another.
#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "cartesian_pendulum.hpp"
#include "simulation/simulation_helpers.hpp"

namespace eomrt::testing {
namespace {

using Pendulum = eomgen_models::cartesian_pendulum::Model;
using Rk4WithKkt = OnlyMethods<Integrator::rk4, ConstraintSolver::kkt, Stabilization::projection>;

State<Pendulum> start() { return make_state<Pendulum>({0.4330127018922193, -0.25}, {0.5, 0.8660254037844386}); }

TEST(OnlyMethods, GivesTheBitsOfTheFullSimulation) {
  SimulationOptions<double> o = fixed(Integrator::rk4, 2.0, 1e-3);
  o.solver = ConstraintSolver::kkt;
  o.stabilization = Stabilization::projection;
  std::vector<State<Pendulum>> only, all;
  const auto keep = [](std::vector<State<Pendulum>>& into) {
    return [&into](const Sample<Pendulum, double>& s) {
      State<Pendulum> x;
      x << s.q, s.qd;
      into.push_back(x);
    };
  };
  const auto a = simulate_with<Rk4WithKkt, Pendulum>({}, start(), o, ZeroInputs{}, keep(only));
  const auto b = simulate<Pendulum>({}, start(), o, ZeroInputs{}, keep(all));
  ASSERT_EQ(a.status, SimulationStatus::ok);
  ASSERT_EQ(b.status, SimulationStatus::ok);
  ASSERT_EQ(only.size(), all.size());
  for (std::size_t k = 0; k < only.size(); ++k) EXPECT_EQ(only[k], all[k]) << "sample " << k;
}

TEST(OnlyMethods, RefusesAMethodItWasNotCompiledWith) {
  SimulationOptions<double> o = adaptive(1.0, 1e-8);  // dp5
  EXPECT_THROW((simulate_with<Rk4WithKkt, Pendulum>({}, start(), o)), std::invalid_argument);
  o = fixed(Integrator::rk4, 1.0, 1e-3);
  o.solver = ConstraintSolver::null_space;
  EXPECT_THROW((simulate_with<Rk4WithKkt, Pendulum>({}, start(), o)), std::invalid_argument);
  o.solver = ConstraintSolver::kkt;
  o.stabilization = Stabilization::baumgarte;
  EXPECT_THROW((simulate_with<Rk4WithKkt, Pendulum>({}, start(), o)), std::invalid_argument);
}

}  // namespace
}  // namespace eomrt::testing
