// Matrix algebra in model expressions (issue 17): scalars times matrices, sums, products and
// transposes of columns and matrices, dcm(B, A) of two frames, used in inertias and in dcm(...)
// frames; each shape error with its whole message.
//
// Conventions (docs/conventions.md): C_ba converts components, v_b = C_ba v_a; C_ab = C_ba^T;
// C_ca = C_cb C_ba; C3(x) = [[c, s, 0], [-s, c, 0], [0, 0, 1]], C2(x) = [[c, 0, -s], [0, 1, 0],
// [s, 0, c]]. A frame `frame f = dcm(a, M)` has C_fa = M, so its rotation shows the value of M.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <string>

#include "eomgen/base/error.hpp"
#include "eomgen/derivation/model_equations.hpp"
#include "eomgen/derivation/numeric_evaluation.hpp"
#include "eomgen/language/model_file.hpp"
#include "support/expect_model_error.hpp"
#include "support/numeric_checks.hpp"

namespace eomgen {
namespace {

using testing::matrices_near;

// A valid point mass on lines 1-3; the cases put their statements before it, from line 1.
const std::string point_mass =
    "coordinate q\n"
    "point p = w + q*a.1\n"
    "particle m(mass = 1, at = p)\n";

std::string error_of(const std::string& text) { return testing::model_error_text(text, "m.eom"); }

double parameter_default(const Model& model, const std::string& name) {
  for (const Parameter& p : model.system.variables().parameters())
    if (p.name == name) return p.default_value;
  ADD_FAILURE() << "no parameter " << name;
  return 0;
}

// The value of `expression`, a constant scalar, as the default of a parameter.
double constant_value(const std::string& expression) {
  return parameter_default(parse_model("parameter k = " + expression + "\n" + point_mass, "m.eom"), "k");
}

Eigen::MatrixXd at_state(const GiNaC::matrix& m, const GiNaC::exmap& state) {
  Eigen::MatrixXd out(m.rows(), m.cols());
  for (unsigned i = 0; i < m.rows(); ++i)
    for (unsigned j = 0; j < m.cols(); ++j)
      out(i, j) = GiNaC::ex_to<GiNaC::numeric>(m(i, j).subs(state).evalf()).to_double();
  return out;
}

// C_fa of the frame `frame` of model at `state`.
Eigen::MatrixXd frame_dcm(const Model& model, const std::string& frame, const NamedValues& state) {
  const auto id = model.system.find_frame(frame);
  EXPECT_TRUE(id) << "no frame " << frame;
  return at_state(model.system.frame(*id).rotation.dcm(), numeric_substitution(model, state));
}

// The inertia of the model's only rigid body, at the parameters' defaults.
Eigen::MatrixXd inertia(const std::string& text) {
  const Model model = parse_model(text, "m.eom");
  return at_state(model.system.rigid_bodies().at(0).inertia, numeric_substitution(model, {}));
}

Eigen::Matrix3d C3(double x) {
  Eigen::Matrix3d c;
  c << std::cos(x), std::sin(x), 0, -std::sin(x), std::cos(x), 0, 0, 0, 1;
  return c;
}

// A rigid body turning about a fixed point, in inertia given by `inertia` in frame `body_frame`.
std::string top(const std::string& definitions, const std::string& body_frame, const std::string& inertia) {
  return "parameter l = 0.8\n"
         "parameter alpha = 0.4\n"
         "parameter J1 = 1\nparameter J2 = 2\nparameter J3 = 3\n"
         "coordinate q1, q2, q3\n"
         "frame b = euler(a, 321, q1, q2, q3)\n" +
         definitions + "point c0 = w + l*b.1 + l/2*b.3\n" + "body B(mass = 2, centre = c0, frame = " + body_frame +
         ", inertia = " + inertia + ")\n" + "gravity = -9.81*a.3\n";
}

// --- scalars, sums, negation ---

TEST(MatrixAlgebra, AScalarTimesAMatrixOnEitherSideScalesEveryEntry) {
  const std::string body = "parameter m0 = 3\nparameter l = 2\ncoordinate q\nframe b = rotate(a, 3, q)\n"
                           "body rod(mass = m0, centre = w, frame = b, inertia = ";
  Eigen::Matrix3d expected = Eigen::Matrix3d::Zero();
  expected.diagonal() << 1, 1, 2;  // 3 * 2^2 / 12 = 1
  EXPECT_TRUE(matrices_near(inertia(body + "m0*l^2/12*diag(1, 1, 2))\n"), expected, 1e-15));
  EXPECT_TRUE(matrices_near(inertia(body + "diag(1, 1, 2)*m0*l^2/12)\n"), expected, 1e-15));
  EXPECT_TRUE(matrices_near(inertia(body + "diag(m0, m0, 2*m0)*l^2/m0/4/3*m0)\n"), expected, 1e-15));
}

TEST(MatrixAlgebra, SumsDifferencesAndNegationsAreEntryByEntry) {
  Eigen::Matrix3d expected;
  expected << 3, 1, 0, 1, 4, 0, 0, 0, 5;
  EXPECT_TRUE(matrices_near(inertia("coordinate q\nframe b = rotate(a, 3, q)\nbody B(mass = 1, centre = w, frame = b, "
                                    "inertia = diag(1, 2, 3) + [[2, 1, 0], [1, 2, 0], [0, 0, 0]] - -diag(0, 0, 2))\n"),
                            expected, 1e-15));
  EXPECT_EQ(constant_value("[1, 0, 0]^T*(-[2, 3, 4] + 2*[5, 6, 7])"), 8.0);
}

TEST(MatrixAlgebra, AHundredThousandMatricesSumToTheirTotal) {
  std::string terms = "diag(1, 2, 3)";
  for (int i = 1; i < 100000; ++i) terms += i % 2 ? " + diag(1, 2, 3)" : " - diag(0, 1, 1)";
  // 50000 + 1 of diag(1, 2, 3), 49999 of -diag(0, 1, 1): diag(50001, 50003, 100004)
  // collected once per entry, not re-sorted at each term (which took minutes; 2.7 s now, measured
  // for issue 17 and no assertion here: the machines are shared, and under the sanitizers it took
  // 25 s. A return of the quadratic cost runs into ctest's timeout.)
  EXPECT_EQ(constant_value("[1, 1, 1]^T*(" + terms + ")*[1, 1, 1]"), 50001.0 + 50003.0 + 100004.0);
}

// --- products and transposes ---

TEST(MatrixAlgebra, ProductsFollowTheShapes) {
  // matrix * column is a column, row * column a scalar, column * row a matrix
  EXPECT_EQ(constant_value("[[1, 2, 3]]*[4, 5, 6]"), 32.0);
  EXPECT_EQ(constant_value("[0, 1]^T*[[1, 2], [3, 4]]*[1, 0]"), 3.0);
  EXPECT_EQ(constant_value("[[0, 1, 0]]*([1, 2, 3]*[[4, 5, 6]])*[0, 0, 1]"), 12.0);
  EXPECT_EQ(constant_value("[1, 2]^T*[[1, 2], [3, 4]]*[[0, 1], [1, 0]]*[1, 1]"), 17.0);  // [7, 10]*[1, 1]
}

TEST(MatrixAlgebra, TransposeAndTheExponentTAreTheSame) {
  EXPECT_EQ(constant_value("[0, 1]^T*transpose([[1, 2], [3, 4]])*[1, 0]"), 2.0);
  EXPECT_EQ(constant_value("[0, 1]^T*[[1, 2], [3, 4]]^T*[1, 0]"), 2.0);
  EXPECT_EQ(constant_value("transpose([1, 2])*[3, 4]"), 11.0);
}

TEST(MatrixAlgebra, ANameTIsAnExponentOfScalarsAndAfterAMatrixTheTranspose) {
  const Model m = parse_model("const T = 3\nparameter k = 2^T\nparameter r = [1, 0]^T*[[1, 2], [3, 4]]^T*[0, 1]\n" +
                                  point_mass,
                              "m.eom");
  EXPECT_EQ(parameter_default(m, "k"), 8.0);
  EXPECT_EQ(parameter_default(m, "r"), 3.0);
  const Model with_parameter = parse_model("parameter T = 2\ncoordinate q\nframe b = rotate(a, 3, q)\n"
                                           "frame f = dcm(a, dcm(b, a)^T)\npotential v = q^T\n"
                                           "body B(mass = 1, centre = w, frame = b, inertia = diag(1, 2, 3))\n",
                                           "m.eom");
  EXPECT_TRUE(matrices_near(frame_dcm(with_parameter, "f", {{"q", 0.3}}), C3(-0.3), 1e-15));
}

TEST(MatrixAlgebra, AChainOfVaryingMatricesHasItsValueUntilItsEntriesGrowTooLarge) {
  // C3(q)^n = C3(n q): the point f.1 turns at n q_dot, so M = n^2
  auto chain = [](int n) {
    std::string product = "dcm(b, a)";
    for (int i = 1; i < n; ++i) product += "*dcm(b, a)";
    return "coordinate q\nframe b = rotate(a, 3, q)\nframe f = dcm(a, " + product +
           ")\npoint p = w + f.1\nparticle P(mass = 1, at = p)\n";
  };
  const Model eight = parse_model(chain(8), "m.eom");
  EXPECT_NEAR(evaluate_equations(eight, derive_equations(eight), {{"q", 0.3}}).mass_matrix(0, 0), 64.0, 1e-12);
  // written out, each factor triples the entries: forty would take centuries to derive
  const std::string error = error_of(chain(40));
  const std::string message = ": error: the product's entries grow beyond 100000 operations written out: expected "
                              "fewer products of matrices that vary (the derivation's work grows with their size)";
  EXPECT_EQ(error.substr(0, 8), "m.eom:3:") << error;
  ASSERT_GT(error.size(), message.size()) << error;
  EXPECT_EQ(error.substr(error.size() - message.size()), message) << error;
}

// --- dcm(B, A) ---

TEST(MatrixAlgebra, DcmOfAFramePairIsThePrincipalRotation) {
  const Model m = parse_model("coordinate q\nframe b = rotate(a, 3, q)\nframe f = dcm(a, dcm(b, a))\n"
                              "frame g = dcm(a, transpose(dcm(b, a)))\n"
                              "body B(mass = 1, centre = w, frame = b, inertia = diag(1, 2, 3))\n",
                              "m.eom");
  for (const double q : {0.0, 0.3, -1.2, 2.5}) {
    EXPECT_TRUE(matrices_near(frame_dcm(m, "f", {{"q", q}}), C3(q), 1e-15)) << q;
    EXPECT_TRUE(matrices_near(frame_dcm(m, "g", {{"q", q}}), C3(-q), 1e-15)) << q;
  }
}

TEST(MatrixAlgebra, DcmsCompoundAndTransposeAsTheConventionsSay) {
  const Model m = parse_model("coordinate q1, q2, q3\n"
                              "frame b = rotate(a, 3, q1)\n"
                              "frame c = euler(b, 123, q2, q3, 0.7)\n"
                              "frame whole = dcm(a, dcm(c, a))\n"
                              "frame chained = dcm(a, dcm(c, b)*dcm(b, a))\n"
                              "frame back = dcm(a, transpose(dcm(c, a)))\n"
                              "frame reverse = dcm(a, dcm(a, c))\n"
                              "frame exponent = dcm(a, dcm(c, a)^T)\n"
                              "body B(mass = 1, centre = w, frame = c, inertia = diag(1, 2, 3))\n",
                              "m.eom");
  for (const NamedValues& state : {NamedValues{{"q1", 0.3}, {"q2", -0.8}, {"q3", 1.1}},
                                   NamedValues{{"q1", -2.1}, {"q2", 0.5}, {"q3", -0.2}}}) {
    const Eigen::MatrixXd C_ca = frame_dcm(m, "whole", state);
    EXPECT_TRUE(matrices_near(frame_dcm(m, "chained", state), C_ca, 1e-14));
    EXPECT_TRUE(matrices_near(frame_dcm(m, "back", state), C_ca.transpose(), 1e-14));
    EXPECT_TRUE(matrices_near(frame_dcm(m, "reverse", state), C_ca.transpose(), 1e-14));
    EXPECT_TRUE(matrices_near(frame_dcm(m, "exponent", state), C_ca.transpose(), 1e-14));
    EXPECT_TRUE(matrices_near(C_ca * C_ca.transpose(), Eigen::Matrix3d::Identity(), 1e-14));
  }
}

TEST(MatrixAlgebra, AFrameFromADcmProductTurnsLikeTheFrameItCopies) {
  // d = dcm(a, C_ba) has the attitude of b, so a body in d has b's equations
  const std::string in_b = "body B(mass = 2, centre = p, frame = b, inertia = diag(1, 2, 3))\n";
  const std::string in_d = "frame d = dcm(a, dcm(b, c)*dcm(c, a))\nbody B(mass = 2, centre = p, frame = d, "
                           "inertia = diag(1, 2, 3))\n";
  const std::string frames = "coordinate q1, q2\nframe c = rotate(a, 1, q1)\nframe b = rotate(c, 3, q2)\n"
                             "point p = w + b.1\ngravity = -9.81*a.3\n";
  const Model x = parse_model(frames + in_b, "m.eom"), y = parse_model(frames + in_d, "m.eom");
  const NamedValues state{{"q1", 0.4}, {"q2", -1.3}, {"q1_dot", 0.7}, {"q2_dot", -0.2}};
  const NumericEquations copied = evaluate_equations(y, derive_equations(y), state);
  const NumericEquations original = evaluate_equations(x, derive_equations(x), state);
  EXPECT_TRUE(matrices_near(copied.mass_matrix, original.mass_matrix, 1e-12));
  EXPECT_TRUE(matrices_near(copied.forcing, original.forcing, 1e-12));
}

// --- inertias ---

TEST(MatrixAlgebra, AnInertiaRotatedIntoTheBodyFrameGivesTheEquationsOfItsNineEntries) {
  // c = rotate(b, 2, alpha): C_bc = C2(alpha)^T, and C_bc diag(J1, J2, J3) C_bc^T multiplied out
  const std::string frame_c = "frame c = rotate(b, 2, alpha)\n";
  const std::string nine_entries =
      "[[cos(alpha)^2*J1 + sin(alpha)^2*J3, 0, cos(alpha)*sin(alpha)*(J3 - J1)], [0, J2, 0], "
      "[cos(alpha)*sin(alpha)*(J3 - J1), 0, sin(alpha)^2*J1 + cos(alpha)^2*J3]]";
  const std::string rotated = "dcm(b, c)*diag(J1, J2, J3)*dcm(b, c)^T";
  const std::string transposed = "dcm(b, c)*diag(J1, J2, J3)*transpose(dcm(b, c))";
  const std::string from_c = "dcm(c, b)^T*diag(J1, J2, J3)*dcm(c, b)";
  const Model by_hand = parse_model(top(frame_c, "b", nine_entries), "m.eom");
  const Model in_c = parse_model(top(frame_c, "c", "diag(J1, J2, J3)"), "m.eom");
  for (const std::string& inertia : {rotated, transposed, from_c}) {
    SCOPED_TRACE(inertia);
    const Model m = parse_model(top(frame_c, "b", inertia), "m.eom");
    for (const NamedValues& state : {NamedValues{{"q1", 0.3}, {"q2", -0.8}, {"q3", 1.1}, {"q1_dot", 0.4},
                                                 {"q2_dot", -1.3}, {"q3_dot", 0.9}},
                                     NamedValues{{"q1", -2.1}, {"q2", 0.5}, {"q3", -0.2}, {"q1_dot", -0.7},
                                                 {"q2_dot", 0.2}, {"q3_dot", 1.6}}}) {
      const NumericEquations x = evaluate_equations(m, derive_equations(m), state);
      const NumericEquations hand = evaluate_equations(by_hand, derive_equations(by_hand), state);
      const NumericEquations c = evaluate_equations(in_c, derive_equations(in_c), state);
      EXPECT_TRUE(matrices_near(x.mass_matrix, hand.mass_matrix, 1e-12));
      EXPECT_TRUE(matrices_near(x.forcing, hand.forcing, 1e-12));
      EXPECT_TRUE(matrices_near(x.mass_matrix, c.mass_matrix, 1e-12));
      EXPECT_TRUE(matrices_near(x.forcing, c.forcing, 1e-12));
    }
  }
}

// --- shape errors ---

TEST(MatrixAlgebra, AProductOfMismatchedShapesNamesBothShapes) {
  EXPECT_EQ(error_of("parameter k = [1, 0, 0]^T*diag(1, 2, 3)*[1, 2]\n" + point_mass),
            "m.eom:1:40: error: cannot multiply a 1x3 matrix and a 2x1 column: expected a right factor with 3 rows, "
            "as many as the left has columns");
  EXPECT_EQ(error_of("parameter k = [1, 2]*[3, 4]\n" + point_mass),
            "m.eom:1:21: error: cannot multiply a 2x1 column and a 2x1 column: expected a right factor with 1 row, "
            "as many as the left has columns");
}

TEST(MatrixAlgebra, ASumOfMismatchedShapesOrKindsNamesBoth) {
  EXPECT_EQ(error_of("parameter k = diag(1, 2, 3) + [1, 2, 3]\n" + point_mass),
            "m.eom:1:29: error: cannot add a 3x3 matrix and a 3x1 column: expected the same shape, 3x3");
  EXPECT_EQ(error_of("parameter k = diag(1, 2, 3) - 1\n" + point_mass),
            "m.eom:1:29: error: cannot subtract a 3x3 matrix and a scalar");
  EXPECT_EQ(error_of("parameter k = 1 + [1, 2]\n" + point_mass),
            "m.eom:1:17: error: cannot add a scalar and a 2x1 column");
}

TEST(MatrixAlgebra, MatricesAndPhysicalVectorsDoNotMultiply) {
  EXPECT_EQ(error_of("output o = diag(1, 2, 3)*a.1\n" + point_mass),
            "m.eom:1:25: error: cannot multiply a 3x3 matrix and a vector: expected a scalar, a column or a matrix");
  EXPECT_EQ(error_of("output o = 2*a.1*[1, 2, 3]\n" + point_mass),
            "m.eom:1:17: error: cannot multiply a vector and a 3x1 column: expected a scalar");
}

TEST(MatrixAlgebra, OnlyScalarsDivide) {
  EXPECT_EQ(error_of("parameter k = 1/diag(1, 2, 3)\n" + point_mass),
            "m.eom:1:16: error: cannot divide by a 3x3 matrix");
  EXPECT_EQ(constant_value("[1, 1]^T*[[2, 4], [6, 8]]/2*[1, 0]"), 4.0);
}

TEST(MatrixAlgebra, PowersOfNonScalarsSayWhatToWriteInstead) {
  EXPECT_EQ(error_of("output o = a.1^2\n" + point_mass),
            "m.eom:1:15: error: cannot raise a vector to a power: use dot(v, v) for its squared length");
  EXPECT_EQ(error_of("parameter k = diag(1, 2, 3)^2\n" + point_mass),
            "m.eom:1:28: error: cannot raise a 3x3 matrix to a power: expected M^T, its transpose, the only exponent "
            "of a matrix or a column (for a power, write the product M*M)");
  EXPECT_EQ(error_of("parameter k = 2^[1, 2]\n" + point_mass),
            "m.eom:1:16: error: cannot raise a scalar to the power of a 2x1 column: expected a scalar exponent");
}

TEST(MatrixAlgebra, TransposeTakesAMatrixOrAColumn) {
  EXPECT_EQ(error_of("parameter k = transpose(2)\n" + point_mass),
            "m.eom:1:25: error: argument 1 of transpose(): expected a matrix or a column, got a scalar");
}

TEST(MatrixAlgebra, DcmInAnExpressionTakesTwoFrames) {
  EXPECT_EQ(error_of("parameter k = [1, 0, 0]^T*dcm(a, diag(1, 1, 1))*[1, 0, 0]\n" + point_mass),
            "m.eom:1:34: error: argument 2 of dcm(): expected a frame: dcm(B, A) is the matrix C_BA of two frames "
            "(dcm(PARENT, MATRIX) defines a frame: 'frame NAME = dcm(...)')");
  EXPECT_EQ(error_of("frame b = rotate(a, 3, q)\noutput o = [1, 0, 0]^T*dcm(bb, a)*[1, 0, 0]\n" + point_mass),
            "m.eom:2:28: error: unknown frame 'bb'; did you mean 'b'?");
}

TEST(MatrixAlgebra, AnInertiaThatIsNotAThreeByThreeMatrixNamesWhatItIs) {
  EXPECT_EQ(error_of("coordinate q\nframe b = rotate(a, 3, q)\n"
                     "body B(mass = 1, centre = w, frame = b, inertia = 2*[1, 2, 3])\n"),
            "m.eom:3:51: error: body 'B': 'inertia' must be a 3x3 matrix, e.g. diag(J1, J2, J3), got a 3x1 column");
}

TEST(MatrixAlgebra, AFrameDcmNamesTheShapeItGotAndChecksAConstantProduct) {
  EXPECT_EQ(error_of("frame c = dcm(a, [1, 0, 0]^T)\n" + point_mass),
            "m.eom:1:18: error: dcm(): expected a 3x3 matrix such as [[C11, C12, C13], [C21, C22, C23], [C31, C32, "
            "C33]] or dcm(B, A), got a 1x3 matrix");
  EXPECT_EQ(error_of("frame b = rotate(a, 3, q)\nframe c = dcm(b, a)\n" + point_mass),
            "m.eom:2:18: error: dcm(): expected a 3x3 matrix after the parent frame, got the frame 'a' (the DCM of "
            "two frames is the matrix dcm(B, A): dcm(PARENT, dcm(B, A)))");
  EXPECT_EQ(error_of("frame b = rotate(a, 3, 0.5)\nframe c = dcm(a, 2*dcm(b, a))\n" + point_mass),
            "m.eom:2:18: error: dcm(): the matrix is not orthogonal at the parameters' default values (C C^T differs "
            "from the identity by 3): expected a rotation matrix");
  EXPECT_EQ(error_of("frame b = rotate(a, 3, 0.5)\nframe c = dcm(a, dcm(b, a)*diag(1, 1, -1))\n" + point_mass),
            "m.eom:2:18: error: dcm(): the matrix is a reflection (determinant -1) at the parameters' default values: "
            "expected a rotation matrix (determinant +1)");
}

// --- the arity of frame functions counts the parent, as the usage does ---

TEST(MatrixAlgebra, FrameFunctionsCountTheirArgumentsAsWritten) {
  EXPECT_EQ(error_of("coordinate x, y\nframe b = euler(a, 313, x, y)\n" + point_mass),
            "m.eom:2:11: error: euler(PARENT, SEQUENCE, ANGLE1, ANGLE2, ANGLE3) takes 5 arguments, got 4");
  EXPECT_EQ(error_of("frame b = rotate(a, 3)\n" + point_mass),
            "m.eom:1:11: error: rotate(PARENT, AXIS, ANGLE) takes 3 arguments, got 2");
  EXPECT_EQ(error_of("frame b = mrp(a, [0, 0, 1], 2)\n" + point_mass),
            "m.eom:1:11: error: mrp(PARENT, [P1, P2, P3]) takes 2 arguments, got 3");
  EXPECT_EQ(error_of("frame b = dcm(a)\n" + point_mass),
            "m.eom:1:11: error: dcm(PARENT, MATRIX) takes 2 arguments, got 1");
}

TEST(MatrixAlgebra, OtherFrameFunctionsInExpressionsStillDefineFramesOnly) {
  EXPECT_EQ(error_of("output o = rotate(a, 3, q)\n" + point_mass),
            "m.eom:1:12: error: rotate() defines a frame: use it as 'frame NAME = rotate(...)'");
}

}  // namespace
}  // namespace eomgen
