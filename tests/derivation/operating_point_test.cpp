// Operating points completed from the constraints: only what the user leaves out is solved,
// dependent rates first and independent ones only where given dependent rates require it, and
// a point that cannot be completed names the constraint.
#include "eomgen/derivation/operating_point.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "eomgen/base/error.hpp"
#include "eomgen/derivation/model_equations.hpp"
#include "eomgen/language/model_file.hpp"
#include "support/expect_throw.hpp"
#include "support/source_dir.hpp"

namespace eomgen {
namespace {

struct Shipped {
  Model model;
  ModelEquations eom;
  explicit Shipped(const std::string& name)
      : model(load_model(eomgen::testing::shipped_model_path(name))), eom(derive_equations(model)) {}
  ConstrainedPoint complete(const NamedValues& given) const { return satisfy_constraints(model, eom, given); }
  NumericEquations at(const NamedValues& point) const { return evaluate_equations(model, eom, point); }
};

double velocity_residual(const Shipped& s, const NamedValues& point) {
  const NumericEquations e = s.at(point);
  Eigen::VectorXd qd(e.constraint_jacobian.cols());
  const auto& coordinates = s.model.system.variables().coordinates();
  for (Eigen::Index j = 0; j < qd.size(); ++j) {
    const auto it = point.find(coordinates[static_cast<std::size_t>(j)].name + "_dot");
    qd(j) = it == point.end() ? 0.0 : it->second;
  }
  return (e.constraint_jacobian * qd + e.constraint_rate_term).cwiseAbs().maxCoeff();
}

// the coin (radius r) rolling upright along -a.2 at heading 0: y_dot = -r phi_dot, x_dot = 0
TEST(OperatingPoint, TheCoinsCentreVelocityFollowsFromItsRateOfRoll) {
  const Shipped coin("rolling_coin");
  const double r = 12.9e-3, w = 30;
  const ConstrainedPoint p = coin.complete({{"phi_dot", w}});
  EXPECT_EQ(p.solved, (std::vector<std::string>{"x_dot", "y_dot"}));
  EXPECT_NEAR(p.point.at("y_dot"), -r * w, 1e-15);
  EXPECT_EQ(p.point.at("x_dot"), 0.0);
  EXPECT_LT(velocity_residual(coin, p.point), 1e-15);
}

// given a dependent rate (the centre's speed), the independent rate it needs is solved instead
TEST(OperatingPoint, AGivenDependentRateIsMetByAnIndependentOne) {
  const Shipped coin("rolling_coin");
  const double r = 12.9e-3;
  const ConstrainedPoint p = coin.complete({{"y_dot", -0.387}});
  EXPECT_EQ(p.solved, (std::vector<std::string>{"x_dot", "phi_dot"}));
  EXPECT_NEAR(p.point.at("phi_dot"), 0.387 / r, 1e-12);
  EXPECT_LT(velocity_residual(coin, p.point), 1e-14);
}

// leaned and steered, the bicycle's pitch is what keeps the front wheel on the ground
TEST(OperatingPoint, TheBicyclesPitchIsSolvedFromItsLeanAndSteer) {
  const Shipped bicycle("whipple_bicycle");
  const ConstrainedPoint p = bicycle.complete({{"phi", 0.1}, {"delta", 0.3}, {"x_dot", 2}});
  ASSERT_FALSE(p.solved.empty());
  EXPECT_EQ(p.solved.front(), "theta");
  EXPECT_GT(std::abs(p.point.at("theta")), 1e-4);  // steering tilts the frame
  EXPECT_LT(bicycle.at(p.point).holonomic_residuals.cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT(velocity_residual(bicycle, p.point), 1e-12);
  EXPECT_EQ(p.point.at("phi"), 0.1);  // given values stay as given
  EXPECT_EQ(p.point.at("delta"), 0.3);
}

TEST(OperatingPoint, RatesThatAreAllGivenAndInconsistentNameTheConstraint) {
  const Shipped coin("rolling_coin");
  EXPECT_THROW_MESSAGE(coin.complete({{"phi_dot", 30}, {"x_dot", 0}, {"y_dot", 0}}), Error,
                       "the operating point violates the constraint 'no_slip_1' (residual 0.387); leave out one of the "
                       "rates it involves (y_dot, phi_dot) to have it solved, or give rates that satisfy it");
}

TEST(OperatingPoint, APointOnTheConstraintsIsLeftAsItIs) {
  const Shipped coin("rolling_coin");
  const ConstrainedPoint p = coin.complete({{"phi_dot", 30}, {"y_dot", -0.387}});
  EXPECT_TRUE(p.solved.empty());
  EXPECT_EQ(p.point, (NamedValues{{"phi_dot", 30}, {"y_dot", -0.387}}));
}

}  // namespace
}  // namespace eomgen
