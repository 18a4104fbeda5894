// Bodies on the boundary of the inertias a mass distribution can have (issue 17): a slender rod
// and a thin disk are accepted and give the textbook equations; a model whose mass matrix is then
// singular is refused by the checks of its equations, at the state where it is.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "eomgen/base/error.hpp"
#include "eomgen/derivation/equations_of_motion.hpp"
#include "eomgen/derivation/numeric_evaluation.hpp"
#include "eomgen/language/model_file.hpp"

namespace eomgen {
namespace {

NumericEquations equations_at(const std::string& text, const NamedValues& state) {
  const Model model = parse_model(text, "rod.eom");
  return evaluate_equations(model, derive_equations(model), state);
}

// A uniform slender rod of length l hinged at one end, swinging in the a.1-a.2 plane.
const std::string rod_pendulum =
    "parameter m = 1.5 [kg]\n"
    "parameter l = 0.8 [m]\n"
    "parameter g = 9.81 [m/s^2]\n"
    "coordinate theta\n"
    "frame b = rotate(a, 3, theta)\n"
    "point c = w + l/2*b.1\n"
    "gravity = -g*a.2\n"
    "body rod(mass = m, centre = c, frame = b, inertia = m*l^2/12*diag(0, 1, 1))\n";  // a factor times a matrix

TEST(SlenderBodies, ARodHingedAtItsEndHasTheTextbookMomentOfInertia) {
  const NumericEquations x = equations_at(rod_pendulum, {{"theta", 0.4}, {"theta_dot", 1.1}});
  // J about the hinge = m l^2/12 + m (l/2)^2 = m l^2/3; the torque of gravity m g l/2 cos(theta)
  EXPECT_NEAR(x.mass_matrix(0, 0), 1.5 * 0.8 * 0.8 / 3, 1e-14);
  EXPECT_NEAR(x.forcing(0), -1.5 * 9.81 * 0.4 * std::cos(0.4), 1e-13);
  EXPECT_NEAR(x.kinetic_energy, 0.5 * 1.5 * 0.64 / 3 * 1.1 * 1.1, 1e-14);
}

TEST(SlenderBodies, AThinDiskSpinningAndTiltingHasItsPrincipalMoments) {
  // a thin disk of radius r in its b.1-b.2 plane: J3 = m r^2/2 = J1 + J2 exactly
  const std::string disk =
      "parameter m = 2 [kg]\n"
      "parameter r = 0.3 [m]\n"
      "coordinate tilt, spin\n"
      "frame n = rotate(a, 1, tilt)\n"
      "frame d = rotate(n, 3, spin)\n"
      "body disk(mass = m, centre = w, frame = d, inertia = diag(m*r^2/4, m*r^2/4, m*r^2/2))\n";
  const NumericEquations x = equations_at(disk, {{"tilt", 0.2}, {"spin", 0.7}});
  EXPECT_NEAR(x.mass_matrix(0, 0), 2 * 0.09 / 4, 1e-15);  // about a diameter
  EXPECT_NEAR(x.mass_matrix(1, 1), 2 * 0.09 / 2, 1e-15);  // about the axis
  EXPECT_NEAR(x.mass_matrix(0, 1), 0, 1e-15);
}

TEST(SlenderBodies, ARodSpinningAboutItsOwnAxisIsAcceptedAndItsSingularMassMatrixReported) {
  // the model is valid; its equations cannot be solved for the spin's acceleration
  const std::string spinning =
      "parameter m = 1 [kg]\n"
      "parameter l = 1 [m]\n"
      "coordinate spin\n"
      "frame b = rotate(a, 1, spin)\n"
      "body rod(mass = m, centre = w, frame = b, inertia = diag(0, m*l^2/12, m*l^2/12))\n";
  const Model model = parse_model(spinning, "rod.eom");
  const NumericEquations x = evaluate_equations(model, derive_equations(model), {{"spin", 0.3}});
  EXPECT_EQ(x.mass_matrix(0, 0), 0.0);
  try {
    solve_accelerations(x);
    ADD_FAILURE() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("the mass matrix is not positive definite at this state"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace eomgen
