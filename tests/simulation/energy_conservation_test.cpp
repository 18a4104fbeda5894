// Energy of the conservative shipped models over 10 s of Dormand-Prince at rtol 1e-10:
// |(T+V)(t) - (T+V)(0)| / |(T+V)(0)| < 1e-8. Constrained models run with projection (the
// default), and the damped spring-mass-damper loses exactly the energy its damper dissipates.
#include <gtest/gtest.h>

#include "cart_pole.hpp"
#include "cartesian_pendulum.hpp"
#include "double_pendulum.hpp"
#include "four_bar.hpp"
#include "heavy_top.hpp"
#include "knife_edge.hpp"
#include "planar_3rrr.hpp"
#include "planar_chain.hpp"
#include "quaternion_rigid_body.hpp"
#include "rolling_coin.hpp"
#include "simple_pendulum.hpp"
#include "simulation/simulation_helpers.hpp"
#include "spacecraft_panel.hpp"
#include "spherical_pendulum.hpp"
#include "spring_mass_damper.hpp"
#include "universal_chain.hpp"

namespace eomrt::testing {
namespace {

namespace m = eomgen_models;

constexpr double kEnergyTolerance = 1e-8;

template <class Model>
void expect_energy_conserved(const State<Model>& x0) {
  SCOPED_TRACE(Model::name);
  const Trajectory<Model> tr = run<Model>(x0, adaptive(10.0, 1e-10));
  ASSERT_EQ(tr.result.status, SimulationStatus::ok) << to_string(tr.result.status);
  EXPECT_EQ(tr.t.back(), 10.0);
  EXPECT_EQ(tr.t.size(), 1001u);
  EXPECT_LT(tr.relative_energy_drift(), kEnergyTolerance);
  // the motion is not trivial: the state moved by much more than the tolerance
  EXPECT_GT((tr.x.back() - tr.x.front()).norm(), 0.1);
}

TEST(EnergyConservation, SimplePendulumSwingingWide) {
  expect_energy_conserved<m::simple_pendulum::Model>(make_state<m::simple_pendulum::Model>({2.5}, {0.0}));
}

TEST(EnergyConservation, DoublePendulumInChaoticMotion) {
  expect_energy_conserved<m::double_pendulum::Model>(
      make_state<m::double_pendulum::Model>({1.8, -0.6}, {0.5, 2.0}));
}

TEST(EnergyConservation, SphericalPendulumOffThePoles) {
  expect_energy_conserved<m::spherical_pendulum::Model>(
      make_state<m::spherical_pendulum::Model>({1.0, 0.0}, {0.0, 2.5}));
}

TEST(EnergyConservation, HeavyTopNutating) {
  expect_energy_conserved<m::heavy_top::Model>(
      make_state<m::heavy_top::Model>({0.0, 0.4, 0.0}, {1.0, 0.0, 80.0}));
}

TEST(EnergyConservation, CartPoleWithoutInput) {
  expect_energy_conserved<m::cart_pole::Model>(make_state<m::cart_pole::Model>({0.0, 2.8}, {0.3, 0.0}));
}

TEST(EnergyConservation, SpacecraftPanelFlapping) {
  expect_energy_conserved<m::spacecraft_panel::Model>(
      make_state<m::spacecraft_panel::Model>({0.0, 0.5}, {1.0, 0.2}));
}

TEST(EnergyConservation, PlanarChainOfFourRods) {
  expect_energy_conserved<m::planar_chain::Model>(
      make_state<m::planar_chain::Model>({1.2, -0.4, 0.3, 0.8}, {0.0, 0.5, -1.0, 0.0}));
}

TEST(EnergyConservation, UniversalChainOfThreeRods) {
  expect_energy_conserved<m::universal_chain::Model>(make_state<m::universal_chain::Model>(
      {0.6, -0.3, 0.2, 0.5, -0.4, 0.1}, {0.0, 1.0, 0.5, 0.0, -0.5, 0.3}));
}

TEST(EnergyConservation, CartesianPendulumWithProjection) {
  // on the circle of radius l = 0.5 at 60 degrees, moving tangentially
  expect_energy_conserved<m::cartesian_pendulum::Model>(
      make_state<m::cartesian_pendulum::Model>({0.4330127018922193, -0.25}, {0.5, 0.8660254037844386}));
}

TEST(EnergyConservation, FourBarCrankTurningThrough) {
  // assembled on the open branch (tests/derivation_references/closed_loop_models_test.cpp's first
  // state), no torque: the crank swings through more than a turn under gravity
  expect_energy_conserved<m::four_bar::Model>(make_state<m::four_bar::Model>(
      {0.3, 0.8444960910563463, 1.813260085372611}, {2.0, -0.6921771811276309, -0.4189886634661008}));
}

TEST(EnergyConservation, Planar3RrrPlatformFallingThroughItsWorkspace) {
  // assembled and at rest (closed_loop_models_test.cpp's third state), no torques: the platform
  // falls and swings, the elbows passing through straight (beta = 0), where Xi keeps its rank
  expect_energy_conserved<m::planar_3rrr::Model>(make_state<m::planar_3rrr::Model>(
      {0.7341278655403614, -3.7418712012219215, -1.4282174485488925, 1.5107848490866023, 1.8173833891898987,
       1.8527361668932327, 0.0, 0.05, 0.3},
      {0, 0, 0, 0, 0, 0, 0, 0, 0}));
}

TEST(EnergyConservation, QuaternionRigidBodyTumbling) {
  // unit quaternion; the rates are projected onto q . qd = 0 (an intermediate-axis tumble)
  expect_energy_conserved<m::quaternion_rigid_body::Model>(
      make_state<m::quaternion_rigid_body::Model>({0.1, 0.2, 0.3, 0.9273618495495703}, {0.2, 0.5, 0.1, -0.1509}));
}

TEST(EnergyConservation, KnifeEdgeCoasting) {
  expect_energy_conserved<m::knife_edge::Model>(
      make_state<m::knife_edge::Model>({0.0, 0.0, 0.3}, {0.9553364891256060, 0.2955202066613395, 0.7}));
}

TEST(EnergyConservation, RollingCoinRollingAndLeaning) {
  // rates that roll without slip follow from the projection of the initial state
  expect_energy_conserved<m::rolling_coin::Model>(
      make_state<m::rolling_coin::Model>({0.0, 0.0, 0.0, 0.2, 0.0}, {0.0, -0.3, 1.0, 0.0, 25.0}));
}

// Example A.21 of the notes: d(T + V)/dt = -d qd^2, so the energy lost up to t is the integral
// of d qd^2, accumulated here with the trapezoidal rule on a fine grid
TEST(EnergyConservation, SpringMassDamperLosesWhatTheDamperDissipates) {
  using Model = m::spring_mass_damper::Model;
  SimulationOptions<double> o = adaptive(10.0, 1e-11);
  o.sample_interval = 1e-4;
  const Parameters<Model> p;
  const Trajectory<Model> tr = run<Model>(make_state<Model>({0.4}, {0.0}), o, p);
  ASSERT_EQ(tr.result.status, SimulationStatus::ok);
  double dissipated = 0;
  for (std::size_t k = 1; k < tr.t.size(); ++k) {
    const double a = tr.x[k - 1](1), b = tr.x[k](1);
    dissipated += 0.5 * (tr.t[k] - tr.t[k - 1]) * p.d * (a * a + b * b);
  }
  const double lost = tr.energy.front() - tr.energy.back();
  EXPECT_GT(lost, 0.5 * tr.energy.front());  // the damper took most of it
  EXPECT_NEAR(lost, dissipated, 1e-6 * tr.energy.front());
}

}  // namespace
}  // namespace eomrt::testing
