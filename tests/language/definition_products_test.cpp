// dot(), cross(), norm() and unit() in frame and point definitions: the same equations as the
// definitions multiplied out by hand, whatever the order of the statements; a cycle through them
// is a cycle; unit() of a zero vector is an error at the vector.
//
// Conventions (docs/conventions.md): C_ba = C1(theta) C3(psi) for b = rotate(rotate(a, 3, psi), 1,
// theta), so the components in a of b.1, b.2, b.3 are the rows of C_ba:
//   b.1 = [c_psi, s_psi, 0], b.2 = [-c_theta s_psi, c_theta c_psi, s_theta],
//   b.3 = [s_theta s_psi, -s_theta c_psi, c_theta].
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "eomgen/base/error.hpp"
#include "eomgen/derivation/model_equations.hpp"
#include "eomgen/derivation/numeric_evaluation.hpp"
#include "eomgen/language/model_file.hpp"
#include "support/expect_model_error.hpp"
#include "support/numeric_checks.hpp"

namespace eomgen {
namespace {

using testing::expect_model_error;
using testing::matrices_near;

const std::string declarations =
    "parameter l = 0.7\n"
    "parameter g = 9.81\n"
    "coordinate psi, theta, q3\n"
    "gravity = -g*a.3\n"
    "particle bead(mass = 1.5, at = p)\n"
    "body plate(mass = 2, centre = p, frame = c, inertia = diag(1, 2, 3))\n";

// b.2 . a.3 = s_theta; b.3 x a.3 = [-s_theta c_psi, -s_theta s_psi, 0]; |l b.1 + l b.2| = sqrt(2) l;
// unit(2 b.2) = b.2; the axis b.1 in a is [c_psi, s_psi, 0]
const std::string with_products =
    "frame h = rotate(a, 3, psi)\n"
    "frame b = rotate(h, 1, theta)\n"
    "point p = w + l*dot(b.2, a.3)*a.1 + l*cross(b.3, a.3) + norm(l*b.1 + l*b.2)*a.3 + unit(2*b.2)\n"
    "frame c = axis_angle(a, [dot(b.1, a.1), dot(b.1, a.2), dot(b.1, a.3)], q3)\n";
const std::string by_hand =
    "frame h = rotate(a, 3, psi)\n"
    "frame b = rotate(h, 1, theta)\n"
    "point p = w + l*sin(theta)*a.1 + [-l*sin(theta)*cos(psi), -l*sin(theta)*sin(psi), 0] in a + sqrt(2)*l*a.3 + b.2\n"
    "frame c = axis_angle(a, [cos(psi), sin(psi), 0], q3)\n";

NumericEquations equations_at(const std::string& text, const NamedValues& state) {
  const Model model = parse_model(text, "test.eom");
  return evaluate_equations(model, derive_equations(model), state);
}

void expect_same_equations(const std::string& a, const std::string& b) {
  for (const NamedValues& state : {NamedValues{{"psi", 0.3}, {"theta", -0.8}, {"q3", 1.1}, {"psi_dot", 0.4},
                                               {"theta_dot", -1.3}, {"q3_dot", 0.9}},
                                   NamedValues{{"psi", -2.1}, {"theta", 0.5}, {"q3", -0.2}, {"psi_dot", -0.7},
                                               {"theta_dot", 0.2}, {"q3_dot", 1.6}}}) {
    const NumericEquations x = equations_at(a, state), y = equations_at(b, state);
    EXPECT_TRUE(matrices_near(x.mass_matrix, y.mass_matrix, 1e-12));
    EXPECT_TRUE(matrices_near(x.forcing, y.forcing, 1e-12));
    EXPECT_NEAR(x.potential_energy, y.potential_energy, 1e-12);
  }
}

TEST(DefinitionProducts, DotCrossNormUnitInDefinitionsGiveTheEquationsOfTheHandExpandedDefinitions) {
  expect_same_equations(declarations + with_products, declarations + by_hand);
}

TEST(DefinitionProducts, DefinitionsThatNameLaterOnesGiveTheSameEquations) {
  // the products name b and p before their definitions; the elements come first as well
  std::istringstream lines(with_products);
  std::string reversed;
  for (std::string line; std::getline(lines, line);) reversed = line + "\n" + reversed;
  expect_same_equations(reversed + declarations, declarations + by_hand);
}

TEST(DefinitionProducts, APositionInsideAFrameDefinitionIsBuiltFirst) {
  // the angle of c is the a.1 coordinate of p, which is defined after c from b
  const std::string text =
      "parameter l = 0.7\n"
      "coordinate psi\n"
      "frame c = rotate(a, 3, dot(position(p), a.1))\n"
      "frame b = rotate(a, 3, psi)\n"
      "point p = w + l*b.1\n"
      "body plate(mass = 2, centre = p, frame = c, inertia = diag(1, 2, 3))\n";
  const NumericEquations x = equations_at(text, {{"psi", 0.4}, {"psi_dot", 1.2}});
  // T = 1/2 m l^2 psi_dot^2 + 1/2 J3 (d/dt (l cos psi))^2 = 1/2 (2 l^2 + 3 l^2 sin^2 psi) psi_dot^2
  const double l = 0.7, s = std::sin(0.4);
  EXPECT_NEAR(x.mass_matrix(0, 0), 2 * l * l + 3 * l * l * s * s, 1e-12);
}

TEST(DefinitionProducts, ACycleThroughADotProductIsReportedAsACycleAtTheDefinition) {
  const std::string text =
      "coordinate q\n"
      "frame b = rotate(a, 3, dot(position(p), a.1))\n"
      "point p = w + q*b.1\n"
      "particle m(mass = 1, at = p)\n";
  expect_model_error(text, 2, 7, "frame 'b' is defined through a cycle: b -> p -> b");
}

const std::string pendulum =
    "parameter l = 1\n"
    "parameter s = 0\n"
    "coordinate theta\n"
    "frame b = rotate(a, 3, theta)\n"
    "particle bob(mass = 1, at = p)\n";

TEST(DefinitionProducts, UnitOfAZeroVectorIsAnErrorAtTheVector) {
  const std::string zero = "unit(): the vector is zero";
  // zero as written
  expect_model_error(pendulum + "point p = w + l*unit(b.1 - b.1)\n", 6, 22, zero);
  // zero once resolved in one frame: b.3 = a.3
  expect_model_error(pendulum + "point p = w + l*unit(b.3 - a.3)\n", 6, 22, zero);
  // zero at the parameters' default values
  expect_model_error(pendulum + "point p = w + l*unit(s*b.1)\n", 6, 22, zero);
  // anywhere an expression can be, not only in definitions
  expect_model_error(pendulum + "point p = w + l*b.1\noutput o = unit(position(p, p))\n", 7, 17, zero);
}

TEST(DefinitionProducts, UnitIsTheDirectionOfItsVectorEverywhere) {
  const Model model = parse_model(pendulum + "point p = w + l*b.1\noutput o = unit(3*position(p) + 4*l*a.3)\n",
                                  "test.eom");
  const NumericEquations x = evaluate_equations(model, derive_equations(model), {{"theta", 0.6}});
  ASSERT_EQ(x.outputs.size(), 3u);
  EXPECT_NEAR(x.outputs[0].second, 0.6 * std::cos(0.6), 1e-12);
  EXPECT_NEAR(x.outputs[1].second, 0.6 * std::sin(0.6), 1e-12);
  EXPECT_NEAR(x.outputs[2].second, 0.8, 1e-12);
}

TEST(DefinitionProducts, RatesStayOutOfDefinitions) {
  expect_model_error(pendulum + "point p = w + l*b.1 + dot(velocity(q), a.1)*a.2\npoint q = w + l*b.2\n", 6, 27,
                  "velocity() may not be used in frame or point definitions: a position or an attitude depends on "
                  "coordinates and time, not on rates");
}

}  // namespace
}  // namespace eomgen
