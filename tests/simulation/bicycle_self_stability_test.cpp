// The generated bicycle, integrated nonlinearly, against its linearization: a small lean
// rate at speed v grows or dies away at the rate of the eigenvalue the sweep reports. Below
// the weave speed the weave oscillation grows; between the weave and capsize speeds the
// bicycle rights itself at the slow capsize rate; above the capsize speed it falls over,
// slowly. Two formulations meet here: the generated code's accelerations (KKT solve of the
// full model) and the symbolic derivatives reduced to the tangent space.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "eomgen/derivation/linearization.hpp"
#include "eomgen/derivation/model_equations.hpp"
#include "eomgen/language/model_file.hpp"
#include "simulation/simulation_helpers.hpp"
#include "support/source_dir.hpp"
#include "whipple_bicycle.hpp"

namespace eomrt::testing {
namespace {

using Bicycle = eomgen_models::whipple_bicycle::Model;
constexpr int phi = 3;  // coordinate indices, in the model's order x, y, psi, phi, ...

/// the rightmost eigenvalue of the reduced linear model at forward speed v
std::complex<double> rightmost_eigenvalue(double v) {
  const eomgen::Model model = eomgen::load_model(eomgen::testing::shipped_model_path("whipple_bicycle"));
  const eomgen::ModelEquations eom = eomgen::derive_equations(model);
  eomgen::LinearizeOptions drop;
  drop.drop_cyclic = true;
  const eomgen::LinearModel lin = eomgen::linearize(model, eom, eomgen::linearize_symbolic(model, eom), {{"x_dot", v}}, drop);
  return eomgen::assess_stability(lin.A).eigenvalues(0);  // sorted by real part, descending
}

/// upright at speed v with a small lean rate (the constraints fix the other rates: the
/// simulation projects the initial state onto them)
Trajectory<Bicycle> ride(double v, double lean_rate, double seconds) {
  State<Bicycle> x0 = State<Bicycle>::Zero();
  const double rR = 0.3, rF = 0.35;
  x0(Bicycle::nq + 0) = v;         // x_dot
  x0(Bicycle::nq + 5) = -v / rR;   // theta_r_dot
  x0(Bicycle::nq + 7) = -v / rF;   // theta_f_dot
  x0(Bicycle::nq + phi) = lean_rate;
  SimulationOptions<double> o = adaptive(seconds, 1e-11);
  o.sample_interval = 0.005;
  return run<Bicycle>(x0, o);
}

/// max |phi| over the samples in [from, to)
double lean_amplitude(const Trajectory<Bicycle>& tr, double from, double to) {
  double largest = 0;
  for (std::size_t k = 0; k < tr.t.size(); ++k)
    if (tr.t[k] >= from && tr.t[k] < to) largest = std::max(largest, std::abs(tr.x[k](phi)));
  return largest;
}

/// phi at the first sample at or after t
double lean_at(const Trajectory<Bicycle>& tr, double t) {
  std::size_t k = 0;
  while (k + 1 < tr.t.size() && tr.t[k] < t) ++k;
  return tr.x[k](phi);
}

TEST(BicycleSelfStability, BelowTheWeaveSpeedTheWeaveGrowsAtItsEigenvaluesRate) {
  const double v = 3;
  const std::complex<double> weave = rightmost_eigenvalue(v);  // 1.707 +- 2.316i
  ASSERT_GT(weave.real(), 0);
  ASSERT_GT(std::abs(weave.imag()), 0);
  const double period = 2 * M_PI / std::abs(weave.imag());
  // small enough to stay linear for three periods, over which it grows a millionfold
  const Trajectory<Bicycle> tr = ride(v, 1e-7, 3 * period);
  ASSERT_EQ(tr.result.status, SimulationStatus::ok);
  // one period apart, once the stable modes are gone; still far from falling over
  const double late = lean_amplitude(tr, 2 * period, 3 * period), early = lean_amplitude(tr, period, 2 * period);
  EXPECT_LT(late, 0.1);
  EXPECT_NEAR(std::log(late / early) / period, weave.real(), 0.01 * weave.real());
}

TEST(BicycleSelfStability, BetweenTheWeaveAndCapsizeSpeedsItRightsItselfAtTheCapsizeRate) {
  const double v = 5;
  const std::complex<double> capsize = rightmost_eigenvalue(v);  // -0.3229, real
  ASSERT_LT(capsize.real(), 0);
  ASSERT_EQ(capsize.imag(), 0);
  const Trajectory<Bicycle> tr = ride(v, 1e-4, 26);
  ASSERT_EQ(tr.result.status, SimulationStatus::ok);
  // the weave (-0.775 +- 4.46i) has died away against the capsize mode by t = 20 s
  EXPECT_NEAR(std::log(lean_at(tr, 26) / lean_at(tr, 20)) / 6, capsize.real(), 0.01 * std::abs(capsize.real()));
  EXPECT_LT(lean_amplitude(tr, 20, 26), 0.01 * lean_amplitude(tr, 0, 2));
}

TEST(BicycleSelfStability, AboveTheCapsizeSpeedItFallsOverSlowlyWithoutOscillating) {
  const double v = 7;
  const std::complex<double> capsize = rightmost_eigenvalue(v);  // +0.1027, real
  ASSERT_GT(capsize.real(), 0);
  ASSERT_EQ(capsize.imag(), 0);
  const Trajectory<Bicycle> tr = ride(v, 1e-4, 16);
  ASSERT_EQ(tr.result.status, SimulationStatus::ok);
  EXPECT_NEAR(std::log(lean_at(tr, 16) / lean_at(tr, 10)) / 6, capsize.real(), 0.01 * capsize.real());
}

}  // namespace
}  // namespace eomrt::testing
