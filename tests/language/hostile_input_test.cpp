// Hostile and careless input (issue 16): each case that once crashed, hung, ended in an internal
// error or was silently accepted, with the exact located message it now gets; and the largest
// inputs within the limits, which must still give the right model.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "eomgen/base/error.hpp"
#include "eomgen/language/model_file.hpp"
#include "support/expect_model_error.hpp"

namespace eomgen {
namespace {

// A valid point mass on lines 1-3; the cases put their statements before it, from line 1.
const std::string point_mass =
    "coordinate q\n"
    "point p = w + q*a.1\n"
    "particle m(mass = 1, at = p)\n";

std::string repeat(const std::string& piece, int times) {
  std::string out;
  for (int i = 0; i < times; ++i) out += piece;
  return out;
}

std::string error_of(const std::string& text) { return testing::model_error_text(text, "h.eom"); }

double parameter_default(const Model& model, const std::string& name) {
  for (const Parameter& p : model.system.variables().parameters())
    if (p.name == name) return p.default_value;
  ADD_FAILURE() << "no parameter " << name;
  return 0;
}

const std::string too_deep =
    "expressions nest deeper than 100 levels (parentheses, calls, brackets, signs and powers): expected a flatter "
    "expression";

// --- nesting: refused at the token that crosses the limit, before any recursion over it ---

TEST(HostileInput, TwentyThousandNestedParenthesesAreRefusedAtTheHundredFirstLevel) {
  EXPECT_EQ(error_of("parameter k = " + repeat("(", 20000) + "1" + repeat(")", 20000) + "\n" + point_mass),
            "h.eom:1:115: error: " + too_deep);
}

TEST(HostileInput, AHundredLevelsOfNestingAreAccepted) {
  // the statement's own expression is the first level
  const Model m = parse_model("parameter k = " + repeat("(", 99) + "2" + repeat(")", 99) + "\n" + point_mass, "h.eom");
  EXPECT_EQ(parameter_default(m, "k"), 2.0);
  EXPECT_EQ(error_of("parameter k = " + repeat("(", 100) + "2" + repeat(")", 100) + "\n" + point_mass),
            "h.eom:1:115: error: " + too_deep);
}

TEST(HostileInput, HundredThousandUnaryMinusesAreRefused) {
  EXPECT_EQ(error_of("parameter k = " + repeat("-", 100000) + "1\n" + point_mass), "h.eom:1:114: error: " + too_deep);
}

TEST(HostileInput, HundredThousandPowersInAChainAreRefused) {
  EXPECT_EQ(error_of("parameter k = 1" + repeat("^1", 100000) + "\n" + point_mass), "h.eom:1:214: error: " + too_deep);
}

TEST(HostileInput, HundredThousandNestedCallsAreRefused) {
  EXPECT_EQ(error_of("parameter k = " + repeat("sin(", 100000) + "1" + repeat(")", 100000) + "\n" + point_mass),
            "h.eom:1:415: error: " + too_deep);
}

TEST(HostileInput, HundredThousandNestedBracketsAreRefused) {
  EXPECT_EQ(error_of("parameter k = " + repeat("[", 100000) + "1" + repeat("]", 100000) + "\n" + point_mass),
            "h.eom:1:115: error: " + too_deep);
}

TEST(HostileInput, TwentyThousandNestedLoopsAreRefusedAtTheThirtyThird) {
  std::string loops;
  for (int i = 0; i < 20000; ++i) loops += "for i" + std::to_string(i) + " in 1..1\n";
  EXPECT_EQ(error_of(loops + repeat("end\n", 20000) + point_mass),
            "h.eom:33:1: error: loops nest deeper than 32 levels: expected fewer loops inside one another");
}

TEST(HostileInput, AChainOfTwentyThousandFramesWrittenBackwardsIsRefused) {
  EXPECT_EQ(error_of("coordinate q\nfor i in 1..20000\nframe b{i} = rotate(b{i+1}, 3, q)\nend\nframe b20001 = a\n"
                     "body B(frame = b1, mass = 1, centre = w, inertia = diag(1, 2, 3))\n"),
            "h.eom:3:7: error: frame 'b257' is defined through more than 256 frames and points that come later in the "
            "file: expected parents defined before their children");
  EXPECT_EQ(error_of("coordinate q\nfor i in 1..20000\npoint p{i} = p{i+1} + q*a.1\nend\npoint p20001 = w\n"
                     "particle m(mass = 1, at = p1)\n"),
            "h.eom:3:7: error: point 'p257' is defined through more than 256 frames and points that come later in the "
            "file: expected parents defined before their children");
}

TEST(HostileInput, AChainOfTwentyThousandFramesInOrderIsAModel) {
  const Model m = parse_model("coordinate q\nframe b0 = a\nfor i in 1..20000\nframe b{i} = rotate(b{i-1}, 3, q)\nend\n"
                              "body B(frame = b20000, mass = 1, centre = w, inertia = diag(1, 2, 3))\n",
                              "h.eom");
  EXPECT_EQ(m.system.frames().size(), 20001u);  // a and b1..b20000: b0 is an alias of a, no frame of its own
}

// --- long flat sums and products: loops, not recursions; and the right value ---

TEST(HostileInput, AFlatSumOfHundredThousandTermsHasItsValue) {
  std::string terms = "1";
  for (int i = 1; i < 100000; ++i) terms += i % 2 ? "+2" : "-1";
  const Model m = parse_model("parameter k = " + terms + "\n" + point_mass, "h.eom");
  EXPECT_EQ(parameter_default(m, "k"), 50002.0);  // 1 + 50000*2 - 49999*1
}

TEST(HostileInput, AFlatVectorSumOfSixtyThousandTermsPlacesThePoint) {
  const Model m =
      parse_model("coordinate q\npoint p = w" + repeat(" + q*a.1 - 0.5*q*a.2", 30000) + "\nparticle m(mass = 1, at = p)\n",
                  "h.eom");
  const Point& p = m.system.points().back();
  ASSERT_EQ(p.offset.terms().size(), 1u);
  const GiNaC::ex q = m.system.variables().coordinates()[0].q;
  EXPECT_TRUE((p.offset.terms()[0].second(0, 0) - 30000 * q).is_zero()) << p.offset.terms()[0].second;
  EXPECT_TRUE((p.offset.terms()[0].second(1, 0) + 15000 * q).is_zero());
}

TEST(HostileInput, AFlatProductOfOneHundredThousandFactorsHasItsValue) {
  // 2 * 3/2 * 4/3 * ... * 100001/100000 = 100001
  std::string factors = "2";
  for (int i = 3; i <= 100001; ++i) factors += "*" + std::to_string(i) + "/" + std::to_string(i - 1);
  const Model m = parse_model("parameter k = " + factors + "\n" + point_mass, "h.eom");
  EXPECT_EQ(parameter_default(m, "k"), 100001.0);
}

TEST(HostileInput, AMismatchInsideAFlatSumIsReportedAtItsOperator) {
  EXPECT_EQ(error_of(point_mass + "output o = q*a.1 + q*a.2 - q + q*a.3\n"),
            "h.eom:4:26: error: cannot subtract a vector and a scalar");
  EXPECT_EQ(error_of(point_mass + "output o = 2 * 3 * a.1 * a.2\n"),
            "h.eom:4:24: error: cannot multiply two vectors: use dot(u, v) or cross(u, v)");
  EXPECT_EQ(error_of("parameter k = 2 * 3 / (1 - 1)\n" + point_mass), "h.eom:1:21: error: division by zero");
}

// --- work: loops and powers that would run for hours ---

TEST(HostileInput, TwoNestedLoopsOfHundredThousandIterationsStop) {
  EXPECT_EQ(error_of("for i in 1..100000\nfor j in 1..100000\nend\nend\n" + point_mass),
            "h.eom:2:1: error: the loops expand the model beyond 2000000 tokens (iterations times the statements "
            "they repeat): expected fewer or shorter loops");
}

TEST(HostileInput, ThreeNestedLoopsCreatingABillionOutputsStop) {
  EXPECT_EQ(error_of(point_mass + "for i in 1..1000\nfor j in 1..1000\nfor k in 1..1000\noutput o{i}_{j}_{k} = q\n"
                                  "end\nend\nend\n"),
            "h.eom:6:1: error: the loops expand the model beyond 2000000 tokens (iterations times the statements "
            "they repeat): expected fewer or shorter loops");
}

TEST(HostileInput, ExactPowersBeyondADoubleAreRefusedWithoutComputingThem) {
  EXPECT_EQ(error_of("parameter k = 2.5^1000000000\n" + point_mass),
            "h.eom:1:18: error: the power is about 10^397940009, beyond the range of a double: expected a smaller "
            "exponent");
  EXPECT_EQ(error_of("parameter k = 2^100000000\n" + point_mass),
            "h.eom:1:16: error: the power is about 10^30103000, beyond the range of a double: expected a smaller "
            "exponent");
  EXPECT_EQ(error_of("parameter k = 0.5^1000000000\n" + point_mass),
            "h.eom:1:18: error: the power is about 10^-301029996, beyond the range of a double: expected a smaller "
            "exponent");
}

TEST(HostileInput, AHugeExactPowerWithinADoubleIsTakenInFloatingPoint) {
  const Model m = parse_model("parameter k = 1.0000001^1000000000\n" + point_mass, "h.eom");
  EXPECT_NEAR(parameter_default(m, "k"), std::exp(1e9 * std::log1p(1e-7)), 1e-6 * std::exp(100.0));
}

TEST(HostileInput, LargeExponentsOnExpressionsThatVaryAreRefused) {
  // (q+1)^100000 and sin(q)^1000000000 made the derivation run for hours
  EXPECT_EQ(error_of("coordinate q\npoint p = w + (q + 1)^100000*a.1\nparticle m(mass = 1, at = p)\n"),
            "h.eom:2:22: error: the exponent 100000 on an expression that is not a number is out of range: expected "
            "an exponent between -100 and 100");
  EXPECT_EQ(error_of("coordinate q\npoint p = w + sin(q)^80*sin(q)^80*a.1\nparticle m(mass = 1, at = p)\n"),
            "h.eom:2:24: error: the exponent 160 on an expression that is not a number is out of range: expected "
            "an exponent between -100 and 100");
  EXPECT_NO_THROW(parse_model("coordinate q\npoint p = w + (q + 1)^100*a.1\nparticle m(mass = 1, at = p)\n", "h.eom"));
}

TEST(HostileInput, LiteralsBeyondADoubleAreRefused) {
  EXPECT_EQ(error_of("parameter m = 1e400\n" + point_mass),
            "h.eom:1:15: error: parameter 'm': the value is too large for a double");
  EXPECT_EQ(error_of("parameter m = 1e100000000000000000000\n" + point_mass),
            "h.eom:1:15: error: number '1e100000000000000000000' is out of range: expected an exponent between -400 "
            "and 400");
}

// --- size ---

TEST(HostileInput, AnEndlessFileIsRefusedAfterFourMebibytes) {
  EXPECT_THROW(
      {
        try {
          load_model("/dev/zero");
        } catch (const SourceError& e) {
          EXPECT_STREQ(e.what(), "/dev/zero:1:1: error: the model is larger than 4 MiB: expected a model file (loops "
                                 "make large models from short text)");
          throw;
        }
      },
      SourceError);
}

TEST(HostileInput, AFileOfControlBytesNamesTheFirstOne) {
  EXPECT_EQ(error_of(std::string("coordinate q\n\0\0", 15)),
            "h.eom:2:1: error: unexpected byte 0x00: expected ASCII model text (names, numbers, operators)");
  EXPECT_EQ(error_of("parameter k\xff = 1\n" + point_mass),
            "h.eom:1:12: error: unexpected byte 0xff: expected ASCII model text (names, numbers, operators)");
}

TEST(HostileInput, StringsMustBeUtf8) {
  EXPECT_EQ(error_of("description \"ok \xff\"\n" + point_mass),
            "h.eom:1:17: error: byte 0xff in a string is not UTF-8: expected UTF-8 text");
  EXPECT_EQ(error_of("description \"\xed\xa0\x80\"\n" + point_mass),  // a surrogate
            "h.eom:1:14: error: byte 0xed in a string is not UTF-8: expected UTF-8 text");
  EXPECT_EQ(error_of("description \"\xc0\xaf\"\n" + point_mass),  // an overlong '/'
            "h.eom:1:14: error: byte 0xc0 in a string is not UTF-8: expected UTF-8 text");
  EXPECT_EQ(parse_model("description \"caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x9a\xb2\"\n" + point_mass, "h.eom").description,
            "caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x9a\xb2");
}

TEST(HostileInput, AModelNamedAfterItsFileGetsAnIdentifier) {
  EXPECT_EQ(parse_model(point_mass, "models/my-model.v2.eom").name, "my_model");
  EXPECT_EQ(parse_model(point_mass, "2link.eom").name, "model_2link");
  EXPECT_EQ(parse_model(point_mass, "/tmp/caf\xc3\xa9 \xff.eom").name, "caf____");  // one _ per byte
  EXPECT_EQ(parse_model("model given\n" + point_mass, "my-model.eom").name, "given");
}

// --- names a loop variable would hide ---

TEST(HostileInput, ALoopVariableMayNotHideAParameter) {
  EXPECT_EQ(error_of("parameter m = 2\nfor m in 2..2\nend\n" + point_mass),
            "h.eom:2:5: error: loop variable 'm' hides the parameter 'm' declared at h.eom:1:11: expected another "
            "loop variable name");
}

TEST(HostileInput, ALoopVariableMayNotHideACoordinateOrItsRate) {
  EXPECT_EQ(error_of("for q in 1..1\nend\n" + point_mass),
            "h.eom:1:5: error: loop variable 'q' hides the coordinate 'q' declared at h.eom:3:12: expected another "
            "loop variable name");
  EXPECT_EQ(error_of("for q_dot in 1..1\nend\n" + point_mass),
            "h.eom:1:5: error: loop variable 'q_dot' hides the rate 'q_dot' declared at h.eom:3:12: expected another "
            "loop variable name");
}

TEST(HostileInput, ALoopVariableMayNotHideAFrameOrAnElement) {
  EXPECT_EQ(error_of("frame b = a\nfor b in 1..1\nend\n" + point_mass),
            "h.eom:2:5: error: loop variable 'b' hides the frame 'b' declared at h.eom:1:7: expected another loop "
            "variable name");
  EXPECT_EQ(error_of("for m in 1..1\nend\n" + point_mass),
            "h.eom:1:5: error: loop variable 'm' hides the particle 'm' declared at h.eom:5:10: expected another "
            "loop variable name");
}

TEST(HostileInput, ALoopVariableMayNotBePiOrAKeyword) {
  EXPECT_EQ(error_of("for pi in 1..1\nend\n" + point_mass), "h.eom:1:5: error: loop variable 'pi' hides another name");
  EXPECT_EQ(error_of("for end in 1..1\nend\n" + point_mass),
            "h.eom:1:5: error: 'end' is a keyword of the model language: expected a loop variable that is not one");
}

TEST(HostileInput, LoopsUsingTheSameVariableOneAfterTheOtherAreFine) {
  const Model m = parse_model("for i in 1..2\nparameter k{i} = i\nend\nfor i in 3..4\nparameter k{i} = i\nend\n" +
                                  point_mass,
                              "h.eom");
  EXPECT_EQ(parameter_default(m, "k4"), 4.0);
}

// --- rotations whose parameters are constants must be rotations ---

const std::string body_in_b =
    "coordinate q\n"
    "frame c = rotate(b, 1, q)\n"
    "body B(frame = c, mass = 1, centre = w, inertia = diag(1, 2, 3))\n";

TEST(HostileInput, AZeroAxisIsRefused) {
  EXPECT_EQ(error_of("frame b = axis_angle(a, [0, 0, 0], 0.3)\n" + body_in_b),
            "h.eom:1:25: error: axis_angle(): the axis has length 0 at the parameters' default values: expected a "
            "unit axis (divide each component by the length)");
}

TEST(HostileInput, ANonUnitAxisIsRefusedAndAUnitOneAccepted) {
  EXPECT_EQ(error_of("frame b = axis_angle(a, [1, 1, 0], 0.3)\n" + body_in_b),
            "h.eom:1:25: error: axis_angle(): the axis has length 1.41421 at the parameters' default values: "
            "expected a unit axis (divide each component by the length)");
  EXPECT_NO_THROW(parse_model("frame b = axis_angle(a, [1/sqrt(2), 1/sqrt(2), 0], 0.3)\n" + body_in_b, "h.eom"));
  // an axis of parameters is judged at their defaults
  EXPECT_EQ(error_of("parameter s = 0.6\nframe b = axis_angle(a, [s, s, 0], 0.3)\n" + body_in_b),
            "h.eom:2:25: error: axis_angle(): the axis has length 0.848528 at the parameters' default values: "
            "expected a unit axis (divide each component by the length)");
}

TEST(HostileInput, ANonUnitConstantQuaternionIsRefused) {
  EXPECT_EQ(error_of("frame b = quaternion(a, [0, 0, 0.6], 0.6)\n" + body_in_b),
            "h.eom:1:25: error: quaternion(): the quaternion [E1, E2, E3, ETA] has length 0.848528 at the "
            "parameters' default values: expected a unit quaternion");
  EXPECT_NO_THROW(parse_model("frame b = quaternion(a, [0, 0, 0.6], 0.8)\n" + body_in_b, "h.eom"));
}

TEST(HostileInput, AQuaternionOfCoordinatesIsLeftToItsConstraint) {
  // the shipped quaternion body keeps |q| = 1 by a constraint; at a generic state it is not 1
  EXPECT_NO_THROW(parse_model("coordinate e3, eta\nframe b = quaternion(a, [0, 0, e3], eta)\n"
                              "body B(frame = b, mass = 1, centre = w, inertia = diag(1, 2, 3))\n",
                              "h.eom"));
}

TEST(HostileInput, ANonOrthogonalDcmIsRefused) {
  EXPECT_EQ(error_of("frame b = dcm(a, [[1, 0, 0], [0, 1, 0], [0, 0.1, 1]])\n" + body_in_b),
            "h.eom:1:18: error: dcm(): the matrix is not orthogonal at the parameters' default values (C C^T differs "
            "from the identity by 0.1): expected a rotation matrix");
}

TEST(HostileInput, AReflectionDcmIsRefused) {
  EXPECT_EQ(error_of("frame b = dcm(a, [[1, 0, 0], [0, 1, 0], [0, 0, -1]])\n" + body_in_b),
            "h.eom:1:18: error: dcm(): the matrix is a reflection (determinant -1) at the parameters' default values: "
            "expected a rotation matrix (determinant +1)");
  EXPECT_NO_THROW(parse_model("frame b = dcm(a, [[0, 1, 0], [-1, 0, 0], [0, 0, 1]])\n" + body_in_b, "h.eom"));
}

}  // namespace
}  // namespace eomgen
