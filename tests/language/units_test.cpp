// Units in the model language (docs/model-language.md, "Units"): what they are written as, what a
// model with units must give, how the coordinates' units are inferred, and what is checked, each
// error with its whole located message.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "eomgen/base/error.hpp"
#include "eomgen/derivation/model_equations.hpp"
#include "eomgen/language/model_file.hpp"
#include "support/expect_model_error.hpp"
#include "support/source_dir.hpp"

namespace eomgen {
namespace {

const Dimension kg = Dimension::mass(), m = Dimension::length(), s = Dimension::time();
const Dimension newton = kg * m / (s * s);

// A pendulum with units, lines 1-6; the cases add their statements after it, from line 7.
const std::string pendulum =
    "parameter mass = 1 [kg]\n"
    "parameter l = 0.5 [m]\n"
    "parameter F = 2 [N]\n"
    "coordinate theta\n"
    "frame b = rotate(a, 3, theta)\n"
    "point p = w + l*b.1\n"
    "body bob(mass = mass, centre = p, frame = b, inertia = mass*l^2*diag(0, 1, 1))\n";

std::string error_of(const std::string& text) { return testing::model_error_text(text, "h.eom"); }

Dimension dimension_of(const Model& model, const std::string& name) {
  const auto symbol = model.system.variables().find(name);
  if (!symbol || !model.dimensions.count(*symbol)) {
    ADD_FAILURE() << "no dimension for " << name;
    return Dimension();
  }
  return model.dimensions.at(*symbol);
}

// --- models without units ---

TEST(Units, AModelWithoutUnitsIsReadAsBeforeAndCarriesNoDimensions) {
  const Model model = parse_model("parameter k = 2\ncoordinate x\npoint p = w + x*a.1\nparticle m(mass = 1, at = p)\n"
                                  "potential energy = k*x^2 + x\n",  // inconsistent, but no units, so unchecked
                                  "h.eom");
  EXPECT_TRUE(model.dimensions.empty());
  EXPECT_EQ(model.system.variables().parameters()[0].unit, "");
}

// --- writing units ---

TEST(Units, UnitsAreKeptAsWrittenAfterParametersCoordinatesAndInputs) {
  const Model model = parse_model("parameter d = 0.4 [ N s/m ]\nparameter mass = 1 [kg]\nparameter r = 0.1 [m]\n"
                                  "coordinate x [m], theta [rad]\n"
                                  "input f [N], tau [N m]\nframe b = rotate(a, 3, theta)\npoint p = w + x*b.1\n"
                                  "body bob(mass = mass, centre = p, frame = b, inertia = mass*r^2*diag(1, 1, 1))\nforce push(at = p, force = f*b.1)\n"
                                  "moment turn(on = b, moment = tau*b.3)\ndamper slow(on = x, damping = d)\n",
                                  "h.eom");
  const Variables& vars = model.system.variables();
  EXPECT_EQ(vars.parameters()[0].unit, "N s/m");
  EXPECT_EQ(vars.coordinates()[0].unit, "m");
  EXPECT_EQ(vars.coordinates()[1].unit, "rad");
  EXPECT_EQ(vars.inputs()[1].unit, "N m");
  EXPECT_EQ(dimension_of(model, "d"), newton * s / m);
  EXPECT_EQ(dimension_of(model, "x_dot"), m / s);
  EXPECT_EQ(dimension_of(model, "x_ddot"), m / (s * s));
  EXPECT_EQ(dimension_of(model, "tau"), newton * m);
  EXPECT_EQ(dimension_of(model, "t"), s);
}

TEST(Units, TheGrammarTakesSpacesStarsSlashesPowersAndParentheses) {
  const Model model = parse_model("parameter j = 1 [kg*m^2/s^2]\nparameter c = 1 [N/m^3]\nparameter f = 1 [1/s]\n"
                                  "parameter n = 1 [-]\nparameter h = 1 [J/(kg K)]\nparameter e = 1 [m^-2 s^+1]\n"
                                  "parameter r = 1 [rad]\nparameter v = 1 [kg m/s^2 / A s]\n" + std::string(pendulum),
                                  "h.eom");
  EXPECT_EQ(dimension_of(model, "j"), newton * m);
  EXPECT_EQ(dimension_of(model, "c"), newton / (m * m * m));
  EXPECT_EQ(dimension_of(model, "f"), Dimension() / s);
  EXPECT_EQ(dimension_of(model, "n"), Dimension());
  EXPECT_EQ(dimension_of(model, "h"), newton * m / (kg * Dimension::of(Dimension::Base::kelvin)));
  EXPECT_EQ(dimension_of(model, "e"), s / (m * m));
  EXPECT_EQ(dimension_of(model, "r"), Dimension());
  // '/' divides by the next factor only
  EXPECT_EQ(dimension_of(model, "v"), newton * s / Dimension::of(Dimension::Base::ampere));
}

TEST(Units, UnitsOtherThanCoherentSiAreRefusedAtTheirColumn) {
  const std::string expected =
      "is not a coherent SI unit: expected SI units (kg, m, s, A, K, mol, cd, rad, sr, N, J, W, Pa, Hz, C, V) or '-'; "
      "values are taken in SI, eomgen converts no unit";
  EXPECT_EQ(error_of("parameter l = 5 [mm]\n" + pendulum), "h.eom:1:18: error: 'mm' " + expected);
  EXPECT_EQ(error_of("parameter m0 = 5 [g]\n" + pendulum), "h.eom:1:19: error: 'g' " + expected);
  EXPECT_EQ(error_of(pendulum + "coordinate q [deg]\n"), "h.eom:8:15: error: 'deg' " + expected);
  EXPECT_EQ(error_of(pendulum + "input v [km/h]\n"), "h.eom:8:10: error: 'km' " + expected);
}

TEST(Units, AMalformedUnitIsAnErrorInsideItsBrackets) {
  EXPECT_EQ(error_of("parameter k = 1 [m^x]\n" + pendulum),
            "h.eom:1:20: error: expected an integer power after '^' in a unit (m^2, s^-1)");
  EXPECT_EQ(error_of("parameter k = 1 [m^2.5]\n" + pendulum),
            "h.eom:1:20: error: expected an integer power after '^' in a unit (m^2, s^-1)");
  EXPECT_EQ(error_of("parameter k = 1 [N/]\n" + pendulum),
            "h.eom:1:19: error: the unit ends after an operator: expected a unit symbol");
  EXPECT_EQ(error_of("parameter k = 1 []\n" + pendulum),
            "h.eom:1:17: error: expected a unit inside '[]', or '[-]' for a dimensionless quantity");
  EXPECT_EQ(error_of("parameter k = 1 [m, s]\n" + pendulum),
            "h.eom:1:19: error: unexpected ',' in a unit: expected unit symbols separated by spaces, '*' or '/', with "
            "integer powers (kg m^2/s^2)");
}

// --- a model with units gives them all ---

TEST(Units, AParameterWithoutAUnitIsRefusedInAModelWithUnits) {
  EXPECT_EQ(error_of(pendulum + "parameter k = 3\n"),
            "h.eom:8:11: error: parameter 'k' has no unit, but the model gives units (the first at h.eom:1:20): "
            "expected [UNIT] after its value, or [-] for a dimensionless parameter");
}

TEST(Units, AnInputWithoutAUnitIsRefusedInAModelWithUnits) {
  EXPECT_EQ(error_of(pendulum + "input u [N m], v\n"),
            "h.eom:8:16: error: input 'v' has no unit, but the model gives units (the first at h.eom:1:20): "
            "expected [UNIT] after its name, or [-] for a dimensionless input");
}

TEST(Units, ACoordinateThatTurnsAFrameIsDimensionless) {
  const Model model = parse_model(pendulum, "h.eom");
  EXPECT_EQ(dimension_of(model, "theta"), Dimension());
  EXPECT_EQ(dimension_of(model, "theta_dot"), Dimension() / s);
}

TEST(Units, ACoordinateOfAPointsPositionIsALength) {
  const Model model = parse_model(pendulum + "coordinate x, y\npoint c = w + x*a.1 + sqrt(y^2 + l^2)*b.2\n"
                                             "particle cart(mass = mass, at = c)\n", "h.eom");
  EXPECT_EQ(dimension_of(model, "x"), m);
  EXPECT_EQ(dimension_of(model, "y"), m);  // under a root, through the sum
  EXPECT_EQ(dimension_of(model, "x_dot"), m / s);
}

TEST(Units, ARotationAngleGivesTheUnitOfACoordinateItDividesByALength) {
  // a wheel of radius l turning as it rolls x along: x/l is the angle, so x is a length
  const Model model = parse_model(pendulum + "coordinate x\nframe c = rotate(a, 2, x/l)\n"
                                             "body disk(mass = mass, centre = p, frame = c, inertia = diag(mass*l^2, mass*l^2, mass*l^2))\n",
                                  "h.eom");
  EXPECT_EQ(dimension_of(model, "x"), m);
}

TEST(Units, ACoordinateWhoseUnitNothingFixesIsAskedFor) {
  EXPECT_EQ(error_of(pendulum + "coordinate x, y\npoint c = w + x*y*a.1\nparticle cart(mass = mass, at = c)\n"),
            "h.eom:8:12: error: coordinate 'x' has no unit, and the rotations and points it enters do not fix one, "
            "but the model gives units (the first at h.eom:1:20): expected 'x [UNIT]'");
}

// --- what is checked ---

TEST(Units, AMomentArmWithoutItsLengthFailsNamingTheTerm) {
  EXPECT_EQ(error_of(pendulum + "moment drive(on = b, moment = F*b.3)\n"),
            "h.eom:8:31: error: moment 'drive': the term 'F' has dimension kg m s^-2 (N), expected kg m^2 s^-2 (N m) "
            "for a moment");
  EXPECT_EQ(error_of(pendulum + "moment drive(on = b, moment = l*F*b.3)\n"), "no error");
}

TEST(Units, AForceAddedToATorqueFailsNamingTheForce) {
  EXPECT_EQ(error_of(pendulum + "parameter tau = 1 [N m]\nmoment drive(on = b, moment = (tau + F)*b.3)\n"),
            "h.eom:9:32: error: moment 'drive': the term 'F' has dimension kg m s^-2 (N), expected kg m^2 s^-2 (N m) "
            "for a moment");
}

TEST(Units, APointOffsetIsALengthInEveryTerm) {
  EXPECT_EQ(error_of(pendulum + "point q = p + l*b.1 + F*b.2\n"),
            "h.eom:8:23: error: point 'q': the term 'F' has dimension kg m s^-2 (N), expected m for a position");
}

TEST(Units, ARotationAngleIsDimensionless) {
  EXPECT_EQ(error_of(pendulum + "frame c = rotate(b, 1, l)\n"),
            "h.eom:8:24: error: frame 'c': the term 'l' has dimension m, expected dimensionless for an angle or a "
            "parameter of a rotation");
}

TEST(Units, TheArgumentOfSinIsDimensionless) {
  EXPECT_EQ(error_of(pendulum + "point q = p + l*sin(l)*b.1\n"),
            "h.eom:8:15: error: point 'q': the argument 'l' of 'sin(l)' has dimension m, expected dimensionless");
}

TEST(Units, MassAndInertiaOfABody) {
  EXPECT_EQ(error_of(pendulum + "body rod(mass = mass, centre = p, frame = b, inertia = diag(mass*l, mass*l^2, mass*l^2))\n"),
            "h.eom:8:56: error: body 'rod': the term 'l*mass' has dimension kg m, expected kg m^2 for an inertia");
  EXPECT_EQ(error_of(pendulum + "particle bob2(mass = l, at = p)\n"),
            "h.eom:8:22: error: particle 'bob2': the term 'l' has dimension m, expected kg for a mass");
}

TEST(Units, GravityIsAnAcceleration) {
  EXPECT_EQ(error_of(pendulum + "parameter g = 9.81 [m/s]\ngravity = -g*a.2\n"),
            "h.eom:9:11: error: gravity: the term '-g' has dimension m s^-1, expected m s^-2 for gravity (an "
            "acceleration)");
}

TEST(Units, ASpringsStiffnessIsForcePerLength) {
  EXPECT_EQ(error_of(pendulum + "spring k1(from = w, to = p, stiffness = F, length = l)\n"),
            "h.eom:8:41: error: spring 'k1': the term 'F' has dimension kg m s^-2 (N), expected kg s^-2 (N/m) for a "
            "spring's stiffness");
}

TEST(Units, ATorsionSpringsStiffnessIsEnergyPerSquaredAngle) {
  EXPECT_EQ(error_of(pendulum + "parameter k = 3 [N m]\ntorsion twist(angle = theta, stiffness = k, rest = 0.1)\n"),
            "no error");
  EXPECT_EQ(error_of(pendulum + "torsion twist(angle = theta, stiffness = F)\n"),
            "h.eom:8:42: error: torsion 'twist': the term 'F' has dimension kg m s^-2 (N), expected kg m^2 s^-2 (J) "
            "for a torsion spring's stiffness (J per the angle's unit squared)");
}

TEST(Units, AGeneralizedForceIsEnergyPerUnitOfItsCoordinate) {
  EXPECT_EQ(error_of(pendulum + "parameter tau = 1 [N m]\ncoordinate x [m]\npoint c = p + x*b.2\n"
                                "particle cart(mass = mass, at = c)\ngeneralized_force push(on = x, value = F + tau)\n"),
            "h.eom:12:40: error: generalized_force 'push': the term 'tau' has dimension kg m^2 s^-2 (N m), expected kg "
            "m s^-2 (N) for a generalized force (J per the unit of 'on')");
}

TEST(Units, ADamperOnAnExpressionDissipatesPower) {
  EXPECT_EQ(error_of(pendulum + "parameter c = 0.1 [N m s]\ndamper friction(on = theta, damping = c)\n"), "no error");
  EXPECT_EQ(error_of(pendulum + "parameter c = 0.1 [N s/m]\ndamper friction(on = theta, damping = c)\n"),
            "h.eom:9:39: error: damper 'friction': the term 'c' has dimension kg s^-1 (N s/m), expected kg m^2 s^-1 "
            "(N m s) for a damping (W per the squared rate of 'on')");
}

TEST(Units, APotentialIsAnEnergy) {
  EXPECT_EQ(error_of(pendulum + "potential lift = 3*l\n"),
            "h.eom:8:18: error: potential 'lift': the term '3*l' has dimension m, expected kg m^2 s^-2 (J) for "
            "an energy");
}

TEST(Units, TheSidesOfAConstraintAgree) {
  EXPECT_EQ(error_of(pendulum + "coordinate x [m]\npoint c = p + x*b.2\nparticle cart(mass = mass, at = c)\n"
                                "constraint fixed: x = theta\n"),
            "h.eom:11:19: error: constraint 'fixed': the terms '-theta' and 'x' have different dimensions, "
            "dimensionless and m");
}

TEST(Units, AnOutputAgreesWithItself) {
  EXPECT_EQ(error_of(pendulum + "output wrong = l + theta_dot\n"),
            "h.eom:8:16: error: output 'wrong': the terms 'l' and 'theta_dot' have different dimensions, m and s^-1");
}

// --- the shipped models ---

TEST(Units, EveryShippedModelGivesUnitsThatPassTheModelAndDerivationChecks) {
  int models = 0;
  for (const auto& entry : std::filesystem::directory_iterator(testing::source_dir() / "models")) {
    if (entry.path().extension() != ".eom") continue;
    SCOPED_TRACE(entry.path().string());
    const Model model = load_model(entry.path().string());
    EXPECT_FALSE(model.dimensions.empty());
    EXPECT_NO_THROW(derive_equations(model));  // checks the derived equations against the units
    ++models;
  }
  EXPECT_EQ(models, 18);
}

}  // namespace
}  // namespace eomgen
