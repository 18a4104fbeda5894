// Tests for tableau.hpp and rk_fixed.hpp: consistency, measured order, exactness, statuses.

#include "runtime/no_malloc.hpp"  // first: it configures Eigen

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
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

template <std::size_t S>
long double sum(const Coefficient (&v)[S]) {
  return std::accumulate(v, v + S, 0.0L);
}

template <std::size_t S>
void expect_consistent(const ButcherTableau<S>& t, const char* name) {
  SCOPED_TRACE(name);
  EXPECT_NEAR(sum(t.b), 1.0L, 1e-17L);
  for (std::size_t i = 0; i < S; ++i) EXPECT_NEAR(sum(t.a[i]), t.c[i], 1e-17L) << "row " << i;
  EXPECT_TRUE(is_consistent(t));
}

TEST(Tableau, WeightsSumToOneAndNodesAreRowSumsOfA) {
  expect_consistent(euler, "euler");
  expect_consistent(rk4, "rk4");
  expect_consistent(dormand_prince54, "dormand_prince54");
  EXPECT_NEAR(sum(dormand_prince54.b_hat), 1.0L, 1e-17L);
  EXPECT_TRUE(is_consistent(dormand_prince54));  // the overload that also checks b_hat
}

TEST(Tableau, ConsistencyChecksRejectBrokenTableaus) {
  ButcherTableau<4> wrong_node = rk4;
  wrong_node.c[2] = 0.6L;
  EXPECT_FALSE(nodes_match_row_sums(wrong_node));
  ButcherTableau<4> wrong_weight = rk4;
  wrong_weight.b[0] = 0.17L;
  EXPECT_FALSE(weights_sum_to_one(wrong_weight));
  ButcherTableau<4> implicit = rk4;
  implicit.a[1][1] = 0.25L;
  implicit.c[1] = 0.75L;  // keep the row sum right, so only explicitness fails
  EXPECT_TRUE(nodes_match_row_sums(implicit));
  EXPECT_FALSE(is_explicit(implicit));
  EmbeddedTableau<7> wrong_embedded = dormand_prince54;
  wrong_embedded.b_hat[6] = 0.5L;
  EXPECT_FALSE(is_consistent(wrong_embedded));
}

TEST(Tableau, DormandPrinceLastStageIsTheNewStateButRk4IsNot) {
  EXPECT_TRUE(is_fsal(dormand_prince54));
  EXPECT_FALSE(is_fsal(rk4));
}

// harmonic oscillator q'' = -q from q = 1, qd = 0: exact x(t) = [cos t; -sin t]
template <std::size_t S>
double oscillator_error(const ButcherTableau<S>& tableau, double h) {
  const auto f = [](double, const Eigen::Vector2d& x, Eigen::Vector2d& dxdt) {
    dxdt << x(1), -x(0);
  };
  const auto r = integrate_fixed(tableau, f, 0.0, Eigen::Vector2d(1, 0), 2.0, h);
  EXPECT_EQ(r.status, IntegrateStatus::ok);
  return (r.x - Eigen::Vector2d(std::cos(2.0), -std::sin(2.0))).norm();
}

// error ratio 2^p when h is halved: measures p from h, h/2 and from h/2, h/4, h = 0.1
template <std::size_t S>
void expect_measured_order(const ButcherTableau<S>& tableau, const char* name) {
  const double e1 = oscillator_error(tableau, 0.1), e2 = oscillator_error(tableau, 0.05),
               e4 = oscillator_error(tableau, 0.025);
  const double p12 = std::log2(e1 / e2), p24 = std::log2(e2 / e4);
  std::printf("[ order    ] %s: errors %.3e %.3e %.3e, measured order %.3f %.3f\n", name, e1, e2,
              e4, p12, p24);
  EXPECT_NEAR(p12, tableau.order, 0.3);
  EXPECT_NEAR(p24, tableau.order, 0.3);
}

TEST(Convergence, EulerErrorHalvesWithStep) { expect_measured_order(euler, "euler"); }

TEST(Convergence, Rk4ErrorShrinksAtFourthOrder) { expect_measured_order(rk4, "rk4"); }

TEST(Convergence, DormandPrinceErrorShrinksAtFifthOrder) {
  expect_measured_order(dormand_prince54, "dormand_prince54 (b)");
}

TEST(Convergence, DormandPrinceEmbeddedWeightsShrinkAtFourthOrder) {
  ButcherTableau<7> embedded = dormand_prince54;
  for (std::size_t i = 0; i < 7; ++i) embedded.b[i] = dormand_prince54.b_hat[i];
  embedded.order = dormand_prince54.embedded_order;
  expect_measured_order(embedded, "dormand_prince54 (b_hat)");
}

TEST(RkStep, Rk4MatchesCourseNotesFormula) {
  // a nonlinear, non-autonomous right-hand side, so stage times and states both matter
  const auto f = [](double t, const Eigen::Vector2d& x, Eigen::Vector2d& dxdt) {
    dxdt << std::sin(t) * x(1), -x(0) * x(0) + t;
  };
  const double t = 0.3, h = 0.25;
  const Eigen::Vector2d x0(0.7, -1.2);
  // notes A.4.2: k_i carry the factor h
  Eigen::Vector2d k1, k2, k3, k4;
  f(t, x0, k1), k1 *= h;
  f(t + h / 2, x0 + k1 / 2, k2), k2 *= h;
  f(t + h / 2, x0 + k2 / 2, k3), k3 *= h;
  f(t + h, x0 + k3, k4), k4 *= h;
  const Eigen::Vector2d expected = x0 + (k1 + 2 * k2 + 2 * k3 + k4) / 6;

  Eigen::Vector2d x = x0;
  RkWorkspace<Eigen::Vector2d, 4> ws(2);
  rk_step(rk4, f, t, x, h, ws);
  EXPECT_LT((x - expected).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(RkStep, DoesNotAllocateWithPreallocatedDynamicWorkspace) {
  const auto f = [](double, const Eigen::VectorXd& x, Eigen::VectorXd& dxdt) {
    dxdt.head(3) = x.tail(3);
    dxdt.tail(3) = -x.head(3);
  };
  Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(6, -1.0, 1.0);
  RkWorkspace<Eigen::VectorXd, 7> ws(6);
  eigen_assert_failures = 0;
  Eigen::internal::set_is_malloc_allowed(false);
  {  // the detector works: an allocation is counted
    Eigen::VectorXd probe(6);
    EXPECT_EQ(eigen_assert_failures, 1);
  }
  eigen_assert_failures = 0;
  for (int step = 0; step < 1000; ++step) rk_step(dormand_prince54, f, step * 1e-3, x, 1e-3, ws);
  Eigen::internal::set_is_malloc_allowed(true);
  EXPECT_EQ(eigen_assert_failures, 0);
}

TEST(RkWorkspace, RejectsDimensionDifferentFromFixedSize) {
  EXPECT_THROW_MESSAGE((RkWorkspace<Eigen::Vector3d, 4>(2)), std::invalid_argument,
                       "RkWorkspace: state dimension expected 3, got 2");
  EXPECT_THROW_MESSAGE((RkWorkspace<Eigen::VectorXd, 4>(-1)), std::invalid_argument,
                       "RkWorkspace: state dimension expected >= 0, got -1");
}

// the same tests over double and long double (practice 12)
template <typename Scalar>
class Exactness : public ::testing::Test {};
TYPED_TEST_SUITE(Exactness, Scalars, ScalarName);

TYPED_TEST(Exactness, Rk4IntegratesCubicInTimeToRounding) {
  using Scalar = TypeParam;
  using Vector1 = Eigen::Matrix<Scalar, 1, 1>;
  // Simpson's rule is exact for quadratics, so x' = 3 t^2 gives x = t^3 with no truncation error
  const auto f = [](Scalar t, const Vector1&, Vector1& dxdt) { dxdt(0) = 3 * t * t; };
  const Scalar eps = std::numeric_limits<Scalar>::epsilon();
  int observed = 0;
  const auto check = [&](Scalar t, const Vector1& x) {
    ++observed;
    EXPECT_NEAR(x(0), t * t * t, 16 * eps * (1 + t * t * t)) << "at t = " << t;
  };
  const auto r =
      integrate_fixed(rk4, f, Scalar(0), Vector1(Scalar(0)), Scalar(2), Scalar(0.1L), check);
  EXPECT_EQ(r.status, IntegrateStatus::ok);
  EXPECT_EQ(observed, 20);
  EXPECT_NEAR(r.x(0), Scalar(8), 16 * eps * 8);
}

TEST(IntegrateFixed, LandsExactlyOnEndTimeWhenSpanIsNotAMultipleOfStep) {
  const auto f = [](double, const Eigen::Vector2d&, Eigen::Vector2d& dxdt) { dxdt << 1.0, 2.0; };
  std::vector<double> times;
  const auto r = integrate_fixed(rk4, f, 0.1, Eigen::Vector2d(0, 0), 1.1, 0.3,
                                 [&](double t, const Eigen::Vector2d&) { times.push_back(t); });
  EXPECT_EQ(r.status, IntegrateStatus::ok);
  EXPECT_EQ(r.t, 1.1);
  ASSERT_EQ(times.size(), 4u);  // 0.4, 0.7, 1.0 and a shortened step of 0.1
  EXPECT_EQ(times.back(), 1.1);
  EXPECT_NEAR(times[2], 1.0, 1e-15);
  EXPECT_LT((r.x - Eigen::Vector2d(1, 2)).norm(), 1e-14);
}

TEST(IntegrateFixed, TakesNoSliverStepWhenSpanIsAMultipleOfStepUpToRounding) {
  const auto f = [](double, const Eigen::Vector2d&, Eigen::Vector2d& dxdt) { dxdt.setZero(); };
  int steps = 0;
  // (0.9 - 0.3) / 0.2 = 3.0000000000000004 in double: ceil alone would add a 1e-16 step
  const auto r = integrate_fixed(rk4, f, 0.3, Eigen::Vector2d(1, 1), 0.9, 0.2,
                                 [&](double, const Eigen::Vector2d&) { ++steps; });
  EXPECT_EQ(steps, 3);
  EXPECT_EQ(r.t, 0.9);
}

TEST(IntegrateFixed, ReportsNonFiniteStatusAndTimeWhenRhsReturnsNaN) {
  const auto f = [](double t, const Eigen::Vector2d& x, Eigen::Vector2d& dxdt) {
    dxdt << x(1), t >= 1.0 ? std::numeric_limits<double>::quiet_NaN() : -x(0);
  };
  std::vector<double> observed;
  const auto r = integrate_fixed(rk4, f, 0.0, Eigen::Vector2d(1, 0), 3.0, 0.125,
                                 [&](double t, const Eigen::Vector2d&) { observed.push_back(t); });
  // the step [0.875, 1] evaluates f at t = 1 in its last stage
  EXPECT_EQ(r.status, IntegrateStatus::non_finite);
  EXPECT_STREQ(to_string(r.status), "non_finite");
  EXPECT_EQ(r.t, 1.0);
  EXPECT_TRUE(std::isnan(r.x(1)));
  ASSERT_EQ(observed.size(), 7u);
  EXPECT_EQ(observed.back(), 0.875);
}

TEST(IntegrateFixed, StopsWithRhsFailedAtTheLastObservedStateWhenRhsCannotEvaluate) {
  // f cannot evaluate past t = 1, as a solve with a singular mass matrix would report
  const auto f = [](double t, const Eigen::Vector2d& x, Eigen::Vector2d& dxdt) {
    if (t > 1.0) return false;
    dxdt << x(1), -x(0);
    return true;
  };
  std::vector<double> observed;
  Eigen::Vector2d last_observed(0, 0);
  const auto r = integrate_fixed(rk4, f, 0.0, Eigen::Vector2d(1, 0), 3.0, 0.25,
                                 [&](double t, const Eigen::Vector2d& x) {
                                   observed.push_back(t);
                                   last_observed = x;
                                 });
  // the step [1, 1.25] fails at its second stage (t = 1.125), before touching the state
  EXPECT_EQ(r.status, IntegrateStatus::rhs_failed);
  EXPECT_STREQ(to_string(r.status), "rhs_failed");
  EXPECT_EQ(r.t, 1.0);
  ASSERT_EQ(observed.size(), 4u);
  EXPECT_EQ(observed.back(), 1.0);
  EXPECT_EQ(r.x, last_observed);
  EXPECT_LT((r.x - Eigen::Vector2d(std::cos(1.0), -std::sin(1.0))).norm(), 1e-4);
}

TEST(IntegrateFixed, RejectsNonPositiveStepAndReversedSpanBeforeStepping) {
  const auto f = [](double, const Eigen::Vector2d& x, Eigen::Vector2d& dxdt) { dxdt = x; };
  const Eigen::Vector2d x0(1, 0);
  EXPECT_THROW_MESSAGE(integrate_fixed(rk4, f, 0.0, x0, 1.0, 0.0), std::invalid_argument,
                       "integrate_fixed: step h expected positive and finite, got 0");
  EXPECT_THROW_MESSAGE(integrate_fixed(rk4, f, 0.0, x0, 1.0, -0.1), std::invalid_argument,
                       "integrate_fixed: step h expected positive and finite, got -0.1");
  EXPECT_THROW_MESSAGE(integrate_fixed(rk4, f, 1.0, x0, 0.0, 0.1), std::invalid_argument,
                       "integrate_fixed: time span expected finite with t_end >= t0, got [1, 0]");
}

}  // namespace
}  // namespace eomrt
