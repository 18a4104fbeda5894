// Errors in model files: every error is a SourceError at an exact line and column whose
// message says what went wrong and what was expected. One test per error case.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "eomgen/base/error.hpp"
#include "eomgen/derivation/model_equations.hpp"
#include "eomgen/language/model_file.hpp"

namespace eomgen {
namespace {

using ::testing::AllOf;
using ::testing::ContainsRegex;
using ::testing::Eq;
using ::testing::HasSubstr;
using ::testing::Matcher;

// A valid planar pendulum on lines 1-5; the cases below append their statements from line 6.
const std::string pendulum =
    "parameter l = 1\n"
    "coordinate theta\n"
    "frame b = rotate(a, 3, theta)\n"
    "point p = w + l*b.1\n"
    "particle bob(mass = 1, at = p)\n";

// Two free coordinates x, y of a point mass in the plane, on lines 1-4; cases append from line 5.
const std::string planar_mass =
    "coordinate x, y\n"
    "parameter m0 = 1\n"
    "point p = w + x*a.1 + y*a.2\n"
    "particle m(mass = m0, at = p)\n";

// A blade on the plane that cannot slide sideways (nq = 3, nc = 1) on lines 1-5; cases append
// their `independent` statements from line 6.
const std::string knife_edge =
    "coordinate x, y, theta\n"
    "frame b = rotate(a, 3, theta)\n"
    "point c = w + x*a.1 + y*a.2\n"
    "body blade(mass = 1, centre = c, frame = b, inertia = diag(1, 1, 1))\n"
    "constraint no_side_slip: dot(velocity(c), b.2) = 0\n";

void expect_error(const std::string& text, int line, int column, const Matcher<const std::string&>& message,
                  const std::map<std::string, double>& overrides = {}) {
  SCOPED_TRACE("model text:\n" + text);
  try {
    parse_model(text, "test.eom", overrides);
    ADD_FAILURE() << "expected a SourceError";
  } catch (const SourceError& e) {
    EXPECT_EQ(e.location().file, "test.eom");
    EXPECT_EQ(e.location().line, line) << e.what();
    EXPECT_EQ(e.location().column, column) << e.what();
    EXPECT_THAT(e.message(), message);
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected a SourceError, got: " << e.what();
  }
}

TEST(ModelErrors, WhatReadsFileLineColumnErrorMessage) {
  try {
    parse_model(pendulum + "output o = thta\n", "test.eom");
    FAIL() << "expected a SourceError";
  } catch (const SourceError& e) {
    EXPECT_STREQ(e.what(), ("test.eom:6:12: error: " + e.message()).c_str());
  }
}

// --- names ---

TEST(ModelErrors, UnknownIdentifierSuggestsNearestName) {
  expect_error(pendulum + "output o = 2*thta\n", 6, 14, HasSubstr("unknown name 'thta'; did you mean 'theta'?"));
}

TEST(ModelErrors, UnknownFunctionSuggestsNearestFunction) {
  expect_error(pendulum + "output o = sinn(theta)\n", 6, 12, HasSubstr("unknown function 'sinn'; did you mean 'sin'?"));
}

TEST(ModelErrors, DuplicateNameNamesTheFirstDeclaration) {
  expect_error(pendulum + "parameter l = 2\n", 6, 11,
               HasSubstr("duplicate name 'l': already declared as a parameter at test.eom:1:11"));
}

TEST(ModelErrors, DuplicateNameIsReportedAtTheLaterDeclarationWhateverTheirKinds) {
  // parameters are declared before frames internally; the report still follows the file
  expect_error("frame c = a\n" + pendulum + "parameter c = 2\n", 7, 11,
               HasSubstr("duplicate name 'c': already declared as a frame at test.eom:1:7"));
}

TEST(ModelErrors, ReservedNameA) {
  expect_error(pendulum + "parameter a = 1\n", 6, 11, HasSubstr("'a' is reserved (the inertial frame is 'a'"));
}

TEST(ModelErrors, ReservedNameT) {
  expect_error(pendulum + "parameter t = 1\n", 6, 11, HasSubstr("'t' is reserved"));
}

// a keyword as a name would read as the statement it begins (issue 16)
TEST(ModelErrors, KeywordsAreNotNames) {
  expect_error(pendulum + "parameter for = 1\n", 6, 11,
               HasSubstr("'for' is a keyword of the model language: expected a parameter name that is not one"));
  expect_error(pendulum + "coordinate end\n", 6, 12, HasSubstr("'end' is a keyword of the model language"));
  expect_error(pendulum + "frame in = a\n", 6, 7, HasSubstr("'in' is a keyword of the model language"));
  expect_error(pendulum + "output body = theta\n", 6, 8, HasSubstr("'body' is a keyword of the model language"));
}

// a default that is no finite real number was taken as its real part, or overflowed into an
// internal error (issue 16)
TEST(ModelErrors, ParameterDefaultsAreFiniteRealNumbers) {
  expect_error(pendulum + "parameter k = sqrt(-1)\n", 6, 15,
               HasSubstr("parameter 'k': expected a real number, got a complex one (0 + 1*I)"));
  expect_error(pendulum + "parameter k = log(-1)\n", 6, 15, HasSubstr("parameter 'k': expected a real number"));
  expect_error(pendulum + "parameter k = 1e400\n", 6, 15, HasSubstr("parameter 'k': the value is too large for a double"));
  expect_error(pendulum + "parameter k = 2^2000\n", 6, 15, HasSubstr("parameter 'k': the value is too large for a double"));
}

TEST(ModelErrors, AccelerationInTheModel) {
  expect_error(pendulum + "output o = theta_ddot\n", 6, 12,
               AllOf(HasSubstr("'theta_ddot' is an acceleration"), HasSubstr("expected coordinates and rates")));
}

TEST(ModelErrors, NegativeIndexInAName) {
  expect_error(pendulum + "for i in 0..1\n  parameter k{i-1} = 1\nend\n", 7, 15,
               HasSubstr("an index in a name: expected 0 or more, got -1"));
}

// --- syntax ---

TEST(ModelErrors, SyntaxErrorDoubleOperator) {
  expect_error(pendulum + "output o = 2 * * theta\n", 6, 16,
               HasSubstr("expected an expression (a number, a name, '(' or '['), got '*'"));
}

TEST(ModelErrors, MissingClosingParenthesisIsReportedAtTheOpening) {
  // the open '(' continues the statement to the end of the file
  expect_error("parameter k = (1 + 2\n" + pendulum, 1, 15, HasSubstr("'(' is never closed: expected ')'"));
}

TEST(ModelErrors, UnterminatedBracket) {
  expect_error(pendulum + "output o = [1, 2\n", 6, 12, HasSubstr("'[' is never closed: expected ']'"));
}

TEST(ModelErrors, UnknownStatementKeyword) {
  expect_error(pendulum + "frme c = a\n", 6, 1,
               AllOf(HasSubstr("unknown statement 'frme'"), HasSubstr("expected one of"), HasSubstr("frame")));
}

TEST(ModelErrors, UnknownArgumentKey) {
  expect_error(pendulum + "particle q(mas = 1, at = p)\n", 6, 12,
               HasSubstr("particle 'q': unknown argument 'mas'; expected mass, at"));
}

TEST(ModelErrors, HugeExponent) {
  expect_error(pendulum + "parameter k = 1e99999999999999999999\n", 6, 15,
               HasSubstr("out of range: expected an exponent between"));
}

// --- frames and points ---

TEST(ModelErrors, UnknownParentFrame) {
  expect_error(pendulum + "frame c = rotate(bb, 1, theta)\n", 6, 18,
               HasSubstr("unknown frame 'bb'; did you mean 'b'?"));
}

TEST(ModelErrors, UnknownParentPoint) {
  // the suggestion may be a point defined later in the file
  expect_error(pendulum + "point q = tipp + l*b.2\npoint tip = w\n", 6, 11,
               HasSubstr("unknown point 'tipp'; did you mean 'tip'?"));
}

TEST(ModelErrors, CycleAmongFrames) {
  expect_error(pendulum + "frame c = rotate(d, 1, theta)\nframe d = rotate(e, 2, theta)\nframe e = c\n", 6, 7,
               HasSubstr("frame 'c' is defined through a cycle: c -> d -> e -> c"));
}

TEST(ModelErrors, CycleAmongPoints) {
  expect_error(pendulum + "point q = r + l*b.1\npoint r = q - l*a.2\n", 6, 7,
               HasSubstr("point 'q' is defined through a cycle: q -> r -> q"));
}

TEST(ModelErrors, InputInsideARotation) {
  expect_error(pendulum + "input u\nframe c = rotate(b, 1, theta + u)\n", 7, 11,
               HasSubstr("a rotation may depend on coordinates, parameters and t only, not on rates, accelerations "
                         "or inputs"));
}

TEST(ModelErrors, RotateWithTheWrongNumberOfArguments) {
  expect_error(pendulum + "frame c = rotate(b, 3)\n", 6, 11,
               ::testing::Eq("rotate(PARENT, AXIS, ANGLE) takes 3 arguments, got 2"));
}

TEST(ModelErrors, RotateWithoutArguments) {
  expect_error(pendulum + "frame c = rotate()\n", 6, 11, HasSubstr("rotate(): expected the parent frame"));
}

TEST(ModelErrors, RotateAboutAxis4) {
  expect_error(pendulum + "frame c = rotate(b, 4, theta)\n", 6, 21,
               HasSubstr("rotate(): expected axis 1, 2 or 3, got 4"));
}

TEST(ModelErrors, InvalidEulerSequence) {
  expect_error(pendulum + "frame c = euler(b, 311, theta, 0, 0)\n", 6, 20,
               AllOf(HasSubstr("Euler sequence '311'"), HasSubstr("no two consecutive axes equal")));
}

// --- bodies ---

TEST(ModelErrors, RigidBodyWithoutMass) {
  expect_error(pendulum + "body disk(centre = p, frame = b, inertia = diag(1, 1, 1))\n", 6, 1,
               HasSubstr("body 'disk': missing argument 'mass'"));
}

TEST(ModelErrors, RigidBodyWithoutInertia) {
  expect_error(pendulum + "body disk(mass = 1, centre = p, frame = b)\n", 6, 1,
               AllOf(HasSubstr("body 'disk': missing argument 'inertia'"), HasSubstr("diag(J1, J2, J3)")));
}

TEST(ModelErrors, InertiaWithANegativePrincipalMoment) {
  expect_error(pendulum + "body disk(mass = 1, centre = p, frame = b, inertia = [[1, 2, 0], [2, 1, 0], [0, 0, 1]])\n",
               6, 6,
               AllOf(HasSubstr("rigid body 'disk'"), HasSubstr("the principal moments -1, 1, 3 at the default "
                                                              "parameters; a negative one belongs to no body")));
}

TEST(ModelErrors, MomentOnAFrameThatNoBodyHasActsOnNothing) {
  // the pendulum's frame b carries a particle, no body
  expect_error(pendulum + "moment drive(on = b, moment = a.3)\n", 6, 19,
               Eq("moment 'drive': no body has the frame 'b', so the moment would act on nothing: expected the "
                  "frame of a body (the model has none)"));
  // a body defined after the moment counts; one on another frame is listed
  const std::string rod = "frame c = rotate(b, 1, 0.2)\n"
                          "body rod(mass = 1, centre = p, frame = b, inertia = diag(0, 1, 1))\n";
  expect_error(pendulum + "moment drive(on = c, moment = a.3)\n" + rod, 6, 19,
               Eq("moment 'drive': no body has the frame 'c', so the moment would act on nothing: expected the "
                  "frame of a body: 'b' (rod)"));
  EXPECT_NO_THROW(parse_model(pendulum + "moment drive(on = b, moment = a.3)\n" + rod, "test.eom"));
}

TEST(ModelErrors, NonPositiveMass) {
  expect_error(pendulum + "parameter m0 = 0\nparticle q(mass = m0 - 1, at = p)\n", 7, 10,
               HasSubstr("particle 'q': the mass must be positive, got -1"));
}

TEST(ModelErrors, PoleAtTheParameterDefaults) {
  expect_error(pendulum + "parameter z = 0\nparticle q(mass = 1/z, at = p)\n", 7, 10,
               HasSubstr("the mass is infinite or undefined at the parameters' default values"));
}

TEST(ModelErrors, PoleOfAFunction) {
  expect_error(pendulum + "parameter k = log(0)\n", 6, 15, HasSubstr("log() is infinite at this argument"));
}

TEST(ModelErrors, ZeroToANegativePower) {
  expect_error(pendulum + "const z = 0\nparameter k = 2*z^-1\n", 7, 18,
               HasSubstr("zero raised to a negative power: expected a non-zero base"));
}

// --- constraints ---

TEST(ModelErrors, NonholonomicConstraintNotLinearInRates) {
  expect_error(planar_mass + "constraint c: x_dot*y_dot = 0\n", 5, 12,
               HasSubstr("the constraint must be linear in the rates, but it is not linear in 'x_dot'"));
}

TEST(ModelErrors, ConstraintIdenticallyZero) {
  expect_error(planar_mass + "constraint c: sin(x)^2 + cos(x)^2 = 1\n", 5, 12,
               HasSubstr("Jacobian is identically zero"));
}

// a row of Xi that depends on those before it is redundant and left out (redundant_constraints_test.cpp)
// where its Xi_t agrees with theirs; x + y = 1 and x + y = t have one row of Xi, and no motion meets both
TEST(ModelErrors, DependentConstraintsThatContradictEachOtherReportTheSecond) {
  expect_error(planar_mass + "constraint c1: x + y = 1\nconstraint c2: 2*x + 2*y = t\n", 6, 12,
               HasSubstr("constraint 'c2' contradicts the constraints before it: at a generic state its row of Xi is a "
                         "multiple of that of 'c1', but its Xi_t is not the same combination of theirs"));
}

// --- independent speeds ---

TEST(ModelErrors, IndependentUnknownCoordinateSuggestsNearestCoordinate) {
  expect_error(knife_edge + "independent x, thta\n", 6, 16, HasSubstr("unknown coordinate 'thta'; did you mean 'theta'?"));
}

TEST(ModelErrors, IndependentNameThatIsNoCoordinate) {
  expect_error(knife_edge + "independent b, theta\n", 6, 13, HasSubstr("independent: 'b' is a frame, expected a coordinate"));
}

TEST(ModelErrors, IndependentRateInsteadOfItsCoordinate) {
  expect_error(knife_edge + "independent x_dot, theta\n", 6, 13,
               HasSubstr("independent: 'x_dot' is a rate: expected its coordinate 'x'"));
}

TEST(ModelErrors, IndependentCoordinateListedTwiceIsReportedAtTheSecond) {
  expect_error(knife_edge + "independent x, x\n", 6, 16,
               HasSubstr("independent: coordinate 'x' is listed twice (first at test.eom:6:13)"));
}

TEST(ModelErrors, IndependentStatementGivenTwice) {
  expect_error(knife_edge + "independent x, theta\nindependent y, theta\n", 7, 1,
               HasSubstr("'independent' is given twice: the independent speeds are already declared at test.eom:6:1"));
}

TEST(ModelErrors, IndependentStatementRepeatedByALoop) {
  expect_error(knife_edge + "for i in 1..2\n  independent x, theta\nend\n", 7, 3,
               HasSubstr("'independent' is repeated by its loop: declare the independent speeds once"));
}

TEST(ModelErrors, IndependentCountDiffersFromTheDegreesOfFreedom) {
  expect_error(knife_edge + "independent theta\n", 6, 1,
               HasSubstr("independent: expected nq - nc = 3 - 1 = 2 coordinates (one per degree of freedom), got 1"));
}

TEST(ModelErrors, IndependentInAModelWithoutConstraints) {
  expect_error(planar_mass + "independent x\n", 5, 1,
               HasSubstr("'independent' in a model without constraints: every speed is independent"));
}

TEST(ModelErrors, IndependentSpeedsLeavingTheDependentOnesUnsolvable) {
  // theta_dot does not appear in the constraint, so it cannot be solved from it
  expect_error(knife_edge + "independent x, y\n", 6, 1,
               AllOf(HasSubstr("the constraints cannot be solved for the rates of the other coordinates ('theta')"),
                     HasSubstr("their columns of Xi are singular")));
}

// --- the whole model ---

TEST(ModelErrors, CoordinateNeverUsed) {
  expect_error(pendulum + "coordinate phi\n", 6, 12, HasSubstr("coordinate 'phi' is declared but never used"));
}

TEST(ModelErrors, EmptyText) {
  expect_error("", 1, 1, HasSubstr("empty model: expected statements"));
}

TEST(ModelErrors, OnlyComments) {
  expect_error("# a model\n\n   # to be written\n", 1, 1, HasSubstr("empty model: expected statements"));
}

TEST(ModelErrors, NoCoordinates) {
  expect_error("particle p(mass = 1, at = w)\n", 1, 1, HasSubstr("declares no coordinates: expected 'coordinate"));
}

TEST(ModelErrors, NoMass) {
  expect_error("coordinate q\nframe b = rotate(a, 3, q)\n", 1, 1,
               HasSubstr("no particle or body, so it has no mass: expected 'particle' or 'body'"));
}

// --- kinds ---

TEST(ModelErrors, VectorWhereAScalarIsExpected) {
  expect_error(pendulum + "particle q(mass = 2*b.1, at = p)\n", 6, 19,
               HasSubstr("particle 'q': 'mass': expected a scalar, got a vector"));
}

TEST(ModelErrors, ScalarWhereAVectorIsExpected) {
  expect_error(pendulum + "parameter g = 9.81\ngravity = 2*g\n", 7, 11,
               HasSubstr("gravity: expected a vector (such as g*a.3 or [x, y, z] in b), got a scalar"));
}

// --- loops and constants ---

TEST(ModelErrors, ConstInsideALoop) {
  expect_error(pendulum + "for i in 1..2\n  const k = 3\nend\n", 7, 3, HasSubstr("'const' must be at the top level"));
}

TEST(ModelErrors, LoopBoundNotAnInteger) {
  expect_error(pendulum + "const n = 2.5\nfor i in 1..n\nend\n", 7, 13,
               HasSubstr("the last value of the loop: expected an integer, got 2.5"));
}

TEST(ModelErrors, LoopBoundBeyondTheIntegerRange) {
  // 2^32 + 2 would wrap to 2 in a 32-bit int
  expect_error(pendulum + "for i in 1..4294967298\nend\n", 6, 13,
               HasSubstr("the last value of the loop: expected an integer between -10^9 and 10^9"));
}

TEST(ModelErrors, DefineOfAnUnknownConst) {
  expect_error(pendulum + "const n = 2\n", 1, 1,
               AllOf(HasSubstr("--define m: the model has no const named 'm'"),
                     HasSubstr("expected one of its consts: n")),
               {{"m", 3}});
}

}  // namespace
}  // namespace eomgen
