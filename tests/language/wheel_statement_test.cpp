// The wheel statement: a rigid disk rolling without slip on a fixed plane. Its equations against
// the shipped rolling coin's hand-placed contact and roll; its contact point against the lowest
// point of a tilted circle; its multipliers against Newton's laws for a disk standing and a disk
// pushed; its contact row present only where the model leaves the wheel free to leave the plane.
// Also roll's normal, which is normalized.
//
// Conventions (docs/conventions.md): M qdd = F + Xi^T lambda; C_ba of rotate(a, k, x) is Ck(x).
// For normal = a.3 the tangents are t1 = a.2 and t2 = -a.1 (docs/model-language.md).
#include <Eigen/Dense>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "eomgen/base/error.hpp"
#include "eomgen/derivation/linearization.hpp"
#include "eomgen/derivation/model_equations.hpp"
#include "eomgen/derivation/numeric_evaluation.hpp"
#include "eomgen/language/model_file.hpp"
#include "support/expect_model_error.hpp"
#include "support/numeric_checks.hpp"
#include "support/source_dir.hpp"

namespace eomgen {
namespace {

using testing::expect_model_error;
using testing::matrices_near;

std::string shipped_text(const std::string& name) {
  std::ifstream in(testing::shipped_model_path(name));
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

// the shipped coin with its hand-placed contact u and roll replaced by a wheel
std::string coin_as_wheel() {
  std::string text = shipped_text("rolling_coin");
  text = replaced(text, "point u = z - r*s.3", "");
  text = replaced(text, "roll no_slip(body = coin, contact = u, normal = a.3)",
                  "wheel no_slip(body = coin, centre = z, axle = p.1, radius = r, normal = a.3)");
  return replaced(text, "output contact = position(u)", "output contact = position(no_slip_contact)");
}

const NamedValues coin_states[] = {
    {{"x", 0.1}, {"y", -0.4}, {"psi", 0.3}, {"theta", 0.2}, {"phi", 0.5}, {"psi_dot", 0.7}, {"theta_dot", -0.4},
     {"phi_dot", 2.0}, {"x_dot", 0.01}, {"y_dot", -0.02}},
    {{"psi", -1.2}, {"theta", -0.9}, {"phi", 2.5}, {"psi_dot", -1.1}, {"theta_dot", 0.8}, {"phi_dot", -3.0}}};

TEST(WheelStatement, CoinWrittenAsAWheelHasTheEquationsOfTheShippedCoin) {
  const Model roll = load_model(testing::shipped_model_path("rolling_coin"));
  const Model wheel = parse_model(coin_as_wheel(), "coin_wheel.eom");
  ASSERT_EQ(wheel.system.constraints().size(), 2u);  // the centre is placed on the plane: no contact row
  EXPECT_EQ(wheel.system.constraints()[0].name, "no_slip_1");
  EXPECT_EQ(wheel.system.constraints()[1].name, "no_slip_2");
  const ModelEquations roll_eom = derive_equations(roll), wheel_eom = derive_equations(wheel);
  for (const NamedValues& state : coin_states) {
    const NumericEquations x = evaluate_equations(roll, roll_eom, state);
    const NumericEquations y = evaluate_equations(wheel, wheel_eom, state);
    EXPECT_TRUE(matrices_near(y.mass_matrix, x.mass_matrix, 1e-15));
    EXPECT_TRUE(matrices_near(y.forcing, x.forcing, 1e-15));
    EXPECT_TRUE(matrices_near(y.constraint_jacobian, x.constraint_jacobian, 1e-15));
    EXPECT_TRUE(matrices_near(y.constraint_acceleration_term, x.constraint_acceleration_term, 1e-15));
    for (std::size_t i = 0; i < x.outputs.size(); ++i) EXPECT_NEAR(y.outputs[i].second, x.outputs[i].second, 1e-15);
  }
  // rolling upright along -a.2 at twice the critical speed sqrt(g r / 3): the same linear model
  const double r = 12.9e-3, w = 2 * std::sqrt(9.81 * r / 3) / r;
  const NamedValues rolling = {{"phi_dot", w}, {"y_dot", -r * w}};
  const LinearModel a = linearize(roll, roll_eom, linearize_symbolic(roll, roll_eom), rolling);
  const LinearModel b = linearize(wheel, wheel_eom, linearize_symbolic(wheel, wheel_eom), rolling);
  EXPECT_EQ(b.state_names, a.state_names);
  EXPECT_TRUE(matrices_near(b.A, a.A, 1e-9 * a.A.cwiseAbs().maxCoeff()));
  const Eigen::VectorXcd ea = assess_stability(a.A).eigenvalues, eb = assess_stability(b.A).eigenvalues;
  ASSERT_EQ(ea.size(), eb.size());
  for (Eigen::Index i = 0; i < ea.size(); ++i) EXPECT_LT(std::abs(ea(i) - eb(i)), 1e-9 * (1 + std::abs(ea(i))));
}

// a disk of radius r: heading psi about a.3, tilt theta about h.1, the wheel frame f (steered or
// not), the spin about the axle f.2 (given to the wheel twice as long); pushed along a.1 at its centre
std::string disk_model(const std::string& coordinates, const std::string& wheel_frame, const std::string& centre) {
  return "parameter r = 0.3 [m]\n"
         "parameter m = 2 [kg]\n"
         "parameter g = 9.81 [m/s^2]\n"
         "parameter P = 0 [N]\n"
         "coordinate " + coordinates + "\n"
         "frame h = rotate(a, 3, psi)\n"
         "frame l = rotate(h, 1, theta)\n" +
         wheel_frame + "\n"
         "frame d = rotate(f, 2, spin)\n" +
         centre + "\n"
         "body disk(mass = m, centre = c, frame = d, inertia = diag(m*r^2/4, m*r^2/2, m*r^2/4))\n"
         "gravity = -g*a.3\n"
         "force push(at = c, force = P*a.1)\n"
         "wheel rim(body = disk, centre = c, axle = 2*f.2, radius = r, normal = a.3)\n"
         "output contact_position = position(rim_contact)\n";
}

// steered by delta about l.3, the centre free in all three directions
const std::string steered_disk = disk_model("x, y, z, psi, theta, delta, spin", "frame f = rotate(l, 3, delta)",
                                            "point c = w + x*a.1 + y*a.2 + z*a.3");
// not steered, the centre free
const std::string free_disk = disk_model("x, y, z, psi, theta, spin", "frame f = l", "point c = w + x*a.1 + y*a.2 + z*a.3");

// C_fa = C3(delta) C1(theta) C3(psi)
Eigen::Matrix3d c1(double x) { return Eigen::AngleAxisd(-x, Eigen::Vector3d::UnitX()).toRotationMatrix(); }
Eigen::Matrix3d c3(double x) { return Eigen::AngleAxisd(-x, Eigen::Vector3d::UnitZ()).toRotationMatrix(); }

TEST(WheelStatement, ContactOfATiltedSteeredDiskIsTheLowestPointOfItsRim) {
  const Model model = parse_model(steered_disk, "disk.eom");
  const double r = 0.3, psi = 0.4, theta = -0.35, delta = 0.8;
  const Eigen::Vector3d centre(0.2, -0.1, 0.5);
  const NumericEquations x = evaluate_equations(model, derive_equations(model),
                                                {{"x", centre(0)}, {"y", centre(1)}, {"z", centre(2)}, {"psi", psi},
                                                 {"theta", theta}, {"delta", delta}, {"spin", 1.0}});
  const Eigen::Vector3d k(x.outputs[0].second, x.outputs[1].second, x.outputs[2].second);
  // the axle in a: the second row of C_fa
  const Eigen::Vector3d e = (c3(delta) * c1(theta) * c3(psi)).row(1).transpose();
  // on the rim: r from the centre, across the axle ...
  EXPECT_NEAR((k - centre).norm(), r, 1e-12);
  EXPECT_NEAR((k - centre).dot(e), 0, 1e-12);
  // ... and its lowest point: a circle of radius r whose normal is e reaches r sqrt(1 - e_3^2) below
  // its centre
  EXPECT_NEAR(k(2), centre(2) - r * std::sqrt(1 - e(2) * e(2)), 1e-12);
}

TEST(WheelStatement, ContactRowIsAddedWhereTheCentreIsFreeInHeight) {
  const Model model = parse_model(steered_disk, "disk.eom");
  ASSERT_EQ(model.system.constraints().size(), 3u);
  EXPECT_EQ(model.system.constraints()[2].name, "rim_3");
  EXPECT_EQ(model.system.constraints()[2].kind, Constraint::Kind::holonomic);
}

TEST(WheelStatement, ContactRowIsLeftOutWhereTheCentreIsPlacedFromAContactPoint) {
  // as the rear wheel of a bicycle: the centre r above a point k of the plane, along the
  // direction of the wheel's plane that is perpendicular to its axle l.2
  const std::string placed =
      disk_model("x, y, psi, theta, spin", "frame f = l", "point ground = w + x*a.1 + y*a.2\npoint c = ground + r*l.3");
  const Model model = parse_model(placed, "rear.eom");
  ASSERT_EQ(model.system.constraints().size(), 2u);
  EXPECT_EQ(model.system.constraints()[0].name, "rim_1");
  EXPECT_EQ(model.system.constraints()[1].name, "rim_2");
}

TEST(WheelStatement, MultipliersAreTheForcesOfThePlaneOnTheWheel) {
  const Model model = parse_model(free_disk, "disk.eom");
  const ModelEquations eom = derive_equations(model);
  const double m = 2, g = 9.81, r = 0.3;
  // standing still upright on the plane: the plane carries the weight, along n
  const AccelerationSolution standing = solve_accelerations(evaluate_equations(model, eom, {{"z", r}}));
  ASSERT_EQ(standing.lambda.size(), 3);
  EXPECT_NEAR(standing.lambda(0), 0, 1e-12);
  EXPECT_NEAR(standing.lambda(1), 0, 1e-12);
  EXPECT_NEAR(standing.lambda(2), m * g, 1e-12);
  EXPECT_LT(standing.qdd.norm(), 1e-12);
  // pushed along a.1 at the centre, the axle along a.2: m a = P + F, J alpha = -r F, a = r alpha
  // with J = m r^2 / 2 give the friction F = -P/3 along a.1, that is +P/3 along t2 = -a.1
  const double P = 1.5;
  const AccelerationSolution pushed = solve_accelerations(evaluate_equations(model, eom, {{"z", r}, {"P", P}}));
  EXPECT_NEAR(pushed.lambda(0), 0, 1e-12);
  EXPECT_NEAR(pushed.lambda(1), P / 3, 1e-12);
  EXPECT_NEAR(pushed.lambda(2), m * g, 1e-12);
  EXPECT_NEAR(pushed.qdd(0), 2 * P / (3 * m), 1e-12);
}

TEST(WheelStatement, RollWithALongerNormalHasTheSameRowsAndMultipliers) {
  const Model unit = load_model(testing::shipped_model_path("rolling_coin"));
  const Model longer = parse_model(replaced(shipped_text("rolling_coin"), "normal = a.3)", "normal = 2*a.3)"),
                                   "coin.eom");
  const ModelEquations unit_eom = derive_equations(unit), longer_eom = derive_equations(longer);
  for (const NamedValues& state : coin_states) {
    const NumericEquations x = evaluate_equations(unit, unit_eom, state);
    const NumericEquations y = evaluate_equations(longer, longer_eom, state);
    EXPECT_TRUE(matrices_near(y.constraint_jacobian, x.constraint_jacobian, 1e-15));
    EXPECT_TRUE(matrices_near(solve_accelerations(y).lambda, solve_accelerations(x).lambda, 1e-12));
  }
}

// --- errors, each at the argument that is wrong ---

// an upright coin on lines 1-8; each case appends its wheel on line 9
const std::string coin =
    "parameter r = 0.3 [m]\n"
    "coordinate x, y, psi, theta, phi\n"
    "frame h = rotate(a, 3, psi)\n"
    "frame l = rotate(h, 1, theta)\n"
    "frame f = rotate(l, 2, phi)\n"
    "point c = w + x*a.1 + y*a.2 + r*cos(theta)*a.3\n"
    "body disk(mass = 1, centre = c, frame = f, inertia = diag(1, 2, 1))\n"
    "particle bead(mass = 1, at = c)\n";

TEST(WheelStatement, ErrorsSayWhichArgumentIsWrongAndWhatWasExpected) {
  struct Case {
    std::string arguments;
    int column;
    std::string message;
  };
  const std::string rest = ", centre = c, axle = f.2, radius = r, normal = a.3";
  const Case cases[] = {
      {"body = disc" + rest, 18, "unknown rigid body 'disc'; did you mean 'disk'?"},
      {"body = bead" + rest, 18, "'bead' is a particle, not a rigid body"},
      {"body = disk, centre = c, axle = f.2, radius = r, normal = sin(theta)*a.3 + a.1", 69,
       "wheel 'rim': the plane's normal must be a constant vector"},
      {"body = disk, centre = c, axle = f.2, radius = r, normal = a.3 - a.3", 69, "wheel 'rim': the plane's normal is zero"},
      // f.2 = l.2: zero only once resolved in one frame
      {"body = disk, centre = c, axle = f.2 - l.2, radius = r, normal = a.3", 43, "wheel 'rim': 'axle': the vector is zero"},
      {"body = disk, centre = c, axle = f.2, radius = -r, normal = a.3", 57, "wheel 'rim': 'radius' must be a positive constant"},
      {"body = disk, centre = c, axle = f.2, radius = r*theta, normal = a.3", 57,
       "wheel 'rim': 'radius' must be a positive constant"},
      {"body = disk, centre = c, axle = a.3, radius = r, normal = a.3", 43,
       "wheel 'rim': the axle is along the plane's normal at a generic state"},
      {"body = disk, centre = c, axle = h.1, radius = r, normal = a.3", 43,
       "wheel 'rim': the axle turns relative to the body 'disk'"},
      {"body = disk, centre = c, axle = f.2, radius = r, normal = a.3, plane = c", 82, "wheel 'rim': the point 'plane' moves"},
      {"body = disk, center = c, axle = f.2, normal = a.3", 1, "wheel 'rim': missing argument 'radius'"},
      {"body = disk, centre = c, axle = f.2, radius = r, normal = a.3, contact = c", 74,
       "wheel 'rim': unknown argument 'contact'"}};
  for (const Case& c : cases) expect_model_error(coin + "wheel rim(" + c.arguments + ")\n", 9, c.column, c.message);
}

TEST(WheelStatement, ACentrePlacedFromItsOwnContactIsACycle) {
  expect_model_error(replaced(coin, "point c = w + x*a.1 + y*a.2 + r*cos(theta)*a.3", "point c = rim_contact + r*l.3") +
                         "wheel rim(body = disk, centre = c, axle = f.2, radius = r, normal = a.3)\n",
                     6, 7, "point 'c' is defined through a cycle: c -> rim_contact -> c");
}

}  // namespace
}  // namespace eomgen
