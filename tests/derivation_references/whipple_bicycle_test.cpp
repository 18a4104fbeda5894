// The shipped Whipple bicycle against the benchmark of Meijaard, Papadopoulos, Ruina and
// Schwab, Proc. R. Soc. A 463 (2007): the coefficient matrices of its linearized equations
//   M qdd + v C1 qd + (g K0 + v^2 K2) q = f,   q = [phi; delta], f = [T_phi; T_delta],
// as the paper prints them to 14 decimals, and its weave and capsize speeds, where upright
// straight running becomes stable and stops being stable.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <string>
#include <vector>

#include "eomgen/derivation/linearization.hpp"
#include "eomgen/derivation/model_equations.hpp"
#include "eomgen/derivation/stability_sweep.hpp"
#include "eomgen/language/model_file.hpp"
#include "support/source_dir.hpp"

namespace eomgen {
namespace {

const double g = 9.81, rR = 0.3, rF = 0.35;

Eigen::Matrix2d matrix(double a, double b, double c, double d) {
  Eigen::Matrix2d m;
  m << a, b, c, d;
  return m;
}

// the paper's eq. (A 1)-(A 3) evaluated for Table 1, as printed in its section 4
const Eigen::Matrix2d M0 = matrix(80.81722, 2.31941332208709, 2.31941332208709, 0.29784188199686);
const Eigen::Matrix2d C1 = matrix(0, 33.86641391492494, -0.85035641456978, 1.68540397397560);
const Eigen::Matrix2d K0 = matrix(-80.95, -2.59951685249872, -2.59951685249872, -0.80329488458618);
const Eigen::Matrix2d K2 = matrix(0, 76.59734589573222, 0, 2.65431523794604);
const double weave_speed = 4.29238253634111, capsize_speed = 6.02426201538837;

class WhippleBicycle : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    model_ = new Model(load_model(eomgen::testing::shipped_model_path("whipple_bicycle")));
    eom_ = new ModelEquations(derive_equations(*model_));
    symbolic_ = new SymbolicLinearization(linearize_symbolic(*model_, *eom_));
  }
  static void TearDownTestSuite() {
    delete symbolic_;
    delete eom_;
    delete model_;
  }
  static LinearModel upright_at(double v) {
    LinearizeOptions drop;
    drop.drop_cyclic = true;
    return linearize(*model_, *eom_, *symbolic_, {{"x_dot", v}}, drop);
  }
  static void expect_near(const Eigen::MatrixXd& got, const Eigen::Matrix2d& want, double tolerance,
                          const std::string& what) {
    ASSERT_EQ(got.rows(), 2) << what;
    ASSERT_EQ(got.cols(), 2) << what;
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j)
        EXPECT_NEAR(got(i, j), want(i, j), tolerance * std::max(1.0, std::abs(want(i, j))))
            << what << "(" << i << ", " << j << ")";
  }
  static Model* model_;
  static ModelEquations* eom_;
  static SymbolicLinearization* symbolic_;
};

Model* WhippleBicycle::model_ = nullptr;
ModelEquations* WhippleBicycle::eom_ = nullptr;
SymbolicLinearization* WhippleBicycle::symbolic_ = nullptr;

TEST_F(WhippleBicycle, ReducedSecondOrderFormIsThePapersInLeanAndSteer) {
  const double v = 5;
  const LinearModel lin = upright_at(v);
  EXPECT_EQ(lin.second_order_coordinates, (std::vector<std::string>{"phi", "delta"}));
  EXPECT_EQ(lin.state_names, (std::vector<std::string>{"phi", "delta", "phi_dot", "delta_dot"}));
  EXPECT_LT(lin.qdd0.cwiseAbs().maxCoeff(), 1e-12);  // straight running is a steady motion
  expect_near(lin.M, M0, 1e-12, "M");
  expect_near(lin.D, v * C1, 1e-12, "D = v C1");
  expect_near(lin.K, g * K0 + v * v * K2, 1e-12, "K = g K0 + v^2 K2");
  // the lean torque and the steer torque are the generalized forces of lean and steer
  expect_near(lin.B_u, Eigen::Matrix2d::Identity(), 1e-12, "B_u");
}

TEST_F(WhippleBicycle, StiffnessSplitsIntoGravityAndSpeedSquaredParts) {
  const LinearModel at_rest = upright_at(0), at_3 = upright_at(3);
  expect_near(at_rest.K / g, K0, 1e-12, "K0");
  expect_near((at_3.K - at_rest.K) / 9, K2, 1e-12, "K2");
  expect_near(at_3.D / 3, C1, 1e-12, "C1");
  EXPECT_LT(at_rest.D.cwiseAbs().maxCoeff(), 1e-12);  // no speed, no damping or gyroscopic terms
}

TEST_F(WhippleBicycle, DependentRatesFollowFromTheForwardSpeed) {
  // given only x_dot: the wheels roll (theta_r_dot = -v/rR, theta_f_dot = -v/rF), nothing turns
  const LinearModel lin = upright_at(4);
  EXPECT_NEAR(lin.point.at("theta_r_dot"), -4 / rR, 1e-12);
  EXPECT_NEAR(lin.point.at("theta_f_dot"), -4 / rF, 1e-12);
  EXPECT_EQ(lin.point.at("psi_dot"), 0.0);
  EXPECT_EQ(lin.point.at("theta_dot"), 0.0);
  // x_dot is a dependent rate: the independent speeds are solved too, the least the constraints
  // require, and lean and steer need no rate for straight running
  EXPECT_EQ(lin.point.at("phi_dot"), 0.0);
  EXPECT_EQ(lin.point.at("delta_dot"), 0.0);
  EXPECT_EQ(lin.solved, (std::vector<std::string>{"y_dot", "psi_dot", "phi_dot", "theta_dot", "theta_r_dot",
                                                  "delta_dot", "theta_f_dot"}));
}

TEST_F(WhippleBicycle, EigenvaluesAreThoseOfThePapersMatrices) {
  for (const double v : {0.0, 2.0, 4.6, 5.0, 8.0}) {
    SCOPED_TRACE(v);
    Eigen::Matrix4d A = Eigen::Matrix4d::Zero();
    A.topRightCorner<2, 2>() = Eigen::Matrix2d::Identity();
    A.bottomLeftCorner<2, 2>() = -M0.inverse() * (g * K0 + v * v * K2);
    A.bottomRightCorner<2, 2>() = -M0.inverse() * (v * C1);
    const StabilityReport paper = assess_stability(A), ours = assess_stability(upright_at(v).A);
    ASSERT_EQ(ours.eigenvalues.size(), 4);
    for (Eigen::Index i = 0; i < 4; ++i)
      EXPECT_LT(std::abs(ours.eigenvalues(i) - paper.eigenvalues(i)), 1e-9 * std::max(1.0, std::abs(paper.eigenvalues(i))));
    EXPECT_EQ(ours.linear, paper.linear);
  }
}

TEST_F(WhippleBicycle, SweepOverTheForwardSpeedFindsTheWeaveAndCapsizeSpeeds) {
  LinearizeOptions drop;
  drop.drop_cyclic = true;
  const StabilitySweep sweep = sweep_stability(*model_, *eom_, *symbolic_, {}, {"x_dot", 0, 10, 0.5}, drop);
  EXPECT_EQ(sweep.points.size(), 21u);
  ASSERT_EQ(sweep.changes.size(), 2u);
  EXPECT_NEAR(sweep.changes[0].value, weave_speed, 1e-9);
  EXPECT_EQ(sweep.changes[0].below, LinearStability::unstable);
  EXPECT_EQ(sweep.changes[0].above, LinearStability::asymptotically_stable);
  EXPECT_NEAR(sweep.changes[1].value, capsize_speed, 1e-9);
  EXPECT_EQ(sweep.changes[1].below, LinearStability::asymptotically_stable);
  EXPECT_EQ(sweep.changes[1].above, LinearStability::unstable);
}

TEST_F(WhippleBicycle, WithoutDroppingTheStatesDoNotPairIntoASecondOrderForm) {
  const LinearModel lin = linearize(*model_, *eom_, *symbolic_, {{"x_dot", 5}});
  EXPECT_EQ(lin.M.size(), 0);
  EXPECT_EQ(lin.no_second_order,
            "the kept coordinates (x, y, psi, phi, theta_r, delta, theta_f) are not those of the kept independent "
            "speeds (phi_dot, theta_r_dot, delta_dot)");
}

}  // namespace
}  // namespace eomgen
