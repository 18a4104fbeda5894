// Validation when building a MechanicalSystem: every bad input is a ModelError that names it.
#include "eomgen/mechanics/mechanical_system.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "eomgen/base/error.hpp"
#include "eomgen/symbolic/simplify.hpp"
#include "support/expect_throw.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;
using GiNaC::matrix;

matrix diag(const ex& a, const ex& b, const ex& c) { return matrix(3, 3, GiNaC::lst{a, 0, 0, 0, b, 0, 0, 0, c}); }

struct Fixture {
  MechanicalSystem s{"a", "w"};
  Coordinate q = s.add_coordinate("q");
  ex m = s.add_parameter("m", 1.0);
  FrameId b = s.add_frame("b", s.inertial_frame(), Rotation::principal(3, q.q));
  PointId p = s.add_point("p", s.origin(), Vector(b, 1, 0, 0));
};

TEST(MechanicalSystem, InertialFrameAndOriginExist) {
  Fixture f;
  EXPECT_EQ(f.s.frame(f.s.inertial_frame()).name, "a");
  EXPECT_EQ(f.s.point(f.s.origin()).name, "w");
  EXPECT_EQ(f.s.find_frame("b")->index, f.b.index);
  EXPECT_EQ(f.s.find_point("p")->index, f.p.index);
  EXPECT_FALSE(f.s.find_frame("nope").has_value());
  EXPECT_EQ(f.s.frame(f.b).depth, 1u);
}

TEST(MechanicalSystem, DuplicateNamesAreRejected) {
  Fixture f;
  EXPECT_THROW_MESSAGE(f.s.add_frame("b", f.s.inertial_frame(), Rotation::identity()), ModelError,
                       "frame 'b': the name is already used");
  EXPECT_THROW_MESSAGE(f.s.add_point("b", f.s.origin(), Vector()), ModelError, "point 'b': the name is already used");
}

TEST(MechanicalSystem, ForeignSymbolInRotationIsRejected) {
  Fixture f;
  GiNaC::realsymbol stranger("stranger");
  EXPECT_THROW_MESSAGE(f.s.add_frame("c", f.b, Rotation::principal(1, stranger)), ModelError,
                       "frame 'c': 'stranger' is not a time, coordinate, rate, parameter or input of this model");
}

TEST(MechanicalSystem, RotationDependingOnRateIsRejected) {
  Fixture f;
  EXPECT_THROW_MESSAGE(
      f.s.add_frame("c", f.b, Rotation::principal(1, f.q.qd)), ModelError,
      "frame 'c': a rotation may depend on coordinates, parameters and t only, not on rates, accelerations or inputs");
}

TEST(MechanicalSystem, NonPositiveMassIsRejected) {
  Fixture f;
  EXPECT_THROW_MESSAGE(f.s.add_particle("bad", -f.m, f.p), ModelError,
                       "particle 'bad': the mass must be positive, got -1");
  EXPECT_THROW_MESSAGE(f.s.add_particle("bad", f.q.q, f.p), ModelError,
                       "particle 'bad': the mass must be a constant (parameters and numbers)");
}

TEST(MechanicalSystem, InertiaMustBeSymmetricWithNonNegativePrincipalMomentsThatFormATriangle) {
  Fixture f;
  matrix J = diag(1, 1, 1);
  J(0, 1) = 0.1;
  EXPECT_THROW_MESSAGE(f.s.add_rigid_body("body", f.m, f.p, f.b, J), ModelError,
                       "rigid body 'body': the inertia matrix must be symmetric, but entry (1,2) differs from (2,1)");
  EXPECT_THROW_MESSAGE(f.s.add_rigid_body("body", f.m, f.p, f.b, diag(1, -1, 1)), ModelError,
                       "rigid body 'body': the inertia matrix has the principal moments -1, 1, 1 at the default "
                       "parameters; a negative one belongs to no body: expected a positive semidefinite matrix");
  // positive diagonal but indefinite: the eigenvalues of [[1, 2], [2, 1]] are -1 and 3
  matrix K = diag(1, 1, 1);
  K(0, 1) = K(1, 0) = 2;
  EXPECT_THROW_MESSAGE(f.s.add_rigid_body("body", f.m, f.p, f.b, K), ModelError,
                       "rigid body 'body': the inertia matrix has the principal moments -1, 1, 3 at the default "
                       "parameters; a negative one belongs to no body: expected a positive semidefinite matrix");
  // positive definite, but Izz = Ixx + Iyy + 1 needs a negative sum of squares
  EXPECT_THROW_MESSAGE(f.s.add_rigid_body("body", f.m, f.p, f.b, diag(1, 2, 4)), ModelError,
                       "rigid body 'body': the inertia matrix has the principal moments 1, 2, 4 at the default "
                       "parameters, and 4 exceeds the sum of the other two, which no mass distribution gives: "
                       "expected each principal moment at most the sum of the other two");
  // the same in a rotated frame: the principal moments are what is checked, not the diagonal
  const matrix R{{GiNaC::numeric(3, 5), GiNaC::numeric(-4, 5), 0}, {GiNaC::numeric(4, 5), GiNaC::numeric(3, 5), 0}, {0, 0, 1}};
  const matrix rotated = R.mul(diag(4, 1, 2)).mul(R.transpose());
  EXPECT_THROW(f.s.add_rigid_body("body", f.m, f.p, f.b, rotated), ModelError);
  EXPECT_THROW_MESSAGE(f.s.add_rigid_body("body", f.m, f.p, f.b, matrix(2, 2)), ModelError,
                       "rigid body 'body': expected a 3x3 inertia matrix, got 2x2");
}

TEST(MechanicalSystem, SlenderRodAndThinDiskInertiasOnTheBoundaryAreAccepted) {
  Fixture f;
  // a rod along its x axis: no moment about the axis, m l^2 / 12 about the other two
  f.s.add_rigid_body("rod", f.m, f.p, f.b, diag(0, f.m / 12, f.m / 12));
  // a thin disk in its xy plane: J3 = J1 + J2 exactly
  f.s.add_rigid_body("disk", f.m, f.p, f.b, diag(f.m / 4, f.m / 4, f.m / 2));
  // a point mass treated as a body, and a rod whose axis is no basis vector
  f.s.add_rigid_body("point", f.m, f.p, f.b, matrix(3, 3));
  const matrix R{{GiNaC::numeric(3, 5), GiNaC::numeric(-4, 5), 0}, {GiNaC::numeric(4, 5), GiNaC::numeric(3, 5), 0}, {0, 0, 1}};
  f.s.add_rigid_body("tilted_rod", f.m, f.p, f.b, R.mul(diag(0, 1, 1)).mul(R.transpose()));
  EXPECT_EQ(f.s.rigid_bodies().size(), 4u);
}

TEST(MechanicalSystem, NonholonomicConstraintMustBeLinearInRates) {
  Fixture f;
  EXPECT_THROW_MESSAGE(
      f.s.add_nonholonomic_constraint("c", f.q.qd * f.q.qd), ModelError,
      "nonholonomic constraint 'c': the constraint must be linear in the rates, but it is not linear in 'q_dot'");
  EXPECT_THROW_MESSAGE(f.s.add_nonholonomic_constraint("c", f.q.q), ModelError,
                       "nonholonomic constraint 'c': the constraint contains no rate with a non-zero coefficient");
}

TEST(MechanicalSystem, NonholonomicConstraintWhoseSquaredRateCancelsIsLinear) {
  // the coefficient of q_dot^2 is q/(q+1) + 1/(q+1) - 1, zero only once normalized: the rate
  // left in q_dot's coefficient is tested exactly, not refused for its looks
  Fixture f;
  const GiNaC::ex vanishing = f.q.q / (f.q.q + 1) + 1 / (f.q.q + 1) - 1;
  f.s.add_nonholonomic_constraint("c", f.q.qd + f.q.qd * f.q.qd * vanishing);
  EXPECT_EQ(f.s.constraints().size(), 1u);
  // and a squared rate whose coefficient does not vanish is refused as before
  EXPECT_THROW_MESSAGE(
      f.s.add_nonholonomic_constraint("d", f.q.qd + f.q.qd * f.q.qd * (vanishing + f.q.q)), ModelError,
      "nonholonomic constraint 'd': the constraint must be linear in the rates, but it is not linear in 'q_dot'");
}

TEST(MechanicalSystem, HolonomicConstraintMustDependOnCoordinatesOnly) {
  Fixture f;
  EXPECT_THROW_MESSAGE(f.s.add_holonomic_constraint("c", f.q.qd), ModelError,
                       "holonomic constraint 'c': phi(q, t) may not contain rates, accelerations or inputs; write a "
                       "rate constraint as a nonholonomic constraint");
  EXPECT_THROW_MESSAGE(
      f.s.add_holonomic_constraint("c", f.s.variables().time()), ModelError,
      "holonomic constraint 'c': the constraint does not depend on any coordinate (its Jacobian is identically zero)");
  // identically zero once simplified
  EXPECT_THROW_MESSAGE(
      f.s.add_holonomic_constraint("c", GiNaC::pow(GiNaC::sin(f.q.q), 2) + GiNaC::pow(GiNaC::cos(f.q.q), 2) - 1),
      ModelError,
      "holonomic constraint 'c': the constraint does not depend on any coordinate (its Jacobian is identically zero)");
}

TEST(MechanicalSystem, RemovedConstraintsLeaveTheOthersInOrderAndTheirNamesTaken) {
  Fixture f;
  for (const char* name : {"c0", "c1", "c2", "c3", "c4"}) f.s.add_holonomic_constraint(name, f.q.q);
  f.s.remove_constraints({3, 1});
  std::vector<std::string> names;
  for (const Constraint& c : f.s.constraints()) names.push_back(c.name);
  EXPECT_EQ(names, (std::vector<std::string>{"c0", "c2", "c4"}));
  // a note on the model still names a removed constraint
  EXPECT_THROW_MESSAGE(f.s.add_holonomic_constraint("c1", f.q.q), ModelError,
                       "constraint 'c1': the name is already used");
  EXPECT_THROW_MESSAGE(f.s.remove_constraints({3}), ModelError,
                       "remove_constraints: no constraint 3 (the system has 3)");
  EXPECT_THROW_MESSAGE(f.s.remove_constraints({0, 0}), ModelError,
                       "remove_constraints: constraint 0 ('c0') is given twice");
  EXPECT_EQ(f.s.constraints().size(), 3u);
}

TEST(MechanicalSystem, SpringNeedsTwoDistinctPoints) {
  Fixture f;
  EXPECT_THROW_MESSAGE(f.s.add_spring("k", f.p, f.p, 1, 0), ModelError, "spring 'k': the two points must differ");
}

TEST(MechanicalSystem, GeneralizedForceOnMissingCoordinateIsRejected) {
  Fixture f;
  EXPECT_THROW_MESSAGE(f.s.add_generalized_force(3, 1), ModelError,
                       "generalized force: coordinate #3 does not exist (the model has 1)");
}

// the derivations add terms, and name shared subexpressions, in the order of loads()
TEST(MechanicalSystem, LoadsAreGroupedByTypeInTheOrderTheyWereAdded) {
  Fixture f;
  const PointId p2 = f.s.add_point("p2", f.s.origin(), Vector(f.b, 0, 1, 0));
  f.s.add_potential("magnet", f.q.q * f.q.q);
  f.s.add_spring("k1", f.p, p2, 1, 0);
  f.s.add_force(f.p, Vector(f.b, 1, 0, 0));
  f.s.add_spring("k2", f.p, p2, 2, 0);
  f.s.add_damper("c1", f.p, p2, 1);
  f.s.add_force(p2, Vector(f.b, 0, 1, 0));
  std::vector<std::string> visited;
  for (const Load& load : f.s.loads())
    visit_load(
        load, [&](const PointForce& force) { visited.push_back(force.point == f.p ? "force at p" : "force at p2"); },
        [&](const BodyMoment&) { visited.push_back("moment"); },
        [&](const LinearDamper& d) { visited.push_back("damper " + d.name); },
        [&](const CoordinateDamper& d) { visited.push_back("damper " + d.name); },
        [&](const GeneralizedForce&) { visited.push_back("generalized force"); },
        [&](const LinearSpring& k) { visited.push_back("spring " + k.name); },
        [&](const TorsionalSpring& k) { visited.push_back("torsion " + k.name); },
        [&](const Potential& v) { visited.push_back("potential " + v.name); });
  EXPECT_EQ(visited, (std::vector<std::string>{"force at p", "force at p2", "damper c1", "spring k1", "spring k2",
                                               "potential magnet"}));
}

TEST(ParallelAxis, UniformRodAboutItsEndIsOneThirdMlSquared) {
  const GiNaC::realsymbol m("m"), l("l");
  const matrix Jc = diag(0, m * l * l / 12, m * l * l / 12);
  const matrix Jo = parallel_axis(Jc, m, matrix(3, 1, GiNaC::lst{l / 2, 0, 0}));
  EXPECT_TRUE((Jo(1, 1) - m * l * l / 3).expand().is_zero());
  EXPECT_TRUE((Jo(2, 2) - m * l * l / 3).expand().is_zero());
  EXPECT_TRUE(Jo(0, 0).expand().is_zero());
  EXPECT_TRUE(Jo(0, 1).expand().is_zero());
}

TEST(ParallelAxis, OffDiagonalProductsOfInertia) {
  // J_o = J_c + m (r^T r 1 - r r^T): off-diagonal -m x y
  const GiNaC::realsymbol m("m"), x("x"), y("y"), z("z");
  const matrix Jo = parallel_axis(matrix(3, 3), m, matrix(3, 1, GiNaC::lst{x, y, z}));
  EXPECT_TRUE((Jo(0, 1) + m * x * y).expand().is_zero());
  EXPECT_TRUE((Jo(0, 0) - m * (y * y + z * z)).expand().is_zero());
}

}  // namespace
}  // namespace eomgen
