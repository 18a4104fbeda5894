// Kinematics on the frame and point trees: the notes' Example 3.1 (spacecraft bus with a
// rotating solar panel), the rolling coin of section 3.7.0.2, and consistency of DCMs,
// angular velocities and the transport theorem between arbitrary frames.
#include "eomgen/mechanics/kinematics.hpp"

#include <gtest/gtest.h>

#include "eomgen/base/error.hpp"
#include "eomgen/symbolic/simplify.hpp"
#include "support/expect_throw.hpp"
#include "support/symbolic_checks.hpp"

namespace eomgen {
namespace {

using GiNaC::cos;
using GiNaC::ex;
using GiNaC::matrix;
using GiNaC::sin;
using testing::simplifies_to_zero;

matrix col(const ex& x, const ex& y, const ex& z) { return matrix(3, 1, GiNaC::lst{x, y, z}); }

struct SpacecraftWithPanel {
  // Example 3.1: C_ba = C3(gamma), C_pb = C2(theta); r^{hw} constant, r^{fh} = l_fh b2,
  // r^{ef} = l_ef p3.
  MechanicalSystem s{"a", "w"};
  Coordinate gamma = s.add_coordinate("gamma");
  Coordinate theta = s.add_coordinate("theta");
  ex l_fh = s.add_parameter("l_fh", 2.0), l_ef = s.add_parameter("l_ef", 3.0);
  ex h1 = s.add_parameter("h1", 0.1), h2 = s.add_parameter("h2", 0.2), h3 = s.add_parameter("h3", 0.3);
  FrameId b = s.add_frame("b", s.inertial_frame(), Rotation::principal(3, gamma.q));
  FrameId p = s.add_frame("p", b, Rotation::principal(2, theta.q));
  PointId h = s.add_point("h", s.origin(), Vector(s.inertial_frame(), h1, h2, h3));
  PointId f = s.add_point("f", h, Vector(b, 0, l_fh, 0));
  PointId e = s.add_point("e", f, Vector(p, 0, 0, l_ef));
};

TEST(Example3_1, AngularVelocityOfPanelResolvedInPanelFrame) {
  SpacecraftWithPanel m;
  const matrix w = resolve(m.s, angular_velocity(m.s, m.p, m.s.inertial_frame()), m.p);
  const ex st = sin(m.theta.q), ct = cos(m.theta.q);
  EXPECT_TRUE(simplifies_to_zero(w.sub(col(-st * m.gamma.qd, m.theta.qd, ct * m.gamma.qd))));
}

TEST(Example3_1, VelocityOfPanelTipMatchesNotes) {
  SpacecraftWithPanel m;
  const matrix v = resolve(m.s, velocity(m.s, m.e), m.p);
  const ex st = sin(m.theta.q), ct = cos(m.theta.q);
  const ex gd = m.gamma.qd, td = m.theta.qd;
  EXPECT_TRUE(simplifies_to_zero(v.sub(col(td * m.l_ef - ct * gd * m.l_fh, st * gd * m.l_ef, -st * gd * m.l_fh))));
}

TEST(Example3_1, AccelerationOfPanelTipMatchesNotesPlusBusAngularAcceleration) {
  SpacecraftWithPanel m;
  const matrix acc = resolve(m.s, acceleration(m.s, m.e), m.p);
  const ex st = sin(m.theta.q), ct = cos(m.theta.q);
  const ex gd = m.gamma.qd, td = m.theta.qd, gdd = m.gamma.qdd, tdd = m.theta.qdd;
  // the notes' result (which takes the bus rate as constant) ...
  const matrix notes = col(m.l_ef * (tdd - ct * st * gd * gd), 2 * td * gd * ct * m.l_ef - gd * gd * m.l_fh,
                           -m.l_ef * (td * td + st * st * gd * gd));
  // ... plus alpha x r^{eh} for a bus angular acceleration gamma_ddot b3
  const matrix bus = col(-ct * gdd * m.l_fh, st * gdd * m.l_ef, -st * gdd * m.l_fh);
  EXPECT_TRUE(simplifies_to_zero(acc.sub(notes).sub(bus)));
}

TEST(Example3_1, ConstantOffsetFromOriginDoesNotContributeToVelocity) {
  SpacecraftWithPanel m;
  const matrix v_h = resolve(m.s, velocity(m.s, m.h), m.s.inertial_frame());
  EXPECT_TRUE(simplifies_to_zero(v_h));
}

struct RollingCoin {
  // section 3.7.0.2: C_pa = C1(phi) C2(theta) C3(psi) through frames q and s
  MechanicalSystem s{"a", "w"};
  Coordinate x = s.add_coordinate("x"), y = s.add_coordinate("y"), zc = s.add_coordinate("zc");
  Coordinate psi = s.add_coordinate("psi"), theta = s.add_coordinate("theta"), phi = s.add_coordinate("phi");
  ex r = s.add_parameter("r", 0.3);
  FrameId q = s.add_frame("q", s.inertial_frame(), Rotation::principal(3, psi.q));
  FrameId sf = s.add_frame("s", q, Rotation::principal(2, theta.q));
  FrameId p = s.add_frame("p", sf, Rotation::principal(1, phi.q));
  PointId z = s.add_point("z", s.origin(), Vector(s.inertial_frame(), x.q, y.q, zc.q));
  PointId u = s.add_point("u", z, Vector(sf, 0, 0, -r));  // contact point, below the centre
};

TEST(RollingCoin, AngularVelocityInCoinAndIntermediateFrames) {
  RollingCoin c;
  const Vector w = angular_velocity(c.s, c.p, c.s.inertial_frame());
  const ex sth = sin(c.theta.q), cth = cos(c.theta.q), sph = sin(c.phi.q), cph = cos(c.phi.q);
  const matrix rates = col(c.psi.qd, c.theta.qd, c.phi.qd);
  const matrix S(3, 3, GiNaC::lst{-sth, 0, 1, sph * cth, cph, 0, cph * cth, -sph, 0});
  EXPECT_TRUE(simplifies_to_zero(resolve(c.s, w, c.p).sub(S.mul(rates))));
  EXPECT_TRUE(
      simplifies_to_zero(resolve(c.s, w, c.sf).sub(col(c.phi.qd - sth * c.psi.qd, c.theta.qd, cth * c.psi.qd))));
}

TEST(RollingCoin, NoSlipGivesCentreVelocityOfTheNotes) {
  RollingCoin c;
  // the material point at the contact has zero velocity: v_z + omega x r^{uz} = 0,
  // hence r_dot^{zw} = r^{uz} x omega^{pa}
  const Vector w = angular_velocity(c.s, c.p, c.s.inertial_frame());
  const matrix centre_rate = resolve(c.s, cross(c.s, position(c.s, c.u, c.z), w), c.s.inertial_frame());
  const ex sth = sin(c.theta.q), cth = cos(c.theta.q), sps = sin(c.psi.q), cps = cos(c.psi.q);
  const ex r = c.r, td = c.theta.qd, fd = c.phi.qd, pd = c.psi.qd;
  EXPECT_TRUE(
      simplifies_to_zero(centre_rate.sub(col(cth * cps * r * td + sps * r * fd - sps * sth * r * pd,
                                             cth * sps * r * td - cps * r * fd + cps * sth * r * pd, -sth * r * td))));
  // and the velocity of the centre computed by the library is (x_dot, y_dot, zc_dot)
  EXPECT_TRUE(
      simplifies_to_zero(resolve(c.s, velocity(c.s, c.z), c.s.inertial_frame()).sub(col(c.x.qd, c.y.qd, c.zc.qd))));
}

struct ThreeDimensionalTree {
  MechanicalSystem s{"a", "w"};
  Coordinate q1 = s.add_coordinate("q1"), q2 = s.add_coordinate("q2"), q3 = s.add_coordinate("q3");
  Coordinate q4 = s.add_coordinate("q4");
  ex L = s.add_parameter("L", 1.3);
  FrameId b = s.add_frame("b", s.inertial_frame(), Rotation::euler(EulerSequence::parse("3-1-3"), q1.q, q2.q, q3.q));
  FrameId c = s.add_frame("c", b, Rotation::principal(2, q4.q));
  FrameId d = s.add_frame("d", s.inertial_frame(), Rotation::principal(1, q4.q * q1.q + s.variables().time()));
  PointId p = s.add_point("p", s.origin(), Vector(b, L, q4.q, 0));
  PointId e = s.add_point("e", p, Vector(c, 0, 0, L));
};

TEST(Kinematics, DcmCompoundsAlongTheTreeAndInverts) {
  ThreeDimensionalTree t;
  const matrix C_ca = dcm(t.s, t.c, t.s.inertial_frame());
  const matrix expected = principal_rotation(2, t.q4.q).mul(t.s.frame(t.b).rotation.dcm());
  EXPECT_TRUE(simplifies_to_zero(C_ca.sub(expected)));
  // C_cd = C_ca C_ad across two branches, and C_dc = C_cd^T
  const matrix C_cd = dcm(t.s, t.c, t.d);
  EXPECT_TRUE(simplifies_to_zero(C_cd.sub(C_ca.mul(dcm(t.s, t.s.inertial_frame(), t.d)))));
  EXPECT_TRUE(simplifies_to_zero(dcm(t.s, t.d, t.c).sub(C_cd.transpose())));
}

TEST(Kinematics, AngularVelocityBetweenBranchesSatisfiesPoisson) {
  ThreeDimensionalTree t;
  const matrix C_cd = dcm(t.s, t.c, t.d);
  const matrix from_poisson = angular_velocity_from_poisson(C_cd, t.s.variables());
  const matrix from_tree = resolve(t.s, angular_velocity(t.s, t.c, t.d), t.c);
  Subexpressions none;
  for (unsigned seed = 1; seed <= 4; ++seed)
    EXPECT_TRUE(testing::matrices_agree_at(from_tree, none, from_poisson, testing::random_state(t.s, seed), 1e-12));
  // omega^{dc} = -omega^{cd}
  const matrix reverse = resolve(t.s, angular_velocity(t.s, t.d, t.c), t.c);
  EXPECT_TRUE(simplifies_to_zero(reverse.add(from_tree)));
}

TEST(Kinematics, TransportTheoremAgreesWithDifferentiatingInertialComponents) {
  ThreeDimensionalTree t;
  const FrameId a = t.s.inertial_frame();
  const matrix r_a = resolve(t.s, position(t.s, t.e, t.s.origin()), a);
  matrix expected(3, 1);
  for (unsigned i = 0; i < 3; ++i) expected(i, 0) = t.s.variables().time_derivative(r_a(i, 0));
  EXPECT_TRUE(simplifies_to_zero(resolve(t.s, velocity(t.s, t.e), a).sub(expected)));
  // seen from the rotating frame d, through time_derivative with respect to d
  const Vector r = position(t.s, t.e, t.s.origin());
  const matrix r_d = resolve(t.s, r, t.d);
  matrix expected_d(3, 1);
  for (unsigned i = 0; i < 3; ++i) expected_d(i, 0) = t.s.variables().time_derivative(r_d(i, 0));
  Subexpressions none;
  EXPECT_TRUE(testing::matrices_agree_at(resolve(t.s, time_derivative(t.s, r, t.d), t.d), none, expected_d,
                                         testing::random_state(t.s, 7), 1e-12));
}

TEST(Kinematics, PartialDerivativeInCoordinateEqualsPartialVelocity) {
  ThreeDimensionalTree t;
  const FrameId a = t.s.inertial_frame();
  const Vector r = position(t.s, t.e, t.s.origin());
  const Vector v = velocity(t.s, t.e);
  for (const auto& c : t.s.variables().coordinates()) {
    const matrix dr_dq = resolve(t.s, partial_derivative(t.s, r, GiNaC::ex_to<GiNaC::symbol>(ex(c.q)), a), a);
    const matrix dv_dqd = resolve(t.s, partial_derivative(t.s, v, GiNaC::ex_to<GiNaC::symbol>(ex(c.qd)), a), a);
    EXPECT_TRUE(simplifies_to_zero(dr_dq.sub(dv_dqd)));
  }
}

TEST(Kinematics, DotAndCrossAreFrameIndependent) {
  ThreeDimensionalTree t;
  const Vector u(t.b, 1, t.q4.q, 2);
  const Vector w(t.d, t.q1.q, 0, -1);
  const matrix ua = resolve(t.s, u, t.s.inertial_frame()), wa = resolve(t.s, w, t.s.inertial_frame());
  const ex dot_a = ua(0, 0) * wa(0, 0) + ua(1, 0) * wa(1, 0) + ua(2, 0) * wa(2, 0);
  EXPECT_TRUE(simplify_for_display(dot(t.s, u, w) - dot_a).is_zero());
  EXPECT_TRUE(simplifies_to_zero(resolve(t.s, cross(t.s, u, w), t.s.inertial_frame()).sub(cross_matrix(ua).mul(wa))));
}

TEST(Kinematics, PartialDerivativeRejectsNonCoordinates) {
  ThreeDimensionalTree t;
  const Vector r = position(t.s, t.e, t.s.origin());
  EXPECT_THROW_MESSAGE(partial_derivative(t.s, r, GiNaC::ex_to<GiNaC::symbol>(t.L), t.s.inertial_frame()),
                       DerivationError,
                       "partial derivative of a vector: 'L' is not a coordinate or a rate of the model");
}

}  // namespace
}  // namespace eomgen
