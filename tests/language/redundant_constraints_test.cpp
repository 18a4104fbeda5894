// Constraints whose rows of Xi are, at a generic state, combinations of those of constraints
// before them are noted and kept: which rows are dependent changes with the state (a Segway's
// heading), and the solves take an independent set at each state, the heading 0 where leaving
// one row out for good would fail included.
#include <Eigen/Dense>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "eomgen/base/error.hpp"
#include "eomgen/derivation/model_equations.hpp"
#include "eomgen/derivation/numeric_evaluation.hpp"
#include "eomgen/language/model_file.hpp"
#include "support/expect_model_error.hpp"

namespace eomgen {
namespace {

using ::testing::HasSubstr;

// A Segway, or a differential-drive robot (lines 1-22): the axle's midpoint o at (x, y) and
// the wheel radius r above the plane, heading psi, the chassis pitched by theta about the axle
// b.2, two wheels spinning about it by phiL and phiR, d to either side. Each wheel is a `wheel`
// with its axle along b.2 and the plane's normal a.3: both forbid the same sideways slip of the
// axle, so the second wheel's rows carry one too many.
const std::string segway =
    "model segway \"Two wheels on one axle\"\n"
    "parameter r = 0.25 [m]\n"
    "parameter d = 0.3 [m]\n"
    "parameter l = 0.5 [m]\n"
    "parameter M = 30 [kg]\n"
    "parameter mw = 2 [kg]\n"
    "parameter g = 9.81 [m/s^2]\n"
    "coordinate x [m], y [m], psi, theta, phiL, phiR\n"
    "frame h = rotate(a, 3, psi)\n"
    "frame b = rotate(h, 2, theta)\n"
    "frame fl = rotate(b, 2, phiL)\n"
    "frame fr = rotate(b, 2, phiR)\n"
    "point o = w + x*a.1 + y*a.2 + r*a.3\n"
    "point cl = o + d*b.2\n"
    "point cr = o - d*b.2\n"
    "point cm = o + l*b.3\n"
    "body chassis(mass = M, centre = cm, frame = b, inertia = diag(M*l^2/3, M*l^2/3, M*d^2/3))\n"
    "body wheel_l(mass = mw, centre = cl, frame = fl, inertia = diag(mw*r^2/4, mw*r^2/2, mw*r^2/4))\n"
    "body wheel_r(mass = mw, centre = cr, frame = fr, inertia = diag(mw*r^2/4, mw*r^2/2, mw*r^2/4))\n"
    "gravity = -g*a.3\n"
    "wheel left(body = wheel_l, centre = cl, axle = b.2, radius = r, normal = a.3)\n"
    "wheel right(body = wheel_r, centre = cr, axle = b.2, radius = r, normal = a.3)\n";

// a third wheel at the midpoint, on lines 23-26, after the right wheel: its row left out comes
// after one left out before it
const std::string three_wheels = segway +
                                 "coordinate phiM\n"
                                 "frame fm = rotate(b, 2, phiM)\n"
                                 "body wheel_m(mass = mw, centre = o, frame = fm, inertia = diag(mw*r^2/4, mw*r^2/2, "
                                 "mw*r^2/4))\n"
                                 "wheel middle(body = wheel_m, centre = o, axle = b.2, radius = r, normal = a.3)\n";

std::vector<std::string> names(const Model& model) {
  std::vector<std::string> result;
  for (const Constraint& c : model.system.constraints()) result.push_back(c.name);
  return result;
}

std::vector<std::size_t> rows_of(const ContactForce& contact) {
  std::vector<std::size_t> result;
  for (const ContactForce::Row& row : contact.rows) result.push_back(row.constraint);
  return result;
}


TEST(RedundantConstraints, TheSecondWheelOnAnAxleIsNotedAndKept) {
  const Model model = parse_model(segway, "segway.eom");
  // left_1 and right_1 forbid slip along t1 = a.2, left_2 and right_2 along t2 = -a.1; the
  // centres are placed on the plane, so there is no left_3 or right_3. With h.1 = (c, s, 0),
  // right_2 = c/s left_1 + left_2 - c/s right_1 in the rates (away from s = 0)
  EXPECT_EQ(names(model), (std::vector<std::string>{"left_1", "left_2", "right_1", "right_2"}));
  ASSERT_EQ(model.redundant_constraints.size(), 1u);
  const RedundantConstraint& redundant = model.redundant_constraints[0];
  EXPECT_EQ(redundant.constraint.name, "right_2");
  EXPECT_EQ(redundant.constraint.kind, Constraint::Kind::nonholonomic);
  EXPECT_EQ(redundant.depends_on, (std::vector<std::string>{"left_1", "left_2", "right_1"}));
  EXPECT_EQ(redundant.location.line, 22);
  EXPECT_EQ(redundant.location.column, 7);
  ASSERT_EQ(model.notes.size(), 1u);
  EXPECT_EQ(note_text(model.notes[0]),
            "segway.eom:22:7: note: constraint 'right_2' is redundant: at a generic state its row of Xi is a "
            "combination of those of 'left_1', 'left_2' and 'right_1'; kept, the solves take independent rows at each "
            "state and give a row they leave out the multiplier 0 (docs/conventions.md, Redundant constraints)");
  ASSERT_EQ(model.constraint_locations.size(), 4u);
  ASSERT_EQ(model.contacts.size(), 2u);
  EXPECT_EQ(rows_of(model.contacts[1]), (std::vector<std::size_t>{2, 3}));
}

// at heading 0 the rows along a.2 coincide (left_1 = right_1 in the rates) and right_2 is no
// combination of the other three: a row left out for good would lose the right wheel's rolling
TEST(RedundantConstraints, AtHeadingZeroTheSolvesTakeTheRowsIndependentThere) {
  const Model model = parse_model(segway, "segway.eom");
  const ModelEquations eom = derive_equations(model);
  for (const double psi : {0.0, 0.9, 1.5707963267948966}) {
    SCOPED_TRACE(psi);
    NamedValues state = {{"psi", psi}, {"theta", 0.2}, {"phiL", 1.4}, {"phiR", -0.5}};
    const NumericEquations e = evaluate_equations(model, eom, state);
    ASSERT_EQ(e.constraint_jacobian.rows(), 4);
    EXPECT_EQ(Eigen::FullPivLU<Eigen::MatrixXd>(e.constraint_jacobian).rank(), 3);
    // tilted forward and let go: the accelerations satisfy all four rows
    const NumericEquations moving = evaluate_equations(model, eom, state);
    const AccelerationSolution a = solve_accelerations(moving);
    EXPECT_LT((moving.constraint_jacobian * a.qdd + moving.constraint_acceleration_term).cwiseAbs().maxCoeff(), 1e-12);
    // and M qdd = F + Xi^T lambda
    EXPECT_LT((moving.mass_matrix * a.qdd - moving.forcing - moving.constraint_jacobian.transpose() * a.lambda)
                  .cwiseAbs()
                  .maxCoeff(),
              1e-12);
  }
}

TEST(RedundantConstraints, AThirdWheelOnTheAxleAddsASecondNote) {
  const Model model = parse_model(three_wheels, "three.eom");
  ASSERT_EQ(model.redundant_constraints.size(), 2u);
  EXPECT_EQ(model.redundant_constraints[0].constraint.name, "right_2");
  EXPECT_EQ(model.redundant_constraints[1].constraint.name, "middle_2");
  ASSERT_EQ(model.notes.size(), 2u);
  EXPECT_EQ(model.notes[1].location.line, 26);
  ASSERT_EQ(model.contacts.size(), 3u);
  EXPECT_EQ(rows_of(model.contacts[2]), (std::vector<std::size_t>{4, 5}));
}

TEST(RedundantConstraints, IndependentSpeedsNeedIndependentRows) {
  testing::expect_model_error(segway + "independent theta, psi, phiL\n", 23, 1,
                              "'independent' in a model with a redundant constraint ('right_2'): the null-space "
                              "method needs independent rows; expected no 'independent' statement (the KKT solve "
                              "takes independent rows at each state)");
}

TEST(RedundantConstraints, AConstraintWrittenTwiceGivesTheSameMotionAndForce) {
  const std::string pendulum = "parameter l = 1.5\n"
                               "coordinate x, y\n"
                               "point p = w + x*a.1 + y*a.2\n"
                               "particle bob(mass = 2, at = p)\n"
                               "gravity = 9.81*a.1\n"
                               "constraint rod: x^2 + y^2 = l^2\n"
                               "constraint again: x^2 + y^2 = l^2\n";
  const Model model = parse_model(pendulum, "pendulum.eom");
  EXPECT_EQ(names(model), (std::vector<std::string>{"rod", "again"}));
  ASSERT_EQ(model.redundant_constraints.size(), 1u);
  EXPECT_EQ(model.redundant_constraints[0].constraint.kind, Constraint::Kind::holonomic);
  EXPECT_EQ(model.redundant_constraints[0].depends_on, (std::vector<std::string>{"rod"}));
  ASSERT_EQ(model.notes.size(), 1u);
  EXPECT_EQ(model.notes[0].location.line, 7);
  // hanging at rest (x = l, along gravity): lambda 2 x = -m g, lambda = -m g / (2 l), carried by
  // one of the two rows, the other's multiplier 0
  const Model once = parse_model(pendulum.substr(0, pendulum.rfind("constraint again")), "pendulum.eom");
  const NamedValues hanging = {{"x", 1.5}, {"y_dot", 0.4}};
  const AccelerationSolution a = solve_accelerations(evaluate_equations(model, derive_equations(model), hanging));
  const AccelerationSolution b = solve_accelerations(evaluate_equations(once, derive_equations(once), hanging));
  ASSERT_EQ(a.lambda.size(), 2);
  EXPECT_NEAR(a.lambda.sum(), b.lambda(0), 1e-12);
  EXPECT_TRUE(a.lambda(0) == 0 || a.lambda(1) == 0);
  EXPECT_LT((a.qdd - b.qdd).norm(), 1e-12);
}

}  // namespace
}  // namespace eomgen
