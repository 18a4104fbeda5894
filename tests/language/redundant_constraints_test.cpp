// Constraints whose rows of Xi are, at a generic state, combinations of those of constraints
// before them are left out of the system with a note; the rows kept, their places and the
// contacts' rows stay consistent, and the motions the kept rows allow satisfy the rows left out.
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

double value_of(const GiNaC::ex& e, const Model& model, const NamedValues& state) {
  const GiNaC::ex v = e.subs(numeric_substitution(model, state)).evalf();
  EXPECT_TRUE(GiNaC::is_a<GiNaC::numeric>(v)) << v;
  return GiNaC::is_a<GiNaC::numeric>(v) ? GiNaC::ex_to<GiNaC::numeric>(v).to_double() : 0.0;
}

TEST(RedundantConstraints, TheSecondWheelOnAnAxleLeavesOutItsRowThatTheFirstHasAlready) {
  const Model model = parse_model(segway, "segway.eom");
  // left_1 and right_1 forbid slip along t1 = a.2, left_2 and right_2 along t2 = -a.1; the
  // centres are placed on the plane, so there is no left_3 or right_3. With h.1 = (c, s, 0),
  // right_2 = c/s left_1 + left_2 - c/s right_1 in the rates
  EXPECT_EQ(names(model), (std::vector<std::string>{"left_1", "left_2", "right_1"}));
  ASSERT_EQ(model.redundant_constraints.size(), 1u);
  const RedundantConstraint& dropped = model.redundant_constraints[0];
  EXPECT_EQ(dropped.constraint.name, "right_2");
  EXPECT_EQ(dropped.constraint.kind, Constraint::Kind::nonholonomic);
  EXPECT_EQ(dropped.depends_on, (std::vector<std::string>{"left_1", "left_2", "right_1"}));
  EXPECT_EQ(dropped.location.line, 22);
  EXPECT_EQ(dropped.location.column, 7);
  ASSERT_EQ(model.notes.size(), 1u);
  EXPECT_EQ(note_text(model.notes[0]),
            "segway.eom:22:7: note: constraint 'right_2' is redundant: at a generic state its row of Xi is a "
            "combination of those of 'left_1', 'left_2' and 'right_1'; left out (their multipliers carry its force)");
  // the places follow the rows kept
  ASSERT_EQ(model.constraint_locations.size(), 3u);
  EXPECT_EQ(model.constraint_locations[0].line, 21);
  EXPECT_EQ(model.constraint_locations[1].line, 21);
  EXPECT_EQ(model.constraint_locations[2].line, 22);
  // the right contact keeps its row along t1 = a.2 only
  ASSERT_EQ(model.contacts.size(), 2u);
  EXPECT_EQ(rows_of(model.contacts[0]), (std::vector<std::size_t>{0, 1}));
  EXPECT_EQ(rows_of(model.contacts[1]), (std::vector<std::size_t>{2}));
  for (unsigned i = 0; i < 3; ++i)
    EXPECT_TRUE(model.contacts[1].rows[0].direction[i].is_equal(GiNaC::ex(i == 1 ? 1 : 0)))
        << model.contacts[1].rows[0].direction[i];
}

TEST(RedundantConstraints, TheRowsKeptHaveFullRankAndEveryMotionTheyAllowSatisfiesTheRowLeftOut) {
  const Model model = parse_model(segway, "segway.eom");
  const ModelEquations eom = derive_equations(model);
  NamedValues state = {{"x", 0.3}, {"y", -1.2}, {"psi", 0.9}, {"theta", 0.2}, {"phiL", 1.4}, {"phiR", -0.5}};
  const NumericEquations at_rest = evaluate_equations(model, eom, state);
  ASSERT_EQ(at_rest.constraint_jacobian.rows(), 3);
  Eigen::FullPivLU<Eigen::MatrixXd> lu(at_rest.constraint_jacobian);
  EXPECT_EQ(lu.rank(), 3);
  EXPECT_LT(at_rest.constraint_rate_term.norm(), 1e-15);
  // rates in the null space of the rows kept (nq - nc = 3 of them): the row left out is zero there
  const Eigen::MatrixXd allowed = lu.kernel();
  ASSERT_EQ(allowed.cols(), 3);
  const Eigen::VectorXd qd = allowed * Eigen::Vector3d(0.7, -1.1, 0.4);
  const char* rates[] = {"x_dot", "y_dot", "psi_dot", "theta_dot", "phiL_dot", "phiR_dot"};
  for (int k = 0; k < 6; ++k) state[rates[k]] = qd[k];
  const GiNaC::ex& right_2 = model.redundant_constraints.at(0).constraint.expression;
  EXPECT_NEAR(value_of(right_2, model, state), 0.0, 1e-13);
  // and the row is no zero row: a rate outside that null space moves it
  state["x_dot"] += 0.5;
  EXPECT_GT(std::abs(value_of(right_2, model, state)), 0.1);
  // the KKT matrix is regular: standing upright and still, nothing moves and the wheels carry no
  // force in the plane
  const AccelerationSolution upright = solve_accelerations(
      evaluate_equations(model, eom, {{"psi", 0.9}, {"phiL", 1.4}, {"phiR", -0.5}}));
  EXPECT_LT(upright.qdd.norm(), 1e-12);
  EXPECT_LT(upright.lambda.norm(), 1e-12);
}

TEST(RedundantConstraints, ALaterContactsRowsFollowTheRowsLeftOutBeforeThem) {
  const Model model = parse_model(three_wheels, "three.eom");
  // middle_2 = left_2 + c/s (left_1 - middle_1)
  EXPECT_EQ(names(model), (std::vector<std::string>{"left_1", "left_2", "right_1", "middle_1"}));
  ASSERT_EQ(model.redundant_constraints.size(), 2u);
  EXPECT_EQ(model.redundant_constraints[0].constraint.name, "right_2");
  EXPECT_EQ(model.redundant_constraints[1].constraint.name, "middle_2");
  EXPECT_EQ(model.redundant_constraints[1].depends_on, (std::vector<std::string>{"left_1", "left_2", "middle_1"}));
  ASSERT_EQ(model.notes.size(), 2u);
  EXPECT_EQ(model.notes[1].location.line, 26);
  ASSERT_EQ(model.contacts.size(), 3u);
  EXPECT_EQ(rows_of(model.contacts[1]), (std::vector<std::size_t>{2}));
  EXPECT_EQ(rows_of(model.contacts[2]), (std::vector<std::size_t>{3}));
  ASSERT_EQ(model.constraint_locations.size(), 4u);
  EXPECT_EQ(model.constraint_locations[3].line, 26);
}

TEST(RedundantConstraints, IndependentSpeedsCountTheRowsKept) {
  // nq - nc = 6 - 3: the dependent speeds x_dot, y_dot and phiR_dot solved from the rows kept
  const Model model = parse_model(segway + "independent theta, psi, phiL\n", "segway.eom");
  EXPECT_EQ(model.independent_speeds, (std::vector<std::size_t>{3, 2, 4}));
  testing::expect_model_error(
      segway + "independent theta, psi\n", 23, 1,
      "independent: expected nq - nc = 6 - 3 = 3 coordinates (one per degree of freedom), got 2");
}

TEST(RedundantConstraints, AConstraintWrittenTwiceIsLeftOutTheSecondTime) {
  const std::string pendulum = "parameter l = 1.5\n"
                               "coordinate x, y\n"
                               "point p = w + x*a.1 + y*a.2\n"
                               "particle bob(mass = 2, at = p)\n"
                               "gravity = 9.81*a.1\n"
                               "constraint rod: x^2 + y^2 = l^2\n"
                               "constraint again: x^2 + y^2 = l^2\n";
  const Model model = parse_model(pendulum, "pendulum.eom");
  EXPECT_EQ(names(model), (std::vector<std::string>{"rod"}));
  ASSERT_EQ(model.redundant_constraints.size(), 1u);
  EXPECT_EQ(model.redundant_constraints[0].constraint.kind, Constraint::Kind::holonomic);
  EXPECT_EQ(model.redundant_constraints[0].depends_on, (std::vector<std::string>{"rod"}));
  ASSERT_EQ(model.notes.size(), 1u);
  EXPECT_EQ(note_text(model.notes[0]),
            "pendulum.eom:7:12: note: constraint 'again' is redundant: at a generic state its row of Xi is a multiple "
            "of that of 'rod'; left out (the multiplier of 'rod' carries its force); it holds along a motion where it "
            "holds at the start");
  // the equations are the pendulum's with one rod: lambda is its force, -m g x / l^2 ... at rest
  // hanging (x = l, along gravity): lambda 2 x = -m g, lambda = -m g / (2 l)
  const Model once = parse_model(pendulum.substr(0, pendulum.rfind("constraint again")), "pendulum.eom");
  const NamedValues hanging = {{"x", 1.5}};
  const AccelerationSolution a = solve_accelerations(evaluate_equations(model, derive_equations(model), hanging));
  const AccelerationSolution b = solve_accelerations(evaluate_equations(once, derive_equations(once), hanging));
  ASSERT_EQ(a.lambda.size(), 1);
  EXPECT_NEAR(a.lambda(0), -2 * 9.81 / (2 * 1.5), 1e-12);
  EXPECT_NEAR(b.lambda(0), a.lambda(0), 1e-15);
  EXPECT_LT(a.qdd.norm(), 1e-12);
}

}  // namespace
}  // namespace eomgen
