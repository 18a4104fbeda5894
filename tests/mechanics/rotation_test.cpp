// Tests of the direction cosine matrices and angular velocities of eomgen/rotation.hpp against
// docs/conventions.md and the course notes (Example 2.9, Example 2.11, the Euler 1-2-3 rate example).
#include "eomgen/mechanics/rotation.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "eomgen/base/error.hpp"
#include "eomgen/mechanics/variables.hpp"
#include "support/expect_throw.hpp"
#include "support/symbolic_checks.hpp"

namespace {

using eomgen::EulerSequence;
using eomgen::Rotation;
using eomgen::Variables;
using eomgen::testing::equal_after_expansion;
using eomgen::testing::matrices_near;
using eomgen::testing::value_at;
using GiNaC::cos;
using GiNaC::ex;
using GiNaC::exmap;
using GiNaC::lst;
using GiNaC::matrix;
using GiNaC::realsymbol;
using GiNaC::sin;

constexpr double kTol = 1e-12;

const std::vector<std::string>& all_sequences() {
  static const std::vector<std::string> s{"1-2-1", "1-3-1", "2-1-2", "2-3-2", "3-1-3", "3-2-3",
                                          "1-2-3", "1-3-2", "2-1-3", "2-3-1", "3-1-2", "3-2-1"};
  return s;
}

matrix mat3(const ex& a11, const ex& a12, const ex& a13, const ex& a21, const ex& a22, const ex& a23,
            const ex& a31, const ex& a32, const ex& a33) {
  return matrix(3, 3, lst{a11, a12, a13, a21, a22, a23, a31, a32, a33});
}

matrix col3(const ex& a, const ex& b, const ex& c) { return matrix(3, 1, lst{a, b, c}); }

::testing::AssertionResult is_rotation(const Eigen::MatrixXd& C) {
  if (C.rows() != 3 || C.cols() != 3) return ::testing::AssertionFailure() << "not 3x3";
  const double orth = (C * C.transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  const double det = C.determinant();
  if (orth <= kTol && std::fabs(det - 1.0) <= kTol) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "|C C^T - 1| = " << orth << ", det C = " << det << "\n" << C;
}

/// What EulerSequence::parse says of a text that is not one of the twelve sequences.
std::string euler_sequence_error(const std::string& text) {
  return "Euler sequence '" + text +
         "': expected three axes from 1, 2, 3 with no two consecutive axes equal, such as \"3-2-1\" or \"3-1-3\"";
}

Eigen::Matrix3d skew(const Eigen::Vector3d& u) {
  Eigen::Matrix3d m;
  m << 0, -u(2), u(1), u(2), 0, -u(0), -u(1), u(0), 0;
  return m;
}

Eigen::Vector3d random_unit(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Vector3d a;
  do a = Eigen::Vector3d(n(rng), n(rng), n(rng));
  while (a.norm() < 0.1);
  return a.normalized();
}

double uniform(std::mt19937& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

Eigen::Vector3d random_vec(std::mt19937& rng, double r = 1.5) {
  return Eigen::Vector3d(uniform(rng, -r, r), uniform(rng, -r, r), uniform(rng, -r, r));
}

/// Numeric (Eigen) principal rotation, with the sign of the sines of docs/conventions.md.
Eigen::Matrix3d C_num(int axis, double x) {
  const double c = std::cos(x), s = std::sin(x);
  Eigen::Matrix3d m;
  if (axis == 1) m << 1, 0, 0, 0, c, s, 0, -s, c;
  if (axis == 2) m << c, 0, -s, 0, 1, 0, s, 0, c;
  if (axis == 3) m << c, s, 0, -s, c, 0, 0, 0, 1;
  return m;
}

/// Numeric axis/angle C = cos(phi) 1 + (1 - cos(phi)) a a^T - sin(phi) a^x.
Eigen::Matrix3d axis_angle_num(const Eigen::Vector3d& a, double phi) {
  return std::cos(phi) * Eigen::Matrix3d::Identity() + (1 - std::cos(phi)) * a * a.transpose() -
         std::sin(phi) * skew(a);
}

// ---------------------------------------------------------------------------------------------
// 1. Principal rotations

TEST(PrincipalRotation, C1HasPlusSineAboveTheDiagonal) {
  const realsymbol x("x");
  const ex c = cos(x), s = sin(x);
  EXPECT_TRUE(equal_after_expansion(eomgen::principal_rotation(1, x), mat3(1, 0, 0, 0, c, s, 0, -s, c)));
}

TEST(PrincipalRotation, C2HasMinusSineAboveTheDiagonal) {
  const realsymbol x("x");
  const ex c = cos(x), s = sin(x);
  EXPECT_TRUE(equal_after_expansion(eomgen::principal_rotation(2, x), mat3(c, 0, -s, 0, 1, 0, s, 0, c)));
}

TEST(PrincipalRotation, C3HasPlusSineAboveTheDiagonal) {
  const realsymbol x("x");
  const ex c = cos(x), s = sin(x);
  EXPECT_TRUE(equal_after_expansion(eomgen::principal_rotation(3, x), mat3(c, s, 0, -s, c, 0, 0, 0, 1)));
}

TEST(PrincipalRotation, RotationFactoryHoldsThePrincipalMatrixAxisAndAngle) {
  const realsymbol x("x");
  for (int axis = 1; axis <= 3; ++axis) {
    const Rotation r = Rotation::principal(axis, x);
    EXPECT_EQ(r.kind(), Rotation::Kind::principal);
    EXPECT_EQ(r.axes()[0], axis);
    ASSERT_EQ(r.parameters().nops(), 1u);
    EXPECT_TRUE(r.parameters().op(0).is_equal(x));
    EXPECT_TRUE(equal_after_expansion(r.dcm(), eomgen::principal_rotation(axis, x)));
  }
}

TEST(PrincipalRotation, NotesExample2_11C3OfHalfPiMapsComponents) {
  // u_a = [0 2 1]^T, C_ba = C3(pi/2)  =>  u_b = [2 0 1]^T, exactly
  const matrix C = eomgen::principal_rotation(3, GiNaC::Pi / 2);
  EXPECT_TRUE(equal_after_expansion(C, mat3(0, 1, 0, -1, 0, 0, 0, 0, 1)));
  EXPECT_TRUE(equal_after_expansion(C.mul(col3(0, 2, 1)), col3(2, 0, 1)));
}

TEST(PrincipalRotation, AxisOutsideOneToThreeThrowsModelError) {
  const realsymbol x("x");
  EXPECT_THROW_MESSAGE(eomgen::principal_rotation(0, x), eomgen::ModelError,
                       "principal rotation: expected axis 1, 2 or 3, got 0");
  EXPECT_THROW_MESSAGE(eomgen::principal_rotation(4, x), eomgen::ModelError,
                       "principal rotation: expected axis 1, 2 or 3, got 4");
  EXPECT_THROW_MESSAGE(Rotation::principal(-1, x), eomgen::ModelError,
                       "principal rotation: expected axis 1, 2 or 3, got -1");
  EXPECT_THROW_MESSAGE(eomgen::unit_column(0), eomgen::ModelError,
                       "principal rotation: expected axis 1, 2 or 3, got 0");
}

TEST(PrincipalRotation, UnitColumnsAreColumnsOfTheIdentity) {
  EXPECT_TRUE(equal_after_expansion(eomgen::unit_column(1), col3(1, 0, 0)));
  EXPECT_TRUE(equal_after_expansion(eomgen::unit_column(2), col3(0, 1, 0)));
  EXPECT_TRUE(equal_after_expansion(eomgen::unit_column(3), col3(0, 0, 1)));
}

// ---------------------------------------------------------------------------------------------
// 2. Every parameterization gives a proper orthonormal C

TEST(Orthonormality, IdentityRotationIsTheIdentity) {
  const Rotation r = Rotation::identity();
  EXPECT_EQ(r.kind(), Rotation::Kind::identity);
  EXPECT_TRUE(equal_after_expansion(r.dcm(), GiNaC::ex_to<matrix>(GiNaC::unit_matrix(3))));
}

TEST(Orthonormality, PrincipalRotationsAreProperOrthonormal) {
  const realsymbol x("x");
  std::mt19937 rng(11);
  for (int axis = 1; axis <= 3; ++axis)
    for (int k = 0; k < 4; ++k) {
      const exmap at{{x, uniform(rng, -4, 4)}};
      EXPECT_TRUE(is_rotation(value_at(Rotation::principal(axis, x).dcm(), at))) << "axis " << axis;
    }
}

TEST(Orthonormality, AllTwelveEulerSequencesAreProperOrthonormal) {
  const realsymbol t1("t1"), t2("t2"), t3("t3");
  std::mt19937 rng(12);
  for (const auto& name : all_sequences()) {
    const matrix C = Rotation::euler(EulerSequence::parse(name), t1, t2, t3).dcm();
    for (int k = 0; k < 4; ++k) {
      const exmap at{{t1, uniform(rng, -4, 4)}, {t2, uniform(rng, -4, 4)}, {t3, uniform(rng, -4, 4)}};
      EXPECT_TRUE(is_rotation(value_at(C, at))) << name;
    }
  }
}

TEST(Orthonormality, AxisAngleWithUnitAxisIsProperOrthonormal) {
  const realsymbol a1("a1"), a2("a2"), a3("a3"), phi("phi");
  const matrix C = Rotation::axis_angle(col3(a1, a2, a3), phi).dcm();
  std::mt19937 rng(13);
  for (int k = 0; k < 6; ++k) {
    const Eigen::Vector3d a = random_unit(rng);
    const exmap at{{a1, a(0)}, {a2, a(1)}, {a3, a(2)}, {phi, uniform(rng, -6, 6)}};
    EXPECT_TRUE(is_rotation(value_at(C, at)));
  }
}

TEST(Orthonormality, UnitQuaternionIsProperOrthonormal) {
  const realsymbol e1("e1"), e2("e2"), e3("e3"), eta("eta");
  const matrix C = Rotation::quaternion(col3(e1, e2, e3), eta).dcm();
  std::mt19937 rng(14);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int k = 0; k < 6; ++k) {
    Eigen::Vector4d q(n(rng), n(rng), n(rng), n(rng));
    q.normalize();
    const exmap at{{e1, q(0)}, {e2, q(1)}, {e3, q(2)}, {eta, q(3)}};
    EXPECT_TRUE(is_rotation(value_at(C, at)));
  }
}

TEST(Orthonormality, RodriguesParametersGiveProperOrthonormal) {
  const realsymbol p1("p1"), p2("p2"), p3("p3");
  const matrix C = Rotation::rodrigues(col3(p1, p2, p3)).dcm();
  std::mt19937 rng(15);
  for (int k = 0; k < 6; ++k) {
    const Eigen::Vector3d p = random_vec(rng, 3.0);
    EXPECT_TRUE(is_rotation(value_at(C, {{p1, p(0)}, {p2, p(1)}, {p3, p(2)}})));
  }
}

TEST(Orthonormality, ModifiedRodriguesParametersGiveProperOrthonormal) {
  const realsymbol s1("s1"), s2("s2"), s3("s3");
  const matrix C = Rotation::modified_rodrigues(col3(s1, s2, s3)).dcm();
  std::mt19937 rng(16);
  for (int k = 0; k < 6; ++k) {
    const Eigen::Vector3d s = random_vec(rng, 2.0);
    EXPECT_TRUE(is_rotation(value_at(C, {{s1, s(0)}, {s2, s(1)}, {s3, s(2)}})));
  }
}

TEST(Orthonormality, ExplicitMatrixIsKeptAsGivenAndIsProperOrthonormal) {
  const realsymbol x("x"), y("y"), z("z");
  const matrix given = eomgen::principal_rotation(2, z)
                           .mul(eomgen::principal_rotation(1, y))
                           .mul(eomgen::principal_rotation(3, x));
  const Rotation r = Rotation::explicit_matrix(given);
  EXPECT_EQ(r.kind(), Rotation::Kind::matrix);
  EXPECT_TRUE(equal_after_expansion(r.dcm(), given));
  std::mt19937 rng(17);
  for (int k = 0; k < 4; ++k) {
    const exmap at{{x, uniform(rng, -4, 4)}, {y, uniform(rng, -4, 4)}, {z, uniform(rng, -4, 4)}};
    EXPECT_TRUE(is_rotation(value_at(r.dcm(), at)));
  }
}

TEST(Orthonormality, WrongShapesThrowModelError) {
  const realsymbol x("x");
  EXPECT_THROW_MESSAGE(Rotation::explicit_matrix(matrix(2, 2)), eomgen::ModelError,
                       "explicit rotation matrix: expected 3x3, got 2x2");
  EXPECT_THROW_MESSAGE(Rotation::quaternion(matrix(4, 1), x), eomgen::ModelError,
                       "quaternion rotation: expected a 3x1 column, got 4x1");
  EXPECT_THROW_MESSAGE(Rotation::axis_angle(matrix(1, 3), x), eomgen::ModelError,
                       "axis/angle rotation: expected a 3x1 column, got 1x3");
  EXPECT_THROW_MESSAGE(Rotation::rodrigues(matrix(2, 1)), eomgen::ModelError,
                       "Rodrigues rotation: expected a 3x1 column, got 2x1");
  EXPECT_THROW_MESSAGE(Rotation::modified_rodrigues(matrix(3, 3)), eomgen::ModelError,
                       "modified Rodrigues rotation: expected a 3x1 column, got 3x3");
  EXPECT_THROW_MESSAGE(eomgen::cross_matrix(matrix(1, 3)), eomgen::ModelError,
                       "cross operator: expected a 3x1 column, got 1x3");
}

// ---------------------------------------------------------------------------------------------
// 3. Cross-agreement between parameterizations

TEST(CrossAgreement, QuaternionOfAxisAndHalfAngleEqualsAxisAngle) {
  const realsymbol a1("a1"), a2("a2"), a3("a3"), phi("phi");
  const matrix a = col3(a1, a2, a3);
  const matrix Cq = Rotation::quaternion(a.mul_scalar(sin(phi / 2)), cos(phi / 2)).dcm();
  const matrix Ca = Rotation::axis_angle(a, phi).dcm();
  std::mt19937 rng(21);
  for (int k = 0; k < 6; ++k) {
    const Eigen::Vector3d u = random_unit(rng);
    const double angle = uniform(rng, -6, 6);
    const exmap at{{a1, u(0)}, {a2, u(1)}, {a3, u(2)}, {phi, angle}};
    EXPECT_TRUE(matrices_near(value_at(Cq, at), value_at(Ca, at), kTol));
    // and both equal the closed form of docs/conventions.md evaluated independently
    EXPECT_TRUE(matrices_near(value_at(Ca, at), axis_angle_num(u, angle), kTol));
  }
}

TEST(CrossAgreement, QuaternionAndItsNegativeGiveTheSameC) {
  const realsymbol e1("e1"), e2("e2"), e3("e3"), eta("eta");
  const matrix Cp = eomgen::quaternion_rotation(col3(e1, e2, e3), eta);
  const matrix Cm = eomgen::quaternion_rotation(col3(-e1, -e2, -e3), -eta);
  EXPECT_TRUE(equal_after_expansion(Cp, Cm));
}

TEST(CrossAgreement, RodriguesAndModifiedRodriguesOfAQuaternionGiveItsC) {
  const realsymbol e1("e1"), e2("e2"), e3("e3"), eta("eta");
  const matrix eps = col3(e1, e2, e3);
  const matrix Cq = eomgen::quaternion_rotation(eps, eta);
  const matrix Cp = eomgen::rodrigues_rotation(eps.mul_scalar(1 / eta));
  const matrix Cs = eomgen::modified_rodrigues_rotation(eps.mul_scalar(1 / (1 + eta)));
  std::mt19937 rng(22);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int k = 0; k < 8; ++k) {
    Eigen::Vector4d q;
    do {
      q = Eigen::Vector4d(n(rng), n(rng), n(rng), n(rng)).normalized();
    } while (std::fabs(q(3)) < 0.2);  // away from the Rodrigues singularity eta = 0
    const exmap at{{e1, q(0)}, {e2, q(1)}, {e3, q(2)}, {eta, q(3)}};
    const Eigen::MatrixXd C = value_at(Cq, at);
    EXPECT_TRUE(matrices_near(value_at(Cp, at), C, kTol));
    EXPECT_TRUE(matrices_near(value_at(Cs, at), C, kTol));
  }
}

TEST(CrossAgreement, EachEulerSequenceIsTheProductOfItsPrincipalRotations) {
  struct Case {
    const char* name;
    int i, j, k;
  };
  const Case cases[] = {{"1-2-1", 1, 2, 1}, {"1-3-1", 1, 3, 1}, {"2-1-2", 2, 1, 2}, {"2-3-2", 2, 3, 2},
                        {"3-1-3", 3, 1, 3}, {"3-2-3", 3, 2, 3}, {"1-2-3", 1, 2, 3}, {"1-3-2", 1, 3, 2},
                        {"2-1-3", 2, 1, 3}, {"2-3-1", 2, 3, 1}, {"3-1-2", 3, 1, 2}, {"3-2-1", 3, 2, 1}};
  const realsymbol t1("t1"), t2("t2"), t3("t3");
  for (const auto& c : cases) {
    // C_ba = Ck(t3) Cj(t2) Ci(t1): the rotation about i applied first
    const matrix expected = eomgen::principal_rotation(c.k, t3)
                                .mul(eomgen::principal_rotation(c.j, t2))
                                .mul(eomgen::principal_rotation(c.i, t1));
    const EulerSequence seq = EulerSequence::parse(c.name);
    const Rotation r = Rotation::euler(seq, t1, t2, t3);
    EXPECT_EQ(r.kind(), Rotation::Kind::euler);
    EXPECT_EQ(r.axes(), (std::array<int, 3>{c.i, c.j, c.k})) << c.name;
    EXPECT_TRUE(equal_after_expansion(r.dcm(), expected)) << c.name;
    EXPECT_TRUE(equal_after_expansion(eomgen::euler_rotation(seq, t1, t2, t3), expected)) << c.name;
  }
}

TEST(CrossAgreement, EulerSequenceMatchesProductOfNumericPrincipalRotations) {
  // independent of the library's principal_rotation: Eigen matrices written from docs/conventions.md
  const realsymbol t1("t1"), t2("t2"), t3("t3");
  std::mt19937 rng(23);
  for (const auto& name : all_sequences()) {
    const EulerSequence seq = EulerSequence::parse(name);
    const matrix C = eomgen::euler_rotation(seq, t1, t2, t3);
    const double x1 = uniform(rng, -3, 3), x2 = uniform(rng, -3, 3), x3 = uniform(rng, -3, 3);
    const Eigen::Matrix3d expected = C_num(seq.axes[2], x3) * C_num(seq.axes[1], x2) * C_num(seq.axes[0], x1);
    EXPECT_TRUE(matrices_near(value_at(C, {{t1, x1}, {t2, x2}, {t3, x3}}), expected, kTol)) << name;
  }
}

TEST(CrossAgreement, Euler313MatchesHandWrittenMatrix) {
  const realsymbol t1("t1"), t2("t2"), t3("t3");
  const ex c1 = cos(t1), s1 = sin(t1), c2 = cos(t2), s2 = sin(t2), c3 = cos(t3), s3 = sin(t3);
  // C3(t3) C1(t2) C3(t1), multiplied out by hand
  const matrix hand = mat3(c3 * c1 - s3 * c2 * s1, c3 * s1 + s3 * c2 * c1, s3 * s2,     //
                           -s3 * c1 - c3 * c2 * s1, -s3 * s1 + c3 * c2 * c1, c3 * s2,  //
                           s2 * s1, -s2 * c1, c2);
  EXPECT_TRUE(equal_after_expansion(eomgen::euler_rotation(EulerSequence::parse("3-1-3"), t1, t2, t3), hand));
}

TEST(CrossAgreement, Euler313AtKnownAnglesIsExact) {
  // 3-1-3 with (pi/2, pi/2, 0): C1(pi/2) C3(pi/2), a cyclic permutation
  const matrix C = eomgen::euler_rotation(EulerSequence::parse("3-1-3"), GiNaC::Pi / 2, GiNaC::Pi / 2, 0);
  EXPECT_TRUE(equal_after_expansion(C, mat3(0, 1, 0, 0, 0, 1, 1, 0, 0)));
}

TEST(CrossAgreement, Euler321MatchesHandWrittenMatrix) {
  const realsymbol psi("psi"), theta("theta"), phi("phi");
  const ex cps = cos(psi), sps = sin(psi), ct = cos(theta), st = sin(theta), cph = cos(phi),
           sph = sin(phi);
  // C1(phi) C2(theta) C3(psi), multiplied out by hand
  const matrix hand = mat3(ct * cps, ct * sps, -st,                                      //
                           sph * st * cps - cph * sps, sph * st * sps + cph * cps, sph * ct,  //
                           cph * st * cps + sph * sps, cph * st * sps - sph * cps, cph * ct);
  EXPECT_TRUE(equal_after_expansion(eomgen::euler_rotation(EulerSequence::parse("3-2-1"), psi, theta, phi), hand));
}

TEST(CrossAgreement, Euler321AtKnownAnglesIsExact) {
  const auto seq = EulerSequence::parse("3-2-1");
  // yaw alone: C3(pi/2)
  EXPECT_TRUE(
      equal_after_expansion(eomgen::euler_rotation(seq, GiNaC::Pi / 2, 0, 0), mat3(0, 1, 0, -1, 0, 0, 0, 0, 1)));
  // (pi/2, pi/2, 0): C2(pi/2) C3(pi/2)
  EXPECT_TRUE(equal_after_expansion(eomgen::euler_rotation(seq, GiNaC::Pi / 2, GiNaC::Pi / 2, 0),
                                    mat3(0, 0, -1, -1, 0, 0, 0, 1, 0)));
}

TEST(CrossAgreement, AxisAngleAboutEachUnitAxisIsThePrincipalRotation) {
  const realsymbol phi("phi");
  for (int axis = 1; axis <= 3; ++axis)
    EXPECT_TRUE(equal_after_expansion(eomgen::axis_angle_rotation(eomgen::unit_column(axis), phi),
                                      eomgen::principal_rotation(axis, phi)))
        << "axis " << axis;
}

TEST(CrossAgreement, QuaternionAboutOneThreeIsC3) {
  const realsymbol phi("phi");
  const matrix C = eomgen::quaternion_rotation(col3(0, 0, sin(phi / 2)), cos(phi / 2));
  std::mt19937 rng(24);
  for (int k = 0; k < 4; ++k) {
    const double x = uniform(rng, -6, 6);
    EXPECT_TRUE(matrices_near(value_at(C, {{phi, x}}), C_num(3, x), kTol));
  }
}

// ---------------------------------------------------------------------------------------------
// 4. Example 2.9 of the notes

TEST(NotesExample2_9, C1C2C1MatchesHandComputation) {
  const realsymbol a("alpha"), b("beta"), g("gamma");
  const ex ca = cos(a), sa = sin(a), cb = cos(b), sb = sin(b), cg = cos(g), sg = sin(g);
  // C1(g) C2(b) C1(a), worked by hand: C2(b) C1(a) = [[cb, sb sa, -sb ca], [0, ca, sa],
  // [sb, -cb sa, cb ca]], then C1(g) mixes rows 2 and 3.
  const matrix hand = mat3(cb, sb * sa, -sb * ca,                                 //
                           sg * sb, cg * ca - sg * cb * sa, cg * sa + sg * cb * ca,  //
                           cg * sb, -sg * ca - cg * cb * sa, -sg * sa + cg * cb * ca);
  const matrix product = eomgen::principal_rotation(1, g)
                             .mul(eomgen::principal_rotation(2, b))
                             .mul(eomgen::principal_rotation(1, a));
  EXPECT_TRUE(equal_after_expansion(product, hand));
  EXPECT_TRUE(equal_after_expansion(eomgen::euler_rotation(EulerSequence::parse("1-2-1"), a, b, g), hand));
}

TEST(NotesExample2_9, PrintedMatrixIsThe321SequenceC1C2C3) {
  const realsymbol a("alpha"), b("beta"), g("gamma");
  const ex ca = cos(a), sa = sin(a), cb = cos(b), sb = sin(b), cg = cos(g), sg = sin(g);
  // the matrix exactly as printed in the notes
  const matrix printed = mat3(cb * ca, cb * sa, -sb,                                       //
                              -cg * sa + sg * sb * ca, cg * ca + sg * sb * sa, sg * cb,   //
                              sg * sa + cg * sb * ca, -sg * ca + cg * sb * sa, cg * cb);
  const matrix c1c2c3 = eomgen::principal_rotation(1, g)
                            .mul(eomgen::principal_rotation(2, b))
                            .mul(eomgen::principal_rotation(3, a));
  EXPECT_TRUE(equal_after_expansion(c1c2c3, printed));
  EXPECT_TRUE(equal_after_expansion(eomgen::euler_rotation(EulerSequence::parse("3-2-1"), a, b, g), printed));

  // ... and it is NOT C1(g) C2(b) C1(a), the product the example asks for
  const matrix c1c2c1 = eomgen::euler_rotation(EulerSequence::parse("1-2-1"), a, b, g);
  const exmap at{{a, 0.3}, {b, -0.7}, {g, 1.1}};
  EXPECT_GT((value_at(c1c2c1, at) - value_at(printed, at)).cwiseAbs().maxCoeff(), 0.1);
}

// ---------------------------------------------------------------------------------------------
// 5. Angular velocity: rate relations against Poisson's equation

/// Compares Rotation::angular_velocity with angular_velocity_from_poisson at one state.
::testing::AssertionResult rate_relation_matches_poisson(const Rotation& r, const Variables& v,
                                                         const exmap& state) {
  const matrix w = r.angular_velocity(v);
  const matrix wp = eomgen::angular_velocity_from_poisson(r.dcm(), v);
  if (w.rows() != 3 || w.cols() != 1) return ::testing::AssertionFailure() << "omega is not 3x1";
  return matrices_near(value_at(w, state), value_at(wp, state), kTol);
}

TEST(AngularVelocity, PrincipalRotationIsAxisTimesRate) {
  Variables v;
  const auto th = v.add_coordinate("theta");
  std::mt19937 rng(31);
  for (int axis = 1; axis <= 3; ++axis) {
    const Rotation r = Rotation::principal(axis, th.q);
    EXPECT_TRUE(equal_after_expansion(r.angular_velocity(v), eomgen::unit_column(axis).mul_scalar(th.qd)));
    for (int k = 0; k < 3; ++k) {
      const exmap at{{th.q, uniform(rng, -3, 3)}, {th.qd, uniform(rng, -3, 3)}};
      EXPECT_TRUE(rate_relation_matches_poisson(r, v, at)) << "axis " << axis;
    }
  }
}

TEST(AngularVelocity, PoissonGivesPositiveRateForC3) {
  // independent sign check: C3(theta) turning at +1 rad/s has omega_b = +1_3
  Variables v;
  const auto th = v.add_coordinate("theta");
  const matrix w = eomgen::angular_velocity_from_poisson(eomgen::principal_rotation(3, th.q), v);
  EXPECT_TRUE(matrices_near(value_at(w, {{th.q, 0.4}, {th.qd, 1.0}}), Eigen::Vector3d(0, 0, 1), kTol));
}

TEST(AngularVelocity, IdentityRotationHasZeroAngularVelocity) {
  Variables v;
  v.add_coordinate("x");
  const matrix w = Rotation::identity().angular_velocity(v);
  EXPECT_TRUE(equal_after_expansion(w, col3(0, 0, 0)));
}

TEST(AngularVelocity, AllTwelveEulerSequencesMatchPoisson) {
  Variables v;
  const auto q1 = v.add_coordinate("t1"), q2 = v.add_coordinate("t2"), q3 = v.add_coordinate("t3");
  std::mt19937 rng(32);
  for (const auto& name : all_sequences()) {
    const Rotation r = Rotation::euler(EulerSequence::parse(name), q1.q, q2.q, q3.q);
    for (int k = 0; k < 3; ++k) {
      exmap at;
      for (const auto& c : {q1, q2, q3}) {
        at[c.q] = uniform(rng, -3, 3);
        at[c.qd] = uniform(rng, -2, 2);
      }
      EXPECT_TRUE(rate_relation_matches_poisson(r, v, at)) << name;
    }
  }
}

TEST(AngularVelocity, NotesEuler123ExampleMatchesHandFormula) {
  Variables v;
  const auto d = v.add_coordinate("d"), e = v.add_coordinate("e"), f = v.add_coordinate("phi");
  const Rotation r = Rotation::euler(EulerSequence::parse("1-2-3"), d.q, e.q, f.q);
  // C_ba = C3(phi) C2(e) C1(d)
  EXPECT_TRUE(equal_after_expansion(r.dcm(), eomgen::principal_rotation(3, f.q)
                                                 .mul(eomgen::principal_rotation(2, e.q))
                                                 .mul(eomgen::principal_rotation(1, d.q))));
  // omega = [C3 C2 1_1, C3 1_2, 1_3] [dd; de; dphi], multiplied out by hand:
  // C2(e) 1_1 = [ce, 0, se], C3(phi) [ce, 0, se] = [cf ce, -sf ce, se], C3(phi) 1_2 = [sf, cf, 0]
  const ex ce = cos(e.q), se = sin(e.q), cf = cos(f.q), sf = sin(f.q);
  const matrix hand = col3(cf * ce * d.qd + sf * e.qd, -sf * ce * d.qd + cf * e.qd, se * d.qd + f.qd);
  EXPECT_TRUE(equal_after_expansion(r.angular_velocity(v), hand));
  std::mt19937 rng(33);
  for (int k = 0; k < 4; ++k) {
    exmap at;
    for (const auto& c : {d, e, f}) {
      at[c.q] = uniform(rng, -3, 3);
      at[c.qd] = uniform(rng, -2, 2);
    }
    EXPECT_TRUE(
        matrices_near(value_at(eomgen::angular_velocity_from_poisson(r.dcm(), v), at), value_at(hand, at), kTol));
  }
}

TEST(AngularVelocity, UnitQuaternionWithTangentRateMatchesPoisson) {
  Variables v;
  const auto e1 = v.add_coordinate("e1"), e2 = v.add_coordinate("e2"), e3 = v.add_coordinate("e3"),
             eta = v.add_coordinate("eta");
  const Rotation r = Rotation::quaternion(col3(e1.q, e2.q, e3.q), eta.q);
  EXPECT_EQ(r.kind(), Rotation::Kind::quaternion);
  std::mt19937 rng(34);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int k = 0; k < 5; ++k) {
    const Eigen::Vector4d q = Eigen::Vector4d(n(rng), n(rng), n(rng), n(rng)).normalized();
    const Eigen::Vector4d raw(n(rng), n(rng), n(rng), n(rng));
    const Eigen::Vector4d qd = raw - raw.dot(q) * q;  // eps.deps + eta deta = 0
    ASSERT_NEAR(q.dot(qd), 0.0, 1e-14);
    const exmap at{{e1.q, q(0)},   {e2.q, q(1)},   {e3.q, q(2)},   {eta.q, q(3)},
                   {e1.qd, qd(0)}, {e2.qd, qd(1)}, {e3.qd, qd(2)}, {eta.qd, qd(3)}};
    EXPECT_TRUE(rate_relation_matches_poisson(r, v, at));
  }
}

TEST(AngularVelocity, QuaternionRateRelationMatchesClosedForm) {
  // omega = 2 (eta 1 - eps^x) deps - 2 eps deta, evaluated independently with Eigen
  Variables v;
  const auto e1 = v.add_coordinate("e1"), e2 = v.add_coordinate("e2"), e3 = v.add_coordinate("e3"),
             eta = v.add_coordinate("eta");
  const matrix w = Rotation::quaternion(col3(e1.q, e2.q, e3.q), eta.q).angular_velocity(v);
  const Eigen::Vector3d eps(0.1, -0.5, 0.3), deps(0.7, 0.2, -0.4);
  const double et = 0.8, det = -0.25;
  const exmap at{{e1.q, eps(0)},   {e2.q, eps(1)},   {e3.q, eps(2)},   {eta.q, et},
                 {e1.qd, deps(0)}, {e2.qd, deps(1)}, {e3.qd, deps(2)}, {eta.qd, det}};
  const Eigen::Vector3d expected = 2 * (et * Eigen::Matrix3d::Identity() - skew(eps)) * deps - 2 * eps * det;
  EXPECT_TRUE(matrices_near(value_at(w, at), expected, kTol));
}

TEST(AngularVelocity, AxisAngleWithUnitAxisAndPerpendicularAxisRateMatchesPoisson) {
  Variables v;
  const auto a1 = v.add_coordinate("a1"), a2 = v.add_coordinate("a2"), a3 = v.add_coordinate("a3"),
             phi = v.add_coordinate("phi");
  const Rotation r = Rotation::axis_angle(col3(a1.q, a2.q, a3.q), phi.q);
  EXPECT_EQ(r.kind(), Rotation::Kind::axis_angle);
  std::mt19937 rng(35);
  for (int k = 0; k < 5; ++k) {
    const Eigen::Vector3d a = random_unit(rng);
    const Eigen::Vector3d raw = random_vec(rng);
    const Eigen::Vector3d da = raw - raw.dot(a) * a;  // a.da = 0
    const exmap at{{a1.q, a(0)},   {a2.q, a(1)},   {a3.q, a(2)},   {phi.q, uniform(rng, -3, 3)},
                   {a1.qd, da(0)}, {a2.qd, da(1)}, {a3.qd, da(2)}, {phi.qd, uniform(rng, -2, 2)}};
    EXPECT_TRUE(rate_relation_matches_poisson(r, v, at));
  }
}

TEST(AngularVelocity, AxisAngleWithFixedAxisIsAxisTimesAngleRate) {
  Variables v;
  const auto phi = v.add_coordinate("phi");
  const matrix a = col3(GiNaC::numeric(2, 3), GiNaC::numeric(-1, 3), GiNaC::numeric(2, 3));  // unit
  const matrix w = Rotation::axis_angle(a, phi.q).angular_velocity(v);
  EXPECT_TRUE(equal_after_expansion(w, a.mul_scalar(phi.qd)));
}

TEST(AngularVelocity, RodriguesRateRelationMatchesPoisson) {
  Variables v;
  const auto p1 = v.add_coordinate("p1"), p2 = v.add_coordinate("p2"), p3 = v.add_coordinate("p3");
  const Rotation r = Rotation::rodrigues(col3(p1.q, p2.q, p3.q));
  EXPECT_EQ(r.kind(), Rotation::Kind::rodrigues);
  std::mt19937 rng(36);
  for (int k = 0; k < 5; ++k) {
    exmap at;
    for (const auto& c : {p1, p2, p3}) {
      at[c.q] = uniform(rng, -2, 2);
      at[c.qd] = uniform(rng, -2, 2);
    }
    EXPECT_TRUE(rate_relation_matches_poisson(r, v, at));
  }
}

TEST(AngularVelocity, InverseRodriguesRateRelationRecoversOmega) {
  // dp/dt = 1/2 (1 + p^x + p p^T) omega  =>  the rate relation and Poisson give back omega
  Variables v;
  const auto p1 = v.add_coordinate("p1"), p2 = v.add_coordinate("p2"), p3 = v.add_coordinate("p3");
  const Rotation r = Rotation::rodrigues(col3(p1.q, p2.q, p3.q));
  const matrix w = r.angular_velocity(v);
  const matrix wp = eomgen::angular_velocity_from_poisson(r.dcm(), v);
  std::mt19937 rng(37);
  for (int k = 0; k < 5; ++k) {
    const Eigen::Vector3d p = random_vec(rng, 2.0), omega = random_vec(rng, 2.0);
    const Eigen::Vector3d dp = 0.5 * (Eigen::Matrix3d::Identity() + skew(p) + p * p.transpose()) * omega;
    const exmap at{{p1.q, p(0)}, {p2.q, p(1)}, {p3.q, p(2)}, {p1.qd, dp(0)}, {p2.qd, dp(1)}, {p3.qd, dp(2)}};
    EXPECT_TRUE(matrices_near(value_at(w, at), omega, kTol));
    EXPECT_TRUE(matrices_near(value_at(wp, at), omega, kTol));
  }
}

TEST(AngularVelocity, ModifiedRodriguesRateRelationMatchesPoisson) {
  Variables v;
  const auto s1 = v.add_coordinate("s1"), s2 = v.add_coordinate("s2"), s3 = v.add_coordinate("s3");
  const Rotation r = Rotation::modified_rodrigues(col3(s1.q, s2.q, s3.q));
  EXPECT_EQ(r.kind(), Rotation::Kind::modified_rodrigues);
  std::mt19937 rng(38);
  for (int k = 0; k < 5; ++k) {
    exmap at;
    for (const auto& c : {s1, s2, s3}) {
      at[c.q] = uniform(rng, -1.5, 1.5);
      at[c.qd] = uniform(rng, -2, 2);
    }
    EXPECT_TRUE(rate_relation_matches_poisson(r, v, at));
  }
}

TEST(AngularVelocity, ExplicitMatrixUsesPoissonAndMatchesEulerRates) {
  Variables v;
  const auto q1 = v.add_coordinate("t1"), q2 = v.add_coordinate("t2"), q3 = v.add_coordinate("t3");
  const Rotation euler = Rotation::euler(EulerSequence::parse("3-1-3"), q1.q, q2.q, q3.q);
  const Rotation explicit_r = Rotation::explicit_matrix(euler.dcm());
  const matrix w_explicit = explicit_r.angular_velocity(v);
  const matrix w_euler = euler.angular_velocity(v);
  std::mt19937 rng(39);
  for (int k = 0; k < 4; ++k) {
    exmap at;
    for (const auto& c : {q1, q2, q3}) {
      at[c.q] = uniform(rng, -3, 3);
      at[c.qd] = uniform(rng, -2, 2);
    }
    EXPECT_TRUE(matrices_near(value_at(w_explicit, at), value_at(w_euler, at), kTol));
  }
}

TEST(AngularVelocity, CompoundedRotationsAddAngularVelocities) {
  // C_ca = C_cb C_ba  =>  omega_c^ca = omega_c^cb + C_cb omega_b^ba
  Variables v;
  const auto x = v.add_coordinate("x"), y = v.add_coordinate("y");
  const matrix Cba = eomgen::principal_rotation(3, x.q), Ccb = eomgen::principal_rotation(2, y.q);
  const matrix w = Rotation::explicit_matrix(Ccb.mul(Cba)).angular_velocity(v);
  const matrix expected = eomgen::unit_column(2).mul_scalar(y.qd).add(
      Ccb.mul(eomgen::unit_column(3).mul_scalar(x.qd)));
  std::mt19937 rng(40);
  for (int k = 0; k < 4; ++k) {
    const exmap at{{x.q, uniform(rng, -3, 3)}, {y.q, uniform(rng, -3, 3)}, {x.qd, uniform(rng, -2, 2)},
                   {y.qd, uniform(rng, -2, 2)}};
    EXPECT_TRUE(matrices_near(value_at(w, at), value_at(expected, at), kTol));
  }
}

// ---------------------------------------------------------------------------------------------
// 6. Cross operator and Euler sequence parsing

TEST(CrossMatrix, TimesVectorIsTheCrossProduct) {
  const realsymbol u1("u1"), u2("u2"), u3("u3"), v1("v1"), v2("v2"), v3("v3");
  const matrix u = col3(u1, u2, u3), v = col3(v1, v2, v3);
  const matrix uxv = col3(u2 * v3 - u3 * v2, u3 * v1 - u1 * v3, u1 * v2 - u2 * v1);
  EXPECT_TRUE(equal_after_expansion(eomgen::cross_matrix(u).mul(v), uxv));
  EXPECT_TRUE(equal_after_expansion(eomgen::cross_matrix(u), mat3(0, -u3, u2, u3, 0, -u1, -u2, u1, 0)));
}

TEST(CrossMatrix, UncrossInvertsCrossMatrix) {
  const realsymbol u1("u1"), u2("u2"), u3("u3");
  const matrix u = col3(u1, u2, u3);
  EXPECT_TRUE(equal_after_expansion(eomgen::uncross(eomgen::cross_matrix(u)), u));
}

TEST(CrossMatrix, UncrossIgnoresTheSymmetricPart) {
  const realsymbol u1("u1"), u2("u2"), u3("u3"), k("k");
  const matrix u = col3(u1, u2, u3);
  const matrix symmetric = mat3(k, 1, 2, 1, 3, k * k, 2, k * k, 5);
  EXPECT_TRUE(equal_after_expansion(eomgen::uncross(eomgen::cross_matrix(u).add(symmetric)), u));
}

TEST(EulerSequenceParse, AcceptsAllTwelveSequencesInEveryNotation) {
  for (const auto& name : all_sequences()) {
    const std::array<int, 3> expected{name[0] - '0', name[2] - '0', name[4] - '0'};
    const std::string compact{name[0], name[2], name[4]};
    const std::string underscored{name[0], '_', name[2], '_', name[4]};
    for (const auto& text : {name, compact, underscored}) {
      EulerSequence seq{};
      ASSERT_NO_THROW(seq = EulerSequence::parse(text)) << text;
      EXPECT_EQ(seq.axes, expected) << text;
      EXPECT_EQ(seq.name(), name) << text;
    }
  }
}

TEST(EulerSequenceParse, AcceptsExactlyTwelveOfTheTwentySevenAxisTriples) {
  int accepted = 0;
  for (int i = 1; i <= 3; ++i)
    for (int j = 1; j <= 3; ++j)
      for (int k = 1; k <= 3; ++k) {
        const std::string text = std::to_string(i) + "-" + std::to_string(j) + "-" + std::to_string(k);
        const bool valid = i != j && j != k;
        if (valid) {
          EXPECT_NO_THROW(EulerSequence::parse(text)) << text;
          ++accepted;
        } else {
          EXPECT_THROW_MESSAGE(EulerSequence::parse(text), eomgen::ModelError, euler_sequence_error(text)) << text;
        }
      }
  EXPECT_EQ(accepted, 12);
}

TEST(EulerSequenceParse, RejectsInvalidSequencesWithModelErrorNamingThem) {
  for (const std::string text : {"3-3-1", "1-2-2", "4-1-2", "12", "", "0-1-2", "1-2-3-1", "x-y-z",
                                 "3 2 1", "331", "1-1-1", "-3-1-3-", "3--1--3", "3-1_3"}) {
    EXPECT_THROW_MESSAGE(EulerSequence::parse(text), eomgen::ModelError, euler_sequence_error(text)) << text;
  }
}

}  // namespace
