// Tests for rk_adaptive.hpp with the Dormand-Prince 5(4) pair: error control against exact
// solutions, measured orders, rejections, dense output, landing on grid and end times, every
// status, no allocation.

#include "runtime/no_malloc.hpp"  // first: it configures Eigen

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "eomrt/eomrt.hpp"
#include "runtime/scalar_types.hpp"
#include "support/expect_throw.hpp"

namespace eomrt {
namespace {

using testing::ScalarName;
using testing::Scalars;

template <typename Scalar>
using Vector2 = Eigen::Matrix<Scalar, 2, 1>;
template <typename Scalar>
using Vector4 = Eigen::Matrix<Scalar, 4, 1>;
template <typename Vector>
using Workspace = AdaptiveWorkspace<Vector, dormand_prince54.stages>;

// harmonic oscillator q'' = -q from q = 1, qd = 0: exact x(t) = [cos t; -sin t]
const auto oscillator = [](auto, const auto& x, auto& dxdt) { dxdt << x(1), -x(0); };

template <typename Scalar>
Vector2<Scalar> oscillator_exact(Scalar t) {
  using std::cos;
  using std::sin;
  return Vector2<Scalar>(cos(t), -sin(t));
}

// Kepler two-body problem x = [q; v], q'' = -q / |q|^3: with a = 1 the period is 2 pi
const auto kepler = [](auto, const auto& x, auto& dxdt) {
  using std::sqrt;
  const auto r2 = x(0) * x(0) + x(1) * x(1);
  const auto r3 = r2 * sqrt(r2);
  dxdt << x(2), x(3), -x(0) / r3, -x(1) / r3;
};

// exact orbit of eccentricity e from the pericenter at t = 0, by Kepler's equation t = E - e sin E
template <typename Scalar>
Vector4<Scalar> kepler_exact(Scalar e, Scalar t) {
  using std::abs;
  using std::cos;
  using std::sin;
  using std::sqrt;
  Scalar E = t;
  for (int i = 0; i < 50; ++i) {
    const Scalar dE = (E - e * sin(E) - t) / (1 - e * cos(E));
    E -= dE;
    if (abs(dE) <= std::numeric_limits<Scalar>::epsilon()) break;
  }
  const Scalar w = sqrt(1 - e * e), rdot = 1 - e * cos(E);
  return Vector4<Scalar>(cos(E) - e, w * sin(E), -sin(E) / rdot, w * cos(E) / rdot);
}

template <typename Scalar>
Scalar kepler_energy(const Vector4<Scalar>& x) {
  using std::sqrt;
  return (x(2) * x(2) + x(3) * x(3)) / 2 - 1 / sqrt(x(0) * x(0) + x(1) * x(1));
}

AdaptiveOptions<double> tolerances(double rtol, double atol) {
  AdaptiveOptions<double> o;
  o.rtol = rtol;
  o.atol = atol;
  return o;
}

// least-squares slope of log(y) over log(x)
double log_log_slope(const std::vector<double>& x, const std::vector<double>& y) {
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < x.size(); ++i) mx += std::log(x[i]), my += std::log(y[i]);
  mx /= x.size(), my /= y.size();
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxy += (std::log(x[i]) - mx) * (std::log(y[i]) - my);
    sxx += (std::log(x[i]) - mx) * (std::log(x[i]) - mx);
  }
  return sxy / sxx;
}

TEST(Convergence, GlobalErrorIsProportionalToToleranceAndFifthOrderInSteps) {
  // three Kepler periods at e = 0.5: the orbit returns to its start, whatever the step pattern
  const double e = 0.5, t_end = 6 * M_PI;
  const Vector4<double> x0 = kepler_exact(e, 0.0);
  std::vector<double> rtols, errors, steps;
  for (double rtol = 1e-4; rtol >= 1e-11; rtol /= 10) {
    const auto r = integrate_adaptive(dormand_prince54, kepler, 0.0, x0, std::array<double, 1>{t_end},
                                      tolerances(rtol, rtol * 1e-2));
    ASSERT_EQ(r.status, AdaptiveStatus::ok);
    const double error = (r.x - x0).norm();
    std::printf("[ order    ] rtol %.0e: %5lld accepted %3lld rejected, error %.3e (%.2f rtol)\n",
                rtol, r.accepted, r.rejected, error, error / rtol);
    rtols.push_back(rtol), errors.push_back(error), steps.push_back(double(r.accepted));
  }
  const double p_steps = -log_log_slope(steps, errors), p_tol = log_log_slope(rtols, errors);
  std::printf("[ order    ] error ~ steps^-%.2f, error ~ rtol^%.2f\n", p_steps, p_tol);
  // steps ~ rtol^(-1/5) and error ~ h^5: the error falls with the 5th power of the steps and
  // in proportion to the tolerance
  EXPECT_NEAR(p_steps, 5.0, 0.5);
  EXPECT_NEAR(p_tol, 1.0, 0.15);
}

TEST(ErrorControl, ErrorAtEndIsASmallMultipleOfToleranceOnOscillatorAndLogistic) {
  // logistic growth x' = x (1 - x) from 0.1: exact x = 1 / (1 + 9 e^-t), nonlinear but stable
  const auto logistic = [](double, const Eigen::Matrix<double, 1, 1>& x,
                           Eigen::Matrix<double, 1, 1>& dxdt) { dxdt(0) = x(0) * (1 - x(0)); };
  const double t_end = 20.0;
  for (double rtol : {1e-6, 1e-8, 1e-10}) {
    const auto r = integrate_adaptive(dormand_prince54, oscillator, 0.0, Eigen::Vector2d(1, 0),
                                      std::vector<double>{t_end}, tolerances(rtol, rtol * 1e-2));
    ASSERT_EQ(r.status, AdaptiveStatus::ok);
    const double error = (r.x - oscillator_exact(t_end)).norm();
    const auto l = integrate_adaptive(dormand_prince54, logistic, 0.0, Eigen::Matrix<double, 1, 1>(0.1),
                                      std::vector<double>{t_end}, tolerances(rtol, rtol * 1e-2));
    ASSERT_EQ(l.status, AdaptiveStatus::ok);
    const double logistic_error = std::abs(l.x(0) - 1 / (1 + 9 * std::exp(-t_end)));
    std::printf(
        "[ control  ] rtol %.0e: oscillator %lld steps, error %.2f rtol; logistic %lld steps, "
        "error %.2f rtol\n",
        rtol, r.accepted, error / rtol, l.accepted, logistic_error / rtol);
    EXPECT_LT(error, 10 * rtol);
    EXPECT_GT(error, 1e-2 * rtol);  // and not bought by steps much smaller than needed
    EXPECT_LT(logistic_error, 10 * rtol);
  }
}

TEST(ErrorControl, KeplerOrbitKeepsInvariantsAndApocenterStateNearTolerance) {
  // e = 0.9: the speed at the pericenter is 19 times that at the apocenter, so the controller
  // must shrink and grow the step by that much every period. A timing error made at the
  // pericenter becomes an along-track error that grows over the orbit (and the acceleration
  // of 100 at the next pericenter magnifies it in the velocity), so the state is checked at
  // the apocenter and the invariants everywhere
  const double e = 0.9, rtol = 1e-9;
  const Vector4<double> x0 = kepler_exact(e, 0.0);
  const auto angular_momentum = [](const Vector4<double>& x) { return x(0) * x(3) - x(1) * x(2); };
  const double energy = kepler_energy(x0), momentum = angular_momentum(x0);
  std::vector<double> grid;
  for (int i = 1; i <= 64; ++i) grid.push_back(2 * M_PI * i / 64);
  double energy_drift = 0, momentum_drift = 0, apocenter_error = 0;
  const auto observer = [&](double t, const Vector4<double>& x) {
    energy_drift = std::max(energy_drift, std::abs(kepler_energy(x) - energy));
    momentum_drift = std::max(momentum_drift, std::abs(angular_momentum(x) - momentum));
    if (t == M_PI) apocenter_error = (x - kepler_exact(e, t)).norm();
  };
  const auto r = integrate_adaptive(dormand_prince54, kepler, 0.0, x0, grid, tolerances(rtol, 1e-12), observer);
  ASSERT_EQ(r.status, AdaptiveStatus::ok);
  std::printf(
      "[ control  ] kepler e = 0.9, rtol %.0e: %lld accepted %lld rejected; drift of energy "
      "%.2f rtol, of angular momentum %.2f rtol; error at apocenter %.2f rtol\n",
      rtol, r.accepted, r.rejected, energy_drift / rtol, momentum_drift / rtol,
      apocenter_error / rtol);
  ASSERT_EQ(grid[31], M_PI);
  EXPECT_GT(r.rejected, 0);
  EXPECT_LT(energy_drift, 10 * rtol);
  EXPECT_LT(momentum_drift, 10 * rtol);
  EXPECT_GT(apocenter_error, 0);
  EXPECT_LT(apocenter_error, 100 * rtol);
}

TEST(ErrorControl, StepChangeInForcingCausesCountedRejectionsAndIsResolved) {
  // x' = -50 (x - u(t)) with u jumping from 0 to 1 at t = 1: steps grown on the smooth decay
  // overrun the jump and must be rejected
  const auto f = [](double t, const Eigen::Matrix<double, 1, 1>& x,
                    Eigen::Matrix<double, 1, 1>& dxdt) {
    dxdt(0) = -50 * (x(0) - (t < 1 ? 0 : 1));
  };
  const auto exact = [](double t) {
    return t < 1 ? std::exp(-50 * t) : 1 + (std::exp(-50.0) - 1) * std::exp(-50 * (t - 1));
  };
  const double rtol = 1e-7;
  Workspace<Eigen::Matrix<double, 1, 1>> ws(1);
  const AdaptiveOptions<double> options = tolerances(rtol, 1e-9);
  ASSERT_EQ(adaptive_start(dormand_prince54, f, 0.0, Eigen::Matrix<double, 1, 1>(1.0), 2.0, options, ws),
            AdaptiveStatus::ok);
  // attempts across the jump fail until the steps are small enough to creep up to it
  long long rejected_near_jump = 0;
  double smallest_step_near_jump = 1;
  while (ws.t < 2.0) {
    const long long before = ws.rejected;
    ASSERT_EQ(adaptive_step(dormand_prince54, f, 2.0, options, ws), AdaptiveStatus::ok);
    // a step that succeeds right after a failure must not propose a longer one
    if (ws.rejected > before && ws.t < 2.0) {
      EXPECT_LE(ws.h, ws.t - ws.t_previous) << "after the step ending at t = " << ws.t;
    }
    if (std::abs(ws.t - 1) < 0.05) {
      rejected_near_jump += ws.rejected - before;
      smallest_step_near_jump = std::min(smallest_step_near_jump, ws.t - ws.t_previous);
    }
  }
  std::printf(
      "[ reject   ] step change: %lld accepted, %lld rejected (%lld within 0.05 of the jump, "
      "smallest step there %.1e), %lld evaluations, error at end %.3e\n",
      ws.accepted, ws.rejected, rejected_near_jump, smallest_step_near_jump, ws.evaluations,
      std::abs(ws.x(0) - exact(2.0)));
  EXPECT_GE(rejected_near_jump, 10);
  EXPECT_LT(smallest_step_near_jump, 1e-5);
  EXPECT_EQ(ws.t, 2.0);
  EXPECT_LT(std::abs(ws.x(0) - exact(2.0)), 10 * rtol);
  // f(t0, x0), the starting-step probe, then 6 stages per attempt (the 7th is reused)
  EXPECT_EQ(ws.evaluations, 2 + 6 * (ws.accepted + ws.rejected));
}

TEST(DenseOutput, LocalErrorShrinksWithFifthPowerOfStep) {
  // one step of forced size h from an exact state: the interpolant's error is O(h^5)
  const double e = 0.5, t0 = 0.3;
  const auto interior_error = [&](double h) {
    Workspace<Vector4<double>> ws(4);
    AdaptiveOptions<double> options = tolerances(1.0, 1.0);  // accept whatever happens
    options.h_initial = h;
    EXPECT_EQ(adaptive_start(dormand_prince54, kepler, t0, kepler_exact(e, t0), t0 + h, options, ws), AdaptiveStatus::ok);
    EXPECT_EQ(adaptive_step(dormand_prince54, kepler, t0 + h, options, ws), AdaptiveStatus::ok);
    EXPECT_EQ(ws.rejected, 0);
    double worst = 0;
    Vector4<double> x;
    for (int i = 1; i < 100; ++i) {
      const double t = t0 + h * i / 100;
      dense_output(ws, t, x);
      worst = std::max(worst, (x - kepler_exact(e, t)).norm());
    }
    return worst;
  };
  const double e1 = interior_error(0.2), e2 = interior_error(0.1), e4 = interior_error(0.05);
  const double p12 = std::log2(e1 / e2), p24 = std::log2(e2 / e4);
  std::printf(
      "[ dense    ] one step, h = 0.2, 0.1, 0.05: interior error %.3e %.3e %.3e, "
      "measured order %.2f %.2f\n",
      e1, e2, e4, p12, p24);
  EXPECT_NEAR(p12, 5.0, 0.4);
  EXPECT_NEAR(p24, 5.0, 0.4);
}

TEST(DenseOutput, InteriorLocalErrorOfAnAdaptiveRunStaysWithinTolerance) {
  // the oscillator's flow is a rotation, so the exact solution through each step's start is
  // known and the interpolant's own (local) error can be measured in the controller's norm
  const double rtol = 1e-8, atol = 1e-11;
  Workspace<Eigen::Vector2d> ws(2);
  const AdaptiveOptions<double> options = tolerances(rtol, atol);
  ASSERT_EQ(adaptive_start(dormand_prince54, oscillator, 0.0, Eigen::Vector2d(1, 0), 20.0, options, ws),
            AdaptiveStatus::ok);
  const auto flow = [&](double t) {
    const double s = t - ws.t_previous;
    return Eigen::Vector2d(std::cos(s) * ws.x_previous(0) + std::sin(s) * ws.x_previous(1),
                           -std::sin(s) * ws.x_previous(0) + std::cos(s) * ws.x_previous(1));
  };
  // the scale of the step's error test, atol + rtol max(|x0|, |x1|), for every point in it
  const auto scaled = [&](const Eigen::Vector2d& error) {
    const Eigen::Array2d scale =
        atol + rtol * ws.x_previous.cwiseAbs().cwiseMax(ws.x.cwiseAbs()).array();
    return std::sqrt((error.array() / scale).square().mean());
  };
  double worst_end = 0, worst_interior = 0;
  Eigen::Vector2d x;
  while (ws.t < 20.0) {
    ASSERT_EQ(adaptive_step(dormand_prince54, oscillator, 20.0, options, ws), AdaptiveStatus::ok);
    worst_end = std::max(worst_end, scaled(ws.x - flow(ws.t)));
    for (int i = 1; i < 20; ++i) {
      const double t = ws.t_previous + (ws.t - ws.t_previous) * i / 20;
      dense_output(ws, t, x);
      worst_interior = std::max(worst_interior, scaled(x - flow(t)));
    }
  }
  std::printf(
      "[ dense    ] oscillator rtol 1e-8, %lld steps: worst local error in the error norm "
      "%.3f at step ends, %.3f inside steps\n",
      ws.accepted, worst_end, worst_interior);
  // the 4th-order interpolant is less accurate than the 5th-order step ends but, like the
  // embedded estimate that controls the step, within the tolerance
  EXPECT_LT(worst_interior, 1.0);
  EXPECT_GT(worst_interior, worst_end);
}

TEST(DenseOutput, ReproducesBothEndsOfTheStepExactly) {
  Workspace<Vector4<double>> ws(4);
  const AdaptiveOptions<double> options = tolerances(1e-6, 1e-9);
  ASSERT_EQ(adaptive_start(dormand_prince54, kepler, 0.0, kepler_exact(0.7, 0.0), 3.0, options, ws), AdaptiveStatus::ok);
  Vector4<double> x;
  dense_output(ws, 0.0, x);  // before the first step: the start state
  EXPECT_EQ(x, ws.x);
  while (ws.t < 3.0) {
    ASSERT_EQ(adaptive_step(dormand_prince54, kepler, 3.0, options, ws), AdaptiveStatus::ok);
    dense_output(ws, ws.t_previous, x);
    EXPECT_EQ(x, ws.x_previous);
    dense_output(ws, ws.t, x);
    EXPECT_EQ(x, ws.x);
  }
}

TEST(IntegrateAdaptive, ObservesEveryGridTimeExactlyWithoutChangingTheSteps) {
  std::vector<double> grid;
  for (int i = 0; i <= 100; ++i) grid.push_back(0.1 * i);  // 0.30000000000000004 and kin
  std::vector<double> times;
  double worst = 0;
  const auto observer = [&](double t, const Eigen::Vector2d& x) {
    times.push_back(t);
    worst = std::max(worst, (x - oscillator_exact(t)).norm());
  };
  const auto options = tolerances(1e-9, 1e-12);
  const auto r =
      integrate_adaptive(dormand_prince54, oscillator, 0.0, Eigen::Vector2d(1, 0), grid, options, observer);
  ASSERT_EQ(r.status, AdaptiveStatus::ok);
  EXPECT_EQ(times, grid);
  EXPECT_EQ(r.t, grid.back());
  EXPECT_LT(worst, 1e-8);
  // output comes from the dense output: the steps are those of a run without the grid
  const auto plain = integrate_adaptive(dormand_prince54, oscillator, 0.0, Eigen::Vector2d(1, 0),
                                        std::vector<double>{grid.back()}, options);
  std::printf("[ grid     ] 101 grid times from %lld steps (%lld without grid), worst error %.3e\n",
              r.accepted, plain.accepted, worst);
  EXPECT_EQ(r.accepted, plain.accepted);
  EXPECT_EQ(r.rejected, plain.rejected);
  EXPECT_EQ(r.x, plain.x);
}

TEST(AdaptiveStep, LandsExactlyOnEndTimeAndNeverStepsPastIt) {
  Workspace<Eigen::Vector2d> ws(2);
  const AdaptiveOptions<double> options = tolerances(1e-6, 1e-9);
  const double t_end = 1.1;  // not representable: landing must copy it, not add up to it
  ASSERT_EQ(adaptive_start(dormand_prince54, oscillator, 0.1, Eigen::Vector2d(1, 0), t_end, options, ws),
            AdaptiveStatus::ok);
  while (ws.t < t_end) {
    ASSERT_EQ(adaptive_step(dormand_prince54, oscillator, t_end, options, ws), AdaptiveStatus::ok);
    EXPECT_LE(ws.t, t_end);
  }
  EXPECT_EQ(ws.t, t_end);
  // at the end there is nothing left to do
  const long long accepted = ws.accepted;
  EXPECT_EQ(adaptive_step(dormand_prince54, oscillator, t_end, options, ws), AdaptiveStatus::ok);
  EXPECT_EQ(ws.accepted, accepted);
}

TEST(AdaptiveStep, LandingOnACloseIntermediateEndDoesNotShrinkLaterSteps) {
  const AdaptiveOptions<double> options = tolerances(1e-8, 1e-11);
  const auto steps_to = [&](double intermediate) {
    Workspace<Eigen::Vector2d> ws(2);
    EXPECT_EQ(adaptive_start(dormand_prince54, oscillator, 0.0, Eigen::Vector2d(1, 0), 10.0, options, ws),
              AdaptiveStatus::ok);
    EXPECT_EQ(adaptive_step(dormand_prince54, oscillator, 10.0, options, ws), AdaptiveStatus::ok);
    // an output or control time a hair after the current one forces a tiny step
    if (intermediate > 0) {
      EXPECT_EQ(adaptive_step(dormand_prince54, oscillator, ws.t + intermediate, options, ws), AdaptiveStatus::ok);
    }
    while (ws.t < 10.0) {
      EXPECT_EQ(adaptive_step(dormand_prince54, oscillator, 10.0, options, ws), AdaptiveStatus::ok);
    }
    return ws.accepted;
  };
  // had the 1e-9 step set the next one, regrowing by 10 per step would cost ~7 more steps
  const long long plain = steps_to(0), interrupted = steps_to(1e-9);
  std::printf("[ landing  ] %lld steps, %lld with a 1e-9 step to an intermediate end\n", plain,
              interrupted);
  EXPECT_LE(interrupted, plain + 2);
}

TEST(AdaptiveStart, AutomaticFirstStepIsAcceptedAndNearTheControllersOwnChoice) {
  const AdaptiveOptions<double> options = tolerances(1e-8, 1e-11);
  Workspace<Vector4<double>> ws(4);
  ASSERT_EQ(adaptive_start(dormand_prince54, kepler, 0.0, kepler_exact(0.5, 0.0), 10.0, options, ws), AdaptiveStatus::ok);
  const double h0 = ws.h;
  for (int i = 0; i < 5; ++i) ASSERT_EQ(adaptive_step(dormand_prince54, kepler, 10.0, options, ws), AdaptiveStatus::ok);
  std::printf(
      "[ start    ] kepler rtol 1e-8: first step %.3e, step proposed after 5 steps %.3e, "
      "%lld rejected\n",
      h0, ws.h, ws.rejected);
  EXPECT_EQ(ws.rejected, 0);
  // Hairer's heuristic errs on the small side (here q_y = 0 is scaled by atol alone, which
  // makes |f0| look huge), but not by orders of magnitude
  EXPECT_LE(h0, ws.h);
  EXPECT_GT(h0, ws.h / 100);
}

TEST(AdaptiveStart, StepSizeOptionsAreHonoured) {
  AdaptiveOptions<double> options = tolerances(1e-6, 1e-9);
  options.h_initial = 1e-3;
  options.h_max = 0.05;
  Workspace<Eigen::Vector2d> ws(2);
  ASSERT_EQ(adaptive_start(dormand_prince54, oscillator, 0.0, Eigen::Vector2d(1, 0), 1.0, options, ws), AdaptiveStatus::ok);
  EXPECT_EQ(ws.h, 1e-3);
  EXPECT_EQ(ws.evaluations, 1);  // no starting-step probe
  double longest = 0;
  while (ws.t < 1.0) {
    ASSERT_EQ(adaptive_step(dormand_prince54, oscillator, 1.0, options, ws), AdaptiveStatus::ok);
    longest = std::max(longest, ws.t - ws.t_previous);
  }
  EXPECT_LE(longest, 0.05 * (1 + 1e-12));  // t + h rounds, so t_new - t may exceed h by an ulp
  EXPECT_GE(longest, 0.04);                // the limit binds: rtol 1e-6 alone would allow ~0.15
}

TEST(Status, BlowUpEndsInUnderflowAtTheSingularityWithFiniteState) {
  // x' = x^2, x(0) = 1: x = 1 / (1 - t) has a pole at t = 1, the integration is asked for t = 2
  const auto f = [](double, const Eigen::Matrix<double, 1, 1>& x,
                    Eigen::Matrix<double, 1, 1>& dxdt) { dxdt(0) = x(0) * x(0); };
  const auto r = integrate_adaptive(dormand_prince54, f, 0.0, Eigen::Matrix<double, 1, 1>(1.0),
                                    std::vector<double>{2.0}, tolerances(1e-8, 1e-10));
  std::printf(
      "[ status   ] blow-up: %s at t - 1 = %.3e, x = %.3e, %lld accepted "
      "%lld rejected\n",
      to_string(r.status), r.t - 1, r.x(0), r.accepted, r.rejected);
  EXPECT_EQ(r.status, AdaptiveStatus::step_size_underflow) << to_string(r.status);
  // the numerical solution has its own pole, within the accumulated error of t = 1
  EXPECT_NEAR(r.t, 1.0, 1e-7);
  EXPECT_TRUE(r.x.allFinite());
  EXPECT_GT(r.x(0), 1e10);
}

TEST(Status, NanFromRhsPastATimeEndsAsNonFiniteAtThatTime) {
  const auto f = [](double t, const Eigen::Vector2d& x, Eigen::Vector2d& dxdt) {
    dxdt << x(1), t > 1.0 ? std::numeric_limits<double>::quiet_NaN() : -x(0);
  };
  const auto r = integrate_adaptive(dormand_prince54, f, 0.0, Eigen::Vector2d(1, 0), std::vector<double>{3.0},
                                    tolerances(1e-8, 1e-10));
  EXPECT_EQ(r.status, AdaptiveStatus::non_finite);
  EXPECT_STREQ(to_string(r.status), "non_finite");
  EXPECT_LE(r.t, 1.0);
  EXPECT_GT(r.t, 1.0 - 1e-12);
  EXPECT_TRUE(r.x.allFinite());
}

TEST(Status, NonFiniteTrialIsRejectedAndRetriedWithSmallerStep) {
  // f is NaN outside |x| <= 2 (think of sqrt of a negative number); a first step of 50 leaves
  // that domain, a smaller one does not
  int non_finite_inputs = 0;
  const auto f = [&](double, const Eigen::Vector2d& x, Eigen::Vector2d& dxdt) {
    if (!x.allFinite()) ++non_finite_inputs;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (x.cwiseAbs().maxCoeff() > 2)
      dxdt << nan, nan;
    else
      dxdt << x(1), -x(0);
  };
  AdaptiveOptions<double> options = tolerances(1e-8, 1e-10);
  options.h_initial = 50;
  const auto r =
      integrate_adaptive(dormand_prince54, f, 0.0, Eigen::Vector2d(1, 0), std::vector<double>{100.0}, options);
  std::printf("[ status   ] non-finite trials: %lld accepted %lld rejected\n", r.accepted,
              r.rejected);
  EXPECT_EQ(r.status, AdaptiveStatus::ok);
  EXPECT_GE(r.rejected, 2);
  EXPECT_EQ(non_finite_inputs, 0);  // f is never asked about an overflowed stage state
  EXPECT_LT((r.x - oscillator_exact(100.0)).norm(), 1e-5);
}

TEST(Status, RhsFailureStopsAtTheLastAcceptedState) {
  // f cannot evaluate past t = 0.5, as a solve with a singular mass matrix would report
  const auto f = [](double t, const Eigen::Vector2d& x, Eigen::Vector2d& dxdt) {
    if (t > 0.5) return false;
    dxdt << x(1), -x(0);
    return true;
  };
  const auto r = integrate_adaptive(dormand_prince54, f, 0.0, Eigen::Vector2d(1, 0), std::vector<double>{3.0},
                                    tolerances(1e-8, 1e-10));
  EXPECT_EQ(r.status, AdaptiveStatus::rhs_failed);
  EXPECT_STREQ(to_string(r.status), "rhs_failed");
  EXPECT_LE(r.t, 0.5);
  EXPECT_LT((r.x - oscillator_exact(r.t)).norm(), 1e-8);

  // and at the very first evaluation
  Workspace<Eigen::Vector2d> ws(2);
  EXPECT_EQ(adaptive_start(dormand_prince54, f, 0.75, Eigen::Vector2d(1, 0), 1.0, AdaptiveOptions<double>(), ws),
            AdaptiveStatus::rhs_failed);
}

TEST(Status, TooManyStepsCountsAcceptedAndRejectedAttempts) {
  AdaptiveOptions<double> options = tolerances(1e-10, 1e-12);
  options.max_steps = 7;
  const auto r = integrate_adaptive(dormand_prince54, oscillator, 0.0, Eigen::Vector2d(1, 0),
                                    std::vector<double>{10.0}, options);
  EXPECT_EQ(r.status, AdaptiveStatus::too_many_steps);
  EXPECT_STREQ(to_string(r.status), "too_many_steps");
  EXPECT_EQ(r.accepted + r.rejected, 7);
  EXPECT_LT(r.t, 10.0);
}

TEST(Status, NonFiniteInitialStateIsReportedWithoutCallingRhs) {
  int calls = 0;
  const auto f = [&](double, const Eigen::Vector2d& x, Eigen::Vector2d& dxdt) {
    ++calls;
    dxdt = x;
  };
  Workspace<Eigen::Vector2d> ws(2);
  EXPECT_EQ(adaptive_start(dormand_prince54, f, 0.0, Eigen::Vector2d(1, std::numeric_limits<double>::infinity()), 1.0,
                     AdaptiveOptions<double>(), ws),
            AdaptiveStatus::non_finite);
  EXPECT_EQ(calls, 0);
}

TEST(AdaptiveRestart, ContinuesFromTheChangedStateLikeAFreshStart) {
  // a velocity reversal (an impact) between steps: with adaptive_restart the next step is the step
  // a fresh start at the changed state takes, bit for bit
  const AdaptiveOptions<double> options = tolerances(1e-8, 1e-11);
  Workspace<Vector4<double>> ws(4);
  ASSERT_EQ(adaptive_start(dormand_prince54, kepler, 0.0, kepler_exact(0.5, 0.0), 5.0, options, ws), AdaptiveStatus::ok);
  for (int i = 0; i < 3; ++i) ASSERT_EQ(adaptive_step(dormand_prince54, kepler, 5.0, options, ws), AdaptiveStatus::ok);
  const Vector4<double> x_before = ws.x;
  const double t_previous = ws.t_previous;
  ws.x.tail<2>() *= -1;
  ASSERT_EQ(adaptive_restart(kepler, ws), AdaptiveStatus::ok);

  // the last step's dense output still describes the trajectory before the change
  Vector4<double> x;
  dense_output(ws, ws.t, x);
  EXPECT_EQ(x, x_before);
  dense_output(ws, (ws.t + t_previous) / 2, x);
  EXPECT_LT((x - kepler_exact(0.5, (ws.t + t_previous) / 2)).norm(), 1e-8);

  Workspace<Vector4<double>> fresh(4);
  AdaptiveOptions<double> same_step = options;
  same_step.h_initial = ws.h;
  ASSERT_EQ(adaptive_start(dormand_prince54, kepler, ws.t, ws.x, 5.0, same_step, fresh), AdaptiveStatus::ok);
  EXPECT_EQ(fresh.k[0], ws.k[0]);
  ASSERT_EQ(adaptive_step(dormand_prince54, kepler, 5.0, options, ws), AdaptiveStatus::ok);
  ASSERT_EQ(adaptive_step(dormand_prince54, kepler, 5.0, options, fresh), AdaptiveStatus::ok);
  EXPECT_EQ(ws.t, fresh.t);
  EXPECT_EQ(ws.x, fresh.x);
}

TEST(DormandPrince, DoesNotAllocateInStepsOrDenseOutput) {
  // fixed size (the common case for a generated model) and dynamic size, preallocated
  Workspace<Vector4<double>> fixed(4);
  Workspace<Eigen::VectorXd> dynamic(4);
  const AdaptiveOptions<double> options = tolerances(1e-10, 1e-12);
  const double t_end = 1e3;
  const Vector4<double> x0 = kepler_exact(0.6, 0.0);
  ASSERT_EQ(adaptive_start(dormand_prince54, kepler, 0.0, x0, t_end, options, fixed), AdaptiveStatus::ok);
  ASSERT_EQ(adaptive_start(dormand_prince54, kepler, 0.0, Eigen::VectorXd(x0), t_end, options, dynamic),
            AdaptiveStatus::ok);
  Vector4<double> x_fixed;
  Eigen::VectorXd x_dynamic(4);

  eigen_assert_failures = 0;
  Eigen::internal::set_is_malloc_allowed(false);
  {  // the detector works: an allocation is counted
    Eigen::VectorXd probe(6);
    EXPECT_EQ(eigen_assert_failures, 1);
  }
  eigen_assert_failures = 0;
  bool all_ok = true;
  for (int step = 0; step < 1000; ++step) {
    all_ok = all_ok && adaptive_step(dormand_prince54, kepler, t_end, options, fixed) == AdaptiveStatus::ok &&
             adaptive_step(dormand_prince54, kepler, t_end, options, dynamic) == AdaptiveStatus::ok;
    dense_output(fixed, (fixed.t + fixed.t_previous) / 2, x_fixed);
    dense_output(dynamic, (dynamic.t + dynamic.t_previous) / 2, x_dynamic);
    all_ok = all_ok && adaptive_restart(kepler, dynamic) == AdaptiveStatus::ok;
  }
  Eigen::internal::set_is_malloc_allowed(true);
  EXPECT_EQ(eigen_assert_failures, 0);
  EXPECT_TRUE(all_ok);
  EXPECT_GT(fixed.rejected, 0);  // the rejection path ran too
}

TEST(DormandPrince, RejectsMisuseBeforeStepping) {
  const Eigen::Vector2d x0(1, 0);
  const std::vector<double> grid = {1.0};
  const auto with = [](auto change) {
    AdaptiveOptions<double> o;
    change(o);
    return o;
  };
  EXPECT_THROW_MESSAGE(integrate_adaptive(dormand_prince54, oscillator, 0.0, x0, grid, with([](auto& o) { o.rtol = 0; })),
                       std::invalid_argument, "integrate_adaptive: rtol expected positive and finite, got 0");
  EXPECT_THROW_MESSAGE(integrate_adaptive(dormand_prince54, oscillator, 0.0, x0, grid, with([](auto& o) { o.atol = -1; })),
                       std::invalid_argument, "integrate_adaptive: atol expected non-negative and finite, got -1");
  EXPECT_THROW_MESSAGE(integrate_adaptive(dormand_prince54, oscillator, 0.0, x0, grid, with([](auto& o) { o.h_max = std::nan(""); })),
                       std::invalid_argument, "integrate_adaptive: h_max expected non-negative and finite, got nan");
  EXPECT_THROW_MESSAGE(integrate_adaptive(dormand_prince54, oscillator, 2.0, x0, grid), std::invalid_argument,
                       "integrate_adaptive: grid expected finite, strictly increasing and >= t0 = 2, got grid[0] = 1");
  EXPECT_THROW_MESSAGE(integrate_adaptive(dormand_prince54, oscillator, 0.0, x0, std::vector<double>{}), std::invalid_argument,
                       "integrate_adaptive: grid expected non-empty, got 0 times");
  EXPECT_THROW_MESSAGE(integrate_adaptive(dormand_prince54, oscillator, 0.0, x0, std::vector<double>{0.5, 0.5, 1.0}),
                       std::invalid_argument,
                       "integrate_adaptive: grid expected finite, strictly increasing and >= t0 = 0, got grid[1] = 0.5 "
                       "after grid[0] = 0.5");
  Workspace<Eigen::VectorXd> ws(3);
  EXPECT_THROW_MESSAGE(adaptive_start(dormand_prince54, oscillator, 0.0, Eigen::VectorXd::Zero(2), 1.0, AdaptiveOptions<double>(), ws),
                       std::invalid_argument, "adaptive_start: initial state x0 of dim 3 expected, got 2");
  EXPECT_THROW_MESSAGE(adaptive_start(dormand_prince54, oscillator, std::numeric_limits<double>::infinity(), Eigen::VectorXd::Zero(3), 1.0,
                                AdaptiveOptions<double>(), ws),
                       std::invalid_argument, "adaptive_start: time span expected finite with t_end >= t0, got [inf, 1]");
  EXPECT_THROW_MESSAGE((Workspace<Eigen::Vector3d>(2)), std::invalid_argument,
                       "AdaptiveWorkspace: state dimension expected 3, got 2");
  // the message names the operation, the parameter and the value
  EXPECT_THROW_MESSAGE(integrate_adaptive(dormand_prince54, oscillator, 0.0, x0, grid, with([](auto& o) { o.rtol = -1e-6; })),
                       std::invalid_argument, "integrate_adaptive: rtol expected positive and finite, got -1e-06");
}

// the same tests over double and long double (practice 12)
template <typename Scalar>
class ScalarTypes : public ::testing::Test {};
TYPED_TEST_SUITE(ScalarTypes, Scalars, ScalarName);

TYPED_TEST(ScalarTypes, ReachesToleranceNearTheScalarsOwnPrecision) {
  using Scalar = TypeParam;
  // 1000 eps is 2e-13 in double but 1e-16 in long double, beyond what double could deliver
  const Scalar eps = std::numeric_limits<Scalar>::epsilon(), rtol = 1000 * eps;
  AdaptiveOptions<Scalar> options;
  options.rtol = rtol;
  options.atol = rtol / 100;
  const Scalar t_end = 5;
  const auto r = integrate_adaptive(dormand_prince54, oscillator, Scalar(0), Vector2<Scalar>(1, 0),
                                    std::vector<Scalar>{t_end}, options);
  ASSERT_EQ(r.status, AdaptiveStatus::ok);
  const Scalar error = (r.x - oscillator_exact(t_end)).norm();
  std::printf("[ scalar   ] %s, rtol %.1Le: %lld steps, error %.3Le = %.2Lf rtol\n",
              std::is_same<Scalar, double>::value ? "double" : "long double",
              static_cast<long double>(rtol), r.accepted, static_cast<long double>(error),
              static_cast<long double>(error / rtol));
  EXPECT_EQ(r.t, t_end);
  EXPECT_LT(error, 20 * rtol);
}

TYPED_TEST(ScalarTypes, DenseOutputEndsAreExactAndMidpointIsAccurate) {
  using Scalar = TypeParam;
  using Vector = Vector4<Scalar>;
  AdaptiveOptions<Scalar> options;
  options.rtol = Scalar(1e-12L);
  options.atol = Scalar(1e-15L);
  Workspace<Vector> ws(4);
  const Scalar e = Scalar(0.5L);
  ASSERT_EQ(adaptive_start(dormand_prince54, kepler, Scalar(0), kepler_exact(e, Scalar(0)), Scalar(1), options, ws),
            AdaptiveStatus::ok);
  Vector x;
  while (ws.t < 1) {
    ASSERT_EQ(adaptive_step(dormand_prince54, kepler, Scalar(1), options, ws), AdaptiveStatus::ok);
    dense_output(ws, ws.t_previous, x);
    EXPECT_EQ(x, ws.x_previous);
    dense_output(ws, ws.t, x);
    EXPECT_EQ(x, ws.x);
    const Scalar mid = (ws.t + ws.t_previous) / 2;
    dense_output(ws, mid, x);
    EXPECT_LT((x - kepler_exact(e, mid)).norm(), Scalar(1e-10L));
  }
}

}  // namespace
}  // namespace eomrt
