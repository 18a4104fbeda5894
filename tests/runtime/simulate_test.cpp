// Tests for simulate(): sampling grid, inputs closing the loop, loud failures, misuse, and
// allocation-free runs, on hand-written models with known solutions.

#include "runtime/no_malloc.hpp"  // first: it configures Eigen

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "eomrt/eomrt.hpp"
#include "runtime/scalar_types.hpp"
#include "support/expect_throw.hpp"
#include "eomrt/simulate.hpp"
#include "runtime/handwritten_models.hpp"

namespace eomrt {
namespace {

using testing::ScalarName;
using testing::Scalars;

using testing::BlowUp;
using testing::CartesianPendulum;
using testing::Oscillator;
using testing::RedundantMass;

template <class Model, class Scalar = double>
using State = typename ModelTypes<Model, Scalar>::State;

template <class Scalar>
SimulationOptions<Scalar> options(Integrator method, Scalar t_end) {
  SimulationOptions<Scalar> o;
  o.integrator = method;
  o.t_end = t_end;
  return o;
}

// qdd = -(k / m) q with k / m computed once per parameter set in its Constants, counting how
// often Constants are built and how often a function is called with the Parameters
struct CountingOscillator : testing::Unconstrained<1> {
  static constexpr int nq = 1, nu = 0;
  inline static int constants_built = 0, calls_with_parameters = 0;
  template <class S>
  using V = Eigen::Matrix<S, 1, 1>;
  template <class S>
  struct Parameters {
    S m = S(2), k = S(8);
  };
  template <class S>
  class Constants {
   public:
    explicit Constants(const Parameters<S>& parameters) noexcept
        : p(parameters), k_over_m(parameters.k / parameters.m) {
      ++constants_built;
    }
    const Parameters<S>& parameters() const noexcept { return p; }
    Parameters<S> p;
    S k_over_m;
  };
  template <class S>
  static void mass_matrix_and_forcing(const S&, const V<S>& q, const V<S>&, const Eigen::Matrix<S, 0, 1>&,
                                      const Constants<S>& c, V<S>& M, V<S>& F) {
    M(0) = 1;
    F(0) = -c.k_over_m * q(0);
  }
  template <class S>
  static void mass_matrix_and_forcing(const S& t, const V<S>& q, const V<S>& qd, const Eigen::Matrix<S, 0, 1>& u,
                                      const Parameters<S>& p, V<S>& M, V<S>& F) {
    ++calls_with_parameters;
    mass_matrix_and_forcing(t, q, qd, u, Constants<S>(p), M, F);
  }
  template <class S>
  static S kinetic_energy(const S&, const V<S>&, const V<S>& qd, const Constants<S>&) {
    return qd(0) * qd(0) / 2;
  }
  template <class S>
  static S kinetic_energy(const S& t, const V<S>& q, const V<S>& qd, const Parameters<S>& p) {
    ++calls_with_parameters;
    return kinetic_energy(t, q, qd, Constants<S>(p));
  }
  template <class S>
  static S potential_energy(const S&, const V<S>& q, const Constants<S>& c) {
    return c.k_over_m * q(0) * q(0) / 2;
  }
  template <class S>
  static S potential_energy(const S& t, const V<S>& q, const Parameters<S>& p) {
    ++calls_with_parameters;
    return potential_energy(t, q, Constants<S>(p));
  }
};

TEST(Simulate, AModelWithConstantsIsEvaluatedThroughConstantsBuiltOnce) {
  static_assert(has_constants_v<CountingOscillator> && !has_constants_v<Oscillator>);
  CountingOscillator::constants_built = CountingOscillator::calls_with_parameters = 0;
  const SimulationResult<CountingOscillator, double> r = simulate<CountingOscillator>(
      CountingOscillator::Parameters<double>{}, State<CountingOscillator>(1.0, 0.0),
      options(Integrator::rk4, 1.0));
  ASSERT_EQ(r.status, SimulationStatus::ok);
  EXPECT_EQ(r.steps, 1000);
  EXPECT_EQ(CountingOscillator::constants_built, 1);
  EXPECT_EQ(CountingOscillator::calls_with_parameters, 0);
  // q = cos(omega t), omega^2 = k / m = 4
  EXPECT_NEAR(r.x(0), std::cos(2.0), 1e-11);
  EXPECT_NEAR(r.x(1), -2 * std::sin(2.0), 1e-11);
}

TEST(Simulate, SamplesLandExactlyOnTheGridWhateverTheStep) {
  for (const Integrator method : {Integrator::euler, Integrator::rk4, Integrator::dormand_prince}) {
    SCOPED_TRACE(to_string(method));
    SimulationOptions<double> o = options(method, 1.0);
    o.step = 0.003;  // does not divide the sample interval: each interval takes 4 steps of 2.5 ms
    o.sample_interval = 0.01;
    std::vector<double> times;
    const SimulationResult<Oscillator, double> r = simulate<Oscillator>(
        Oscillator::Parameters<double>{}, State<Oscillator>(1.0, 0.0), o, ZeroInputs{},
        [&](const Sample<Oscillator, double>& s) { times.push_back(s.t); });
    ASSERT_EQ(r.status, SimulationStatus::ok);
    ASSERT_EQ(times.size(), 101u);
    for (std::size_t k = 0; k < times.size(); ++k) EXPECT_DOUBLE_EQ(times[k], 0.01 * static_cast<double>(k));
    EXPECT_EQ(times.back(), 1.0);
    EXPECT_EQ(r.t, 1.0);
    if (method != Integrator::dormand_prince) {
      EXPECT_EQ(r.steps, 400);
    }
  }
}

// u = -c qd turns the oscillator m qdd + k q = u into a damped one with a closed-form solution
TEST(Simulate, InputCallbackClosesTheLoop) {
  const Oscillator::Parameters<double> p;  // m = 2, k = 8: omega0 = 2
  const double c = 1.6;
  const double zeta = c / (2 * p.m * 2.0), omega0 = 2.0;
  const double omega_d = omega0 * std::sqrt(1 - zeta * zeta);
  SimulationOptions<double> o = options(Integrator::dormand_prince, 3.0);
  o.adaptive.rtol = 1e-12;
  o.adaptive.atol = 1e-14;
  const auto damper = [c](double, const State<Oscillator>& x, Eigen::Matrix<double, 1, 1>& u) {
    u(0) = -c * x(1);
  };
  const SimulationResult<Oscillator, double> r =
      simulate<Oscillator>(p, State<Oscillator>(1.0, 0.0), o, damper);
  ASSERT_EQ(r.status, SimulationStatus::ok);
  // x(0) = 1, xd(0) = 0: x = e^{-zeta w0 t} (cos(wd t) + zeta w0 / wd sin(wd t))
  const double t = 3.0, decay = std::exp(-zeta * omega0 * t);
  const double x = decay * (std::cos(omega_d * t) + zeta * omega0 / omega_d * std::sin(omega_d * t));
  EXPECT_NEAR(r.x(0), x, 1e-10);
}

// qdd = qd^2 from qd(0) = 1 has qd = 1 / (1 - t): the run must stop near t = 1 with the last
// good (finite) state, for the adaptive method by step-size underflow, for a fixed step by the
// state overflowing
TEST(Simulate, FiniteTimeBlowUpStopsLoudlyWithTheLastGoodState) {
  for (const Integrator method : {Integrator::dormand_prince, Integrator::rk4, Integrator::euler}) {
    SCOPED_TRACE(to_string(method));
    SimulationOptions<double> o = options(method, 2.0);
    o.step = 1e-3;
    double last_sample = -1;
    bool finite = true;
    const SimulationResult<BlowUp, double> r = simulate<BlowUp>(
        BlowUp::Parameters<double>{}, State<BlowUp>(0.0, 1.0), o, ZeroInputs{},
        [&](const Sample<BlowUp, double>& s) {
          last_sample = s.t;
          finite = finite && s.q.allFinite() && s.qd.allFinite();
        });
    EXPECT_EQ(r.status, method == Integrator::dormand_prince ? SimulationStatus::step_size_underflow
                                                             : SimulationStatus::non_finite_state)
        << to_string(r.status);
    EXPECT_TRUE(r.x.allFinite());
    EXPECT_TRUE(finite);
    EXPECT_GT(r.failure_time, 0.99);
    EXPECT_LT(r.failure_time, 1.5);
    EXPECT_LE(last_sample, r.failure_time);
  }
}

TEST(Simulate, SingularMassMatrixStopsAtTheStart) {
  const SimulationResult<RedundantMass<false>, double> r = simulate<RedundantMass<false>>(
      RedundantMass<false>::Parameters<double>{}, State<RedundantMass<false>>(0.1, 0.2, 0.0, 0.0),
      options(Integrator::rk4, 1.0));
  EXPECT_EQ(r.status, SimulationStatus::singular_mass_matrix);
  EXPECT_EQ(r.failure_time, 0.0);
}

TEST(Simulate, NonFiniteInitialStateIsRejected) {
  const SimulationResult<Oscillator, double> r = simulate<Oscillator>(
      Oscillator::Parameters<double>{}, State<Oscillator>(std::nan(""), 0.0), options(Integrator::rk4, 1.0));
  EXPECT_EQ(r.status, SimulationStatus::non_finite_state);
}

TEST(Simulate, InconsistentOptionsThrowBeforeTheLoop) {
  const Oscillator::Parameters<double> p;
  const State<Oscillator> x0(1.0, 0.0);
  SimulationOptions<double> o = options(Integrator::rk4, 1.0);
  o.t_end = -1.0;
  EXPECT_THROW_MESSAGE(simulate<Oscillator>(p, x0, o), std::invalid_argument,
                       "simulate: time span expected finite with t_end >= t0, got [0, -1]");
  o = options(Integrator::rk4, 1.0);
  o.step = 0.0;
  EXPECT_THROW_MESSAGE(simulate<Oscillator>(p, x0, o), std::invalid_argument,
                       "simulate: step expected positive and finite, got 0");
  o = options(Integrator::dormand_prince, 1.0);
  o.adaptive.rtol = 0.0;
  EXPECT_THROW_MESSAGE(simulate<Oscillator>(p, x0, o), std::invalid_argument,
                       "simulate: tolerances expected rtol > 0 and atol >= 0, got rtol 0, atol 1e-10");
  o = options(Integrator::dormand_prince, 1.0);
  o.sample_interval = -0.1;
  EXPECT_THROW_MESSAGE(simulate<Oscillator>(p, x0, o), std::invalid_argument,
                       "simulate: sample interval expected >= 0 and finite, got -0.1");
}

TEST(Simulate, ProjectionPutsTheInitialStateOnTheConstraints) {
  const CartesianPendulum::Parameters<double> p;  // l = 0.8
  std::vector<ConstraintResiduals<double>> residuals;
  const SimulationResult<CartesianPendulum, double> r = simulate<CartesianPendulum>(
      p, State<CartesianPendulum>(0.5, -0.5, 0.3, 0.1), options(Integrator::rk4, 0.1), ZeroInputs{},
      [&](const Sample<CartesianPendulum, double>& s) { residuals.push_back(s.residuals); });
  ASSERT_EQ(r.status, SimulationStatus::ok);
  EXPECT_LT(residuals.front().position, 1e-15);
  EXPECT_LT(residuals.front().velocity, 1e-15);
  EXPECT_NEAR(r.x.head<2>().norm(), 0.8, 1e-14);
}

template <class Scalar>
class SimulateOverScalars : public ::testing::Test {};
TYPED_TEST_SUITE(SimulateOverScalars, Scalars, ScalarName);

// energy of the Cartesian pendulum over 5 s at a tolerance near each type's precision
TYPED_TEST(SimulateOverScalars, ConservesEnergyToTheScalarsPrecision) {
  using Scalar = TypeParam;
  const typename CartesianPendulum::template Parameters<Scalar> p;
  SimulationOptions<Scalar> o = options(Integrator::dormand_prince, Scalar(5));
  const Scalar eps = std::numeric_limits<Scalar>::epsilon();
  o.adaptive.rtol = std::sqrt(eps) * Scalar(1e-4);  // 1.5e-12 in double, 3e-14 in long double
  o.adaptive.atol = o.adaptive.rtol;
  o.sample_interval = Scalar(0.05);
  std::vector<Scalar> energy;
  const State<CartesianPendulum, Scalar> x0(Scalar(0.8) * std::sin(Scalar(2)), Scalar(-0.8) * std::cos(Scalar(2)),
                                            0, 0);
  const auto r = simulate<CartesianPendulum, Scalar>(
      p, x0, o, ZeroInputs{}, [&](const Sample<CartesianPendulum, Scalar>& s) {
        energy.push_back(s.kinetic_energy + s.potential_energy);
      });
  ASSERT_EQ(r.status, SimulationStatus::ok);
  Scalar drift = 0;
  for (const Scalar e : energy) drift = std::max(drift, std::abs(e - energy.front()));
  EXPECT_LT(drift / std::abs(energy.front()), 100 * o.adaptive.rtol);
}

TEST(Simulate, RunsWithoutHeapAllocation) {
  const CartesianPendulum::Parameters<double> p;
  const State<CartesianPendulum> x0(0.8 * std::sin(1.0), -0.8 * std::cos(1.0), 0.0, 0.0);
  double checksum = 0;
  const auto observer = [&checksum](const Sample<CartesianPendulum, double>& s) { checksum += s.q(0); };
  eigen_assert_failures = 0;
  Eigen::internal::set_is_malloc_allowed(false);
  SimulationOptions<double> o = options(Integrator::dormand_prince, 10.0);
  o.sample_interval = 0.01;
  const auto adaptive = simulate<CartesianPendulum>(p, x0, o, ZeroInputs{}, observer);
  o = options(Integrator::rk4, 2.0);
  o.solver = ConstraintSolver::null_space;
  o.stabilization = Stabilization::baumgarte;
  const auto fixed = simulate<CartesianPendulum>(p, x0, o, ZeroInputs{}, observer);
  Eigen::internal::set_is_malloc_allowed(true);
  EXPECT_EQ(eigen_assert_failures, 0);
  EXPECT_EQ(adaptive.status, SimulationStatus::ok);
  EXPECT_EQ(fixed.status, SimulationStatus::ok);
  EXPECT_GT(adaptive.steps + fixed.steps, 1000);
  EXPECT_TRUE(std::isfinite(checksum));
}

}  // namespace
}  // namespace eomrt
