// Operating points completed from the constraints by the runtime's assembly: what the user
// leaves out is solved, the declared independent speeds only where given rates require it;
// given values that admit no solution move as little as they must, and a loop that cannot
// close names the constraint.
#include "eomgen/derivation/operating_point.hpp"

#include <gtest/gtest.h>

#include <fmt/format.h>

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

// given a dependent rate (the centre's speed), the independent rates are solved too, as little
// as the constraints allow: the coin rolls (phi_dot) and neither leans nor slides
TEST(OperatingPoint, AGivenDependentRateIsMetByAnIndependentOne) {
  const Shipped coin("rolling_coin");
  const double r = 12.9e-3;
  const ConstrainedPoint p = coin.complete({{"y_dot", -0.387}});
  EXPECT_EQ(p.solved, (std::vector<std::string>{"x_dot", "theta_dot", "phi_dot"}));
  EXPECT_NEAR(p.point.at("phi_dot"), 0.387 / r, 1e-12);
  EXPECT_EQ(p.point.at("x_dot"), 0.0);
  EXPECT_EQ(p.point.at("theta_dot"), 0.0);
  EXPECT_TRUE(p.moved.empty());
  EXPECT_LT(velocity_residual(coin, p.point), 1e-14);
}

// every rate given, and no rolling motion has them all: they move, the least they must (weighted
// by M's diagonal), and the result says which moved and by how much
TEST(OperatingPoint, GivenRatesThatContradictTheConstraintsMoveAndSaySo) {
  const Shipped coin("rolling_coin");
  const NamedValues given{{"phi_dot", 30}, {"x_dot", 0}, {"y_dot", 0}};
  const ConstrainedPoint p = coin.complete(given);
  EXPECT_LT(velocity_residual(coin, p.point), 1e-14);
  ASSERT_FALSE(p.moved.empty());
  for (const MovedValue& m : p.moved) {
    EXPECT_EQ(m.requested, given.at(m.name));
    EXPECT_EQ(m.used, p.point.at(m.name));
  }
  EXPECT_NE(describe_moved(p.moved).find("moved by"), std::string::npos);
}

// a four-bar linkage (crank a = 0.3, coupler b = 1, rocker c = 0.8 at (d, 0) = (1.1, 0), absolute
// angles): given the crank angle, the coupler and rocker angles of the closure nearest the guess
Model four_bar(double d = 1.1) {
  return parse_model(fmt::format(R"(model four_bar "four-bar"
parameter m = 1.0
parameter a1 = 0.3
parameter b1 = 1.0
parameter c1 = 0.8
parameter d1 = {}
coordinate q1, q2, q3
frame f1 = rotate(a, 3, q1)
frame f2 = rotate(a, 3, q2)
frame f3 = rotate(a, 3, q3)
point A = w + a1*f1.1
point B = A + b1*f2.1
point D = w + d1*a.1
point C = D + c1*f3.1
body crank(mass = m, centre = A, frame = f1, inertia = diag(1, 1, 1))
body coupler(mass = m, centre = B, frame = f2, inertia = diag(1, 1, 1))
body rocker(mass = m, centre = C, frame = f3, inertia = diag(1, 1, 1))
constraint loop_x: dot(position(B) - position(C), a.1) = 0
constraint loop_y: dot(position(B) - position(C), a.2) = 0
)",
                                 d),
                     "four_bar.eom", {});
}

TEST(OperatingPoint, AFourBarKeepsItsGivenCrankAngleOnTheBranchNearestTheGuess) {
  const Model model = four_bar();
  const ModelEquations eom = derive_equations(model);
  for (const double guess : {0.8, -1.0}) {  // near each of the two closures at q1 = 0.5
    const ConstrainedPoint p = satisfy_constraints(model, eom, {{"q1", 0.5}, {"q1_dot", 1.0}},
                                                   {{"q2", guess}, {"q3", guess > 0 ? 1.5 : -1.8}});
    EXPECT_EQ(p.point.at("q1"), 0.5);
    EXPECT_EQ(p.point.at("q1_dot"), 1.0);
    EXPECT_TRUE(p.moved.empty());
    EXPECT_EQ(p.solved, (std::vector<std::string>{"q2", "q3", "q2_dot", "q3_dot"}));
    const NumericEquations e = evaluate_equations(model, eom, p.point);
    EXPECT_LT(e.holonomic_residuals.cwiseAbs().maxCoeff(), 1e-13);
    // the closures by hand (circle intersection): q2 = 0.710597 and q3 = 1.669397 on one branch,
    // q2 = -1.051057 and q3 = -2.009857 on the other
    EXPECT_NEAR(p.point.at("q2"), guess > 0 ? 0.710597 : -1.051057, 1e-6);
    EXPECT_NEAR(p.point.at("q3"), guess > 0 ? 1.669397 : -2.009857, 1e-6);
  }
}

TEST(OperatingPoint, ALoopThatCannotCloseNamesTheConstraintAndTheShortfall) {
  const Model model = four_bar(3.0);  // a + b + c = 2.1 < d = 3
  const ModelEquations eom = derive_equations(model);
  EXPECT_THROW_MESSAGE(satisfy_constraints(model, eom, {{"q1", 0.3}}, {{"q2", 0.2}, {"q3", 2.5}}), Error,
                       "no state near the point satisfies the constraint 'loop_x': the nearest the search came, "
                       "with every value free to move, leaves phi = -0.914 (given: q1); check the model's dimensions, "
                       "or give values near an assembly");
}

TEST(OperatingPoint, APointOnTheConstraintsIsLeftAsItIs) {
  const Shipped coin("rolling_coin");
  const ConstrainedPoint p = coin.complete({{"phi_dot", 30}, {"y_dot", -0.387}});
  EXPECT_TRUE(p.solved.empty());
  EXPECT_EQ(p.point, (NamedValues{{"phi_dot", 30}, {"y_dot", -0.387}}));
}

}  // namespace
}  // namespace eomgen
