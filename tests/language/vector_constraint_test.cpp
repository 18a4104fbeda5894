// `constraint NAME: VECTOR = VECTOR [in FRAME]`: one row per component, NAME_1 to NAME_3, each
// holonomic or nonholonomic as a scalar constraint; a component that is identically zero is
// left out with its number, one that depends on the others is redundant (a note), and the rows
// are those of the scalar constraints or the roll statement written for the same components.
#include <Eigen/Dense>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "eomgen/base/error.hpp"
#include "eomgen/derivation/model_equations.hpp"
#include "eomgen/derivation/numeric_evaluation.hpp"
#include "eomgen/language/model_file.hpp"
#include "support/numeric_checks.hpp"

namespace eomgen {
namespace {

using testing::matrices_near;

// A four-bar linkage in the plane of the frame e (lines 1-23): the crank b1 about w, the coupler
// b2 on it, the rocker b3 about p0, l0 from w along e.1; the coupler's end c should meet the
// rocker's end d. Slender rods, gravity along -a.2.
std::string four_bar(const std::string& plane) {
  return "parameter l0 = 1.0 [m]\n"
         "parameter l1 = 0.4 [m]\n"
         "parameter l2 = 1.1 [m]\n"
         "parameter l3 = 0.8 [m]\n"
         "parameter m = 0.5 [kg]\n"
         "parameter g = 9.81 [m/s^2]\n"
         "parameter tilt = 0.4 [-]\n"
         "coordinate q1, q2, q3\n" +
         plane + "\n" +
         "frame b1 = rotate(e, 3, q1)\n"
         "frame b2 = rotate(b1, 3, q2)\n"
         "frame b3 = rotate(e, 3, q3)\n"
         "point p1 = w + l1*b1.1\n"
         "point c = p1 + l2*b2.1\n"
         "point p0 = w + l0*e.1\n"
         "point d = p0 + l3*b3.1\n"
         "point g1 = w + l1/2*b1.1\n"
         "point g2 = p1 + l2/2*b2.1\n"
         "point g3 = p0 + l3/2*b3.1\n"
         "body crank(mass = m, centre = g1, frame = b1, inertia = m*l1^2/12*diag(0, 1, 1))\n"
         "body coupler(mass = m, centre = g2, frame = b2, inertia = m*l2^2/12*diag(0, 1, 1))\n"
         "body rocker(mass = m, centre = g3, frame = b3, inertia = m*l3^2/12*diag(0, 1, 1))\n"
         "gravity = -g*a.2\n";
}

const std::string planar_four_bar = four_bar("frame e = a");
const std::string tilted_four_bar = four_bar("frame e = rotate(a, 1, tilt)");

const NamedValues four_bar_states[] = {{{"q1", 0.7}, {"q2", 1.9}, {"q3", 1.2}, {"q1_dot", 0.8}, {"q2_dot", -1.3},
                                        {"q3_dot", 0.4}},
                                       {{"q1", -2.1}, {"q2", 0.3}, {"q3", 2.6}, {"q1_dot", -0.2}, {"q2_dot", 0.9},
                                        {"q3_dot", 1.7}}};

TEST(VectorConstraint, PlanarFourBarHasTheEquationsOfTwoScalarConstraints) {
  const Model vector = parse_model(planar_four_bar + "constraint loop: position(c) = position(d)\n", "four_bar.eom");
  const Model scalar = parse_model(planar_four_bar +
                                       "constraint loop_1: dot(position(c) - position(d), a.1) = 0\n"
                                       "constraint loop_2: dot(position(c) - position(d), a.2) = 0\n",
                                   "four_bar.eom");
  // the component along a.3, the normal of the plane, is zero: no loop_3, and no note
  ASSERT_EQ(vector.system.constraints().size(), 2u);
  EXPECT_EQ(vector.system.constraints()[0].name, "loop_1");
  EXPECT_EQ(vector.system.constraints()[1].name, "loop_2");
  for (const Constraint& c : vector.system.constraints()) EXPECT_EQ(c.kind, Constraint::Kind::holonomic);
  EXPECT_TRUE(vector.notes.empty());
  EXPECT_TRUE(vector.redundant_constraints.empty());
  ASSERT_EQ(vector.constraint_locations.size(), 2u);
  for (const SourceLocation& at : vector.constraint_locations) {
    EXPECT_EQ(at.line, 24);
    EXPECT_EQ(at.column, 12);
  }
  const ModelEquations v_eom = derive_equations(vector), s_eom = derive_equations(scalar);
  for (const NamedValues& state : four_bar_states) {
    const NumericEquations x = evaluate_equations(vector, v_eom, state), y = evaluate_equations(scalar, s_eom, state);
    EXPECT_TRUE(matrices_near(x.mass_matrix, y.mass_matrix, 1e-14));
    EXPECT_TRUE(matrices_near(x.forcing, y.forcing, 1e-14));
    EXPECT_TRUE(matrices_near(x.constraint_jacobian, y.constraint_jacobian, 1e-14));
    EXPECT_TRUE(matrices_near(x.constraint_acceleration_term, y.constraint_acceleration_term, 1e-14));
    EXPECT_TRUE(matrices_near(x.holonomic_residuals, y.holonomic_residuals, 1e-14));
    // and the rows are those of the loop: Xi = d(c - d)/dq in a's first two components, by hand
    const double q1 = state.at("q1"), q12 = q1 + state.at("q2"), q3 = state.at("q3");
    const double l1 = 0.4, l2 = 1.1, l3 = 0.8;
    Eigen::MatrixXd xi(2, 3);
    xi << -l1 * std::sin(q1) - l2 * std::sin(q12), -l2 * std::sin(q12), l3 * std::sin(q3),  //
        l1 * std::cos(q1) + l2 * std::cos(q12), l2 * std::cos(q12), -l3 * std::cos(q3);
    EXPECT_TRUE(matrices_near(x.constraint_jacobian, xi, 1e-14));
  }
}

TEST(VectorConstraint, RowsInAFrameAreTheComponentsAlongItsAxes) {
  const Model in_a = parse_model(planar_four_bar + "constraint loop: position(c) = position(d)\n", "four_bar.eom");
  const Model in_b1 =
      parse_model(planar_four_bar + "constraint loop: position(c) = position(d) in b1\n", "four_bar.eom");
  ASSERT_EQ(in_b1.system.constraints().size(), 2u);
  EXPECT_EQ(in_b1.system.constraints()[1].name, "loop_2");
  // phi_b1 = C_{b1 a} phi_a, C_{b1 a} = C3(q1)
  for (const NamedValues& state : four_bar_states) {
    const NumericEquations a = evaluate_equations(in_a, derive_equations(in_a), state);
    const NumericEquations b = evaluate_equations(in_b1, derive_equations(in_b1), state);
    const double q1 = state.at("q1");
    Eigen::Matrix2d c3;
    c3 << std::cos(q1), std::sin(q1), -std::sin(q1), std::cos(q1);
    EXPECT_TRUE(matrices_near(b.holonomic_residuals, c3 * a.holonomic_residuals, 1e-14));
  }
}

TEST(VectorConstraint, APlanarLoopInATiltedPlaneHasARedundantRowWithANote) {
  // the plane's normal is e.3 = -sin(tilt) a.2 + cos(tilt) a.3: the component along a.3 is
  // tan(tilt) times the one along a.2, and not zero
  const Model model = parse_model(tilted_four_bar + "constraint loop: position(c) = position(d)\n", "tilted.eom");
  ASSERT_EQ(model.system.constraints().size(), 3u);
  EXPECT_EQ(model.system.constraints()[0].name, "loop_1");
  EXPECT_EQ(model.system.constraints()[1].name, "loop_2");
  EXPECT_EQ(model.system.constraints()[2].name, "loop_3");
  ASSERT_EQ(model.redundant_constraints.size(), 1u);
  const RedundantConstraint& dropped = model.redundant_constraints[0];
  EXPECT_EQ(dropped.constraint.name, "loop_3");
  EXPECT_EQ(dropped.constraint.kind, Constraint::Kind::holonomic);
  EXPECT_EQ(dropped.depends_on, (std::vector<std::string>{"loop_2"}));
  EXPECT_EQ(dropped.location.line, 24);
  EXPECT_EQ(dropped.location.column, 12);
  ASSERT_EQ(model.notes.size(), 1u);
  EXPECT_EQ(note_text(model.notes[0]),
            "tilted.eom:24:12: note: constraint 'loop_3' is redundant: at a generic state its row of Xi is a multiple "
            "of that of 'loop_2'; kept, the solves take independent rows at each state and give a row they leave out "
            "the multiplier 0 (docs/conventions.md, Redundant constraints)");
  // the redundant row: its value is tan(tilt) times loop_2's, at any state
  for (const NamedValues& state : four_bar_states) {
    const NumericEquations x = evaluate_equations(model, derive_equations(model), state);
    const GiNaC::ex value = dropped.constraint.expression.subs(numeric_substitution(model, state)).evalf();
    ASSERT_TRUE(GiNaC::is_a<GiNaC::numeric>(value)) << value;
    EXPECT_NEAR(GiNaC::ex_to<GiNaC::numeric>(value).to_double(), std::tan(0.4) * x.holonomic_residuals(1), 1e-14);
  }
}

TEST(VectorConstraint, VelocityOfTheContactEqualToZeroGivesTheRowsOfRoll) {
  // a ball on the plane z = 0 (lines 1-6): no slip at its lowest point k
  const std::string ball =
      "parameter R = 0.5\n"
      "coordinate x, y, phi, theta, psi\n"
      "frame b = euler(a, 313, phi, theta, psi)\n"
      "point c = w + [x, y, R] in a\n"
      "point k = c - R*a.3\n"
      "body ball(mass = 1, centre = c, frame = b, inertia = diag(0.1, 0.1, 0.1))\n";
  const Model roll = parse_model(ball + "roll stick(body = ball, contact = k)\n", "ball.eom");
  const Model vector = parse_model(
      ball + "constraint stick: velocity(c) + cross(angular_velocity(b), position(k, c)) = 0\n", "ball.eom");
  const Model reversed = parse_model(
      ball + "constraint stick: 0 = velocity(c) + cross(angular_velocity(b), position(k, c))\n", "ball.eom");
  // the component along a.3 is zero: stick_1 and stick_2, nonholonomic
  ASSERT_EQ(vector.system.constraints().size(), 2u);
  ASSERT_EQ(reversed.system.constraints().size(), 2u);
  EXPECT_EQ(vector.system.constraints()[0].name, "stick_1");
  EXPECT_EQ(vector.system.constraints()[1].name, "stick_2");
  for (const Constraint& c : vector.system.constraints()) EXPECT_EQ(c.kind, Constraint::Kind::nonholonomic);
  EXPECT_TRUE(vector.notes.empty());
  const NamedValues state = {{"x", 0.2}, {"y", -0.3}, {"phi", 0.4}, {"theta", 1.1}, {"psi", -0.6},
                             {"x_dot", 0.5}, {"phi_dot", 1.2}, {"theta_dot", -0.7}, {"psi_dot", 0.9}};
  const NumericEquations r = evaluate_equations(roll, derive_equations(roll), state);
  const NumericEquations v = evaluate_equations(vector, derive_equations(vector), state);
  const NumericEquations n = evaluate_equations(reversed, derive_equations(reversed), state);
  EXPECT_TRUE(matrices_near(v.constraint_jacobian, r.constraint_jacobian, 1e-14));
  EXPECT_TRUE(matrices_near(v.constraint_acceleration_term, r.constraint_acceleration_term, 1e-14));
  EXPECT_TRUE(matrices_near(n.constraint_jacobian, -r.constraint_jacobian, 1e-14));
}

TEST(VectorConstraint, AComponentDependentOnTheOthersInThreeDimensionsIsRedundant) {
  // a bead on the line through w along u = a.1 + a.2: position(p) x u = (-z, z, x - y), whose
  // second row is minus the first
  const Model model = parse_model("coordinate x, y, z\n"
                                  "point p = w + x*a.1 + y*a.2 + z*a.3\n"
                                  "particle bead(mass = 1, at = p)\n"
                                  "constraint line: cross(position(p), a.1 + a.2) = 0\n",
                                  "bead.eom");
  ASSERT_EQ(model.system.constraints().size(), 3u);
  EXPECT_EQ(model.system.constraints()[0].name, "line_1");
  EXPECT_EQ(model.system.constraints()[1].name, "line_2");
  EXPECT_EQ(model.system.constraints()[2].name, "line_3");
  ASSERT_EQ(model.notes.size(), 1u);
  EXPECT_EQ(note_text(model.notes[0]),
            "bead.eom:4:12: note: constraint 'line_2' is redundant: at a generic state its row of Xi is a multiple of "
            "that of 'line_1'; kept, the solves take independent rows at each state and give a row they leave out the "
            "multiplier 0 (docs/conventions.md, Redundant constraints)");
  ASSERT_EQ(model.constraint_locations.size(), 3u);
  EXPECT_EQ(model.constraint_locations[1].line, 4);
}

// --- errors ---

struct ErrorCase {
  std::string constraint;  // appended to the planar four-bar as line 24
  int column;
  std::string message;
};

TEST(VectorConstraint, ErrorsSayWhatWasExpected) {
  const ErrorCase cases[] = {
      {"constraint loop: position(c) = q1", 32,
       "constraint 'loop': the left side is a vector and this one a scalar: expected a vector on both sides (or 0, "
       "the zero vector), or a scalar on both"},
      {"constraint loop: q1 = position(d)", 18,
       "constraint 'loop': the right side is a vector and this one a scalar: expected a vector on both sides (or 0, "
       "the zero vector), or a scalar on both"},
      {"constraint loop: position(c) = diag(1, 1, 1)", 32,
       "constraint 'loop': expected a scalar or a vector on each side, got a matrix"},
      {"constraint loop: q1 = q3 in b1", 29,
       "constraint 'loop': 'in FRAME' resolves the rows of a vector constraint, and both sides are scalars: expected "
       "no 'in'"},
      {"constraint loop: position(c) = position(d) in f", 47, "unknown frame 'f'"},
      // a.3 components: 0 and l0, which no coordinate changes
      {"constraint loop: position(c) = position(d) + l0*a.3", 12,
       "constraint 'loop': its component along a.3 (row 'loop_3') does not depend on the coordinates at a generic "
       "state and is not zero there, so the constraint cannot hold: expected sides that can be equal"},
      {"constraint loop: position(c) = position(c)", 12,
       "constraint 'loop' is identically zero: each of its components vanishes at a generic state"},
      // not linear in the rates, as the scalar constraint: the row is named
      {"constraint loop: q1_dot*velocity(c) = 0", 12,
       "nonholonomic constraint 'loop_1': the constraint must be linear in the rates, but it is not linear in "
       "'q1_dot'"},
  };
  for (const ErrorCase& c : cases) {
    SCOPED_TRACE(c.constraint);
    try {
      parse_model(planar_four_bar + c.constraint + "\n", "test.eom");
      ADD_FAILURE() << "expected a SourceError";
    } catch (const SourceError& e) {
      EXPECT_EQ(e.location().line, 24) << e.what();
      EXPECT_EQ(e.location().column, c.column) << e.what();
      EXPECT_THAT(e.message(), ::testing::HasSubstr(c.message));
    }
  }
}

}  // namespace
}  // namespace eomgen
