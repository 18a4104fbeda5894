#include "eomgen/derivation/articulated_body.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <string>

#include "eomgen/derivation/equations_of_motion.hpp"
#include "eomgen/language/model_file.hpp"
#include "support/numeric_checks.hpp"
#include "support/source_dir.hpp"
#include "support/test_models.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;

Model shipped(const std::string& name, std::map<std::string, double> defines = {}) {
  return load_model(testing::shipped_model_path(name), defines);
}

double number(const ex& e, const GiNaC::exmap& values) {
  return GiNaC::ex_to<GiNaC::numeric>(e.subs(values, GiNaC::subs_options::no_pattern).evalf()).to_double();
}

// parameters at their defaults, everything else random
GiNaC::exmap random_state(const MechanicalSystem& s, std::mt19937& rng) {
  std::uniform_real_distribution<double> uniform(-1.5, 1.5);
  GiNaC::exmap values = s.parameter_defaults();
  for (const Coordinate& c : s.variables().coordinates()) {
    values[c.q] = uniform(rng);
    values[c.qd] = uniform(rng);
  }
  for (const Input& u : s.variables().inputs()) values[u.symbol] = uniform(rng);
  values[s.variables().time()] = uniform(rng);
  return values;
}

// qdd = M^-1 F from Kane's equations
Eigen::VectorXd reference(const EquationsOfMotion& eom, const GiNaC::exmap& state) {
  const GiNaC::exmap all = eom.subexpressions.evaluate_all(state);
  const Eigen::Index n = static_cast<Eigen::Index>(eom.coordinate_count);
  Eigen::MatrixXd M(n, n);
  Eigen::VectorXd F(n);
  for (unsigned i = 0; i < n; ++i) {
    for (unsigned j = 0; j < n; ++j) M(i, j) = number(eom.mass_matrix(i, j), all);
    F(i) = number(eom.forcing(i, 0), all);
  }
  return M.llt().solve(F);
}

Eigen::VectorXd articulated(const ForwardDynamics& fd, const GiNaC::exmap& state) {
  const GiNaC::exmap all = fd.subexpressions.evaluate_all(state);
  Eigen::VectorXd qdd(fd.accelerations.rows());
  for (unsigned i = 0; i < fd.accelerations.rows(); ++i) qdd(i) = number(fd.accelerations(i, 0), all);
  for (const ex& d : fd.pivots) EXPECT_GT(number(d, all), 0.0) << "a pivot of a regular mass matrix";
  return qdd;
}

void expect_kane_accelerations(const MechanicalSystem& s, int states = 3) {
  auto derived = derive_forward_dynamics(s);
  const auto* reason = std::get_if<std::string>(&derived);
  ASSERT_EQ(reason, nullptr) << *reason;
  const ForwardDynamics& fd = std::get<ForwardDynamics>(derived);
  const EquationsOfMotion eom = derive_equations(s);
  std::mt19937 rng(14);
  for (int k = 0; k < states; ++k) {
    const GiNaC::exmap state = random_state(s, rng);
    EXPECT_TRUE(testing::matrices_near_relative(articulated(fd, state), reference(eom, state), 1e-12));
  }
}

std::string rejection(const MechanicalSystem& s) {
  auto derived = derive_forward_dynamics(s);
  const auto* reason = std::get_if<std::string>(&derived);
  return reason ? *reason : "(a forward dynamics)";
}

TEST(ArticulatedBody, PlanarChainsMatchKane) {
  for (double n : {1, 2, 5}) {
    SCOPED_TRACE(n);
    expect_kane_accelerations(shipped("planar_chain", {{"n", n}}).system);
  }
}

TEST(ArticulatedBody, UniversalChainsMatchKane) {
  for (double n : {1, 3}) {
    SCOPED_TRACE(n);
    expect_kane_accelerations(shipped("universal_chain", {{"n", n}}).system);
  }
}

TEST(ArticulatedBody, ParticlesOnMasslessRodsMatchKane) {
  expect_kane_accelerations(shipped("double_pendulum").system);
  expect_kane_accelerations(testing::double_pendulum_model().system);
}

TEST(ArticulatedBody, PrismaticJointWithInputForceMatchesKane) {
  expect_kane_accelerations(shipped("cart_pole").system);
}

TEST(ArticulatedBody, PotentialAndCoordinateDamperMatchKane) {
  expect_kane_accelerations(shipped("spring_mass_damper").system);
}

// two rods, a torque input on the elbow, a force at the tip, a moment on rod 1, a spring and a
// damper from the tip to a fixed point and a torsional spring on the elbow
Model loaded_double_rod() {
  Model model;
  MechanicalSystem& s = model.system;
  const Coordinate q1 = s.add_coordinate("q1"), q2 = s.add_coordinate("q2");
  const ex m = s.add_parameter("m", 1.3), l = s.add_parameter("l", 0.7);
  const ex torque = s.add_input("torque"), push = s.add_input("push");
  const FrameId b = s.add_frame("b", s.inertial_frame(), Rotation::principal(3, q1.q));
  const FrameId c = s.add_frame("c", b, Rotation::principal(3, q2.q));
  const GiNaC::matrix J = GiNaC::ex_to<GiNaC::matrix>(GiNaC::diag_matrix(GiNaC::lst{0.01, m * l * l / 12, 0.02}));
  const PointId elbow = s.add_point("elbow", s.origin(), Vector(b, l, 0, 0));
  s.add_rigid_body("rod1", m, s.add_point("c1", s.origin(), Vector(b, l / 2, 0, 0)), b, J);
  s.add_rigid_body("rod2", m, s.add_point("c2", elbow, Vector(c, l / 2, 0.05, 0)), c, J);
  const PointId tip = s.add_point("tip", elbow, Vector(c, l, 0, 0));
  const PointId anchor = s.add_point("anchor", s.origin(), Vector(s.inertial_frame(), 0.5, 1.5, 0.2));
  s.set_gravity(Vector(s.inertial_frame(), 9.81, 0, 0));
  s.add_generalized_force(1, torque);
  s.add_force(tip, Vector(s.inertial_frame(), push, 0.3, 0));
  s.add_moment(b, Vector(s.inertial_frame(), 0, 0, 0.4));
  s.add_spring("spring", tip, anchor, 20.0, 0.5);
  s.add_damper("damper", tip, anchor, 0.7);
  s.add_torsional_spring("elbow_spring", q2.q, 3.0, 0.1);
  return model;
}

TEST(ArticulatedBody, ForcesMomentsSpringsAndDampersMatchKane) { expect_kane_accelerations(loaded_double_rod().system); }

// a body on a rail (x) turning about a.3 (psi), two pendulums hanging from it: a branched tree
Model branched_tree() {
  Model model;
  MechanicalSystem& s = model.system;
  const Coordinate x = s.add_coordinate("x"), psi = s.add_coordinate("psi");
  const Coordinate q1 = s.add_coordinate("q1"), q2 = s.add_coordinate("q2");
  const FrameId body = s.add_frame("platform", s.inertial_frame(), Rotation::principal(3, psi.q));
  const FrameId arm1 = s.add_frame("arm1", body, Rotation::principal(1, q1.q));
  const FrameId arm2 = s.add_frame("arm2", body, Rotation::principal(2, q2.q));
  const PointId centre = s.add_point("centre", s.origin(), Vector(s.inertial_frame(), x.q, 0, 0));
  GiNaC::matrix J(3, 3);
  J(0, 0) = 0.3, J(1, 1) = 0.4, J(2, 2) = 0.5, J(0, 1) = J(1, 0) = 0.05;
  s.add_rigid_body("carriage", 3.0, centre, body, J);
  const PointId hinge1 = s.add_point("hinge1", centre, Vector(body, 0.4, 0, 0));
  const PointId hinge2 = s.add_point("hinge2", centre, Vector(body, -0.4, 0.1, 0));
  s.add_rigid_body("rod1", 0.7, s.add_point("c1", hinge1, Vector(arm1, 0, 0.1, -0.3)), arm1, J);
  s.add_particle("bob2", 0.9, s.add_point("c2", hinge2, Vector(arm2, 0.05, 0, -0.5)));
  s.set_gravity(Vector(s.inertial_frame(), 0, 0, -9.81));
  return model;
}

TEST(ArticulatedBody, BranchedTreeMatchesKane) { expect_kane_accelerations(branched_tree().system); }

// a rigid pendulum on a pivot that shakes along a.1 inside a frame that spins about a.3: joints
// whose motion depends on time explicitly
TEST(ArticulatedBody, TimeDependentJointsMatchKane) {
  MechanicalSystem s;
  const Coordinate q = s.add_coordinate("q"), x = s.add_coordinate("x");
  const ex t = s.variables().time();
  const FrameId spin = s.add_frame("spin", s.inertial_frame(), Rotation::principal(3, 0.7 * t));
  const FrameId b = s.add_frame("b", spin, Rotation::principal(1, q.q));
  const PointId pivot = s.add_point("pivot", s.origin(), Vector(spin, 0.2 * GiNaC::sin(3 * t), 0, 0.1));
  GiNaC::matrix J(3, 3);
  J(0, 0) = 0.02, J(1, 1) = 0.03, J(2, 2) = 0.04;
  const PointId centre = s.add_point("centre", pivot, Vector(b, 0.1, 0.05, -0.5));
  s.add_rigid_body("rod", 1.2, centre, b, J);
  s.add_particle("slider", 0.4, s.add_point("slider_point", centre, Vector(b, 0, x.q, 0)));
  s.set_gravity(Vector(s.inertial_frame(), 0, 0, -9.81));
  expect_kane_accelerations(s);
}

TEST(ArticulatedBody, ModelsWithConstraintsHaveNone) {
  EXPECT_EQ(rejection(testing::cartesian_pendulum_model().system), "the model has constraints");
}

TEST(ArticulatedBody, AbsoluteAnglesAreNotJoints) {
  // the second rod's frame turns by q2 from the inertial frame, not from the first rod's
  MechanicalSystem s;
  const Coordinate q1 = s.add_coordinate("q1"), q2 = s.add_coordinate("q2");
  const FrameId b = s.add_frame("b", s.inertial_frame(), Rotation::principal(3, q1.q));
  const FrameId c = s.add_frame("c", s.inertial_frame(), Rotation::principal(3, q2.q));
  const PointId p1 = s.add_point("p1", s.origin(), Vector(b, 1, 0, 0));
  s.add_particle("bob1", 1.0, p1);
  s.add_particle("bob2", 1.0, s.add_point("p2", p1, Vector(c, 1, 0, 0)));
  EXPECT_EQ(rejection(s), "'bob2' moves relative to 'bob1' through more than its joint's coordinates");
}

TEST(ArticulatedBody, ClosedChainsAreNotTrees) {
  // a bar joining the bobs of two independent pendulums moves with both
  MechanicalSystem s;
  const Coordinate q1 = s.add_coordinate("q1"), q2 = s.add_coordinate("q2");
  const FrameId b = s.add_frame("b", s.inertial_frame(), Rotation::principal(3, q1.q));
  const FrameId c = s.add_frame("c", s.inertial_frame(), Rotation::principal(3, q2.q));
  const PointId p1 = s.add_point("p1", s.origin(), Vector(b, 1, 0, 0));
  const PointId p2 = s.add_point("p2", s.origin(), Vector(c, 1, 0, 0));
  s.add_particle("bob1", 1.0, p1);
  s.add_particle("bob2", 1.0, p2);
  s.add_particle("bar", 1.0, s.add_point("middle", p1, Vector(c, 0.5, 0, 0)));
  EXPECT_EQ(rejection(s), "'bob2' and 'bob1' both move 'bar' but not one with the other: not a tree");
}

TEST(ArticulatedBody, CoordinatesThatMoveNoMassLeaveNoJoint) {
  MechanicalSystem s;
  s.add_coordinate("x");
  const Coordinate y = s.add_coordinate("y");
  s.add_particle("block", 1.0, s.add_point("p", s.origin(), Vector(s.inertial_frame(), y.q, 0, 0)));
  EXPECT_EQ(rejection(s), "coordinate 'x' moves no mass");
}

}  // namespace
}  // namespace eomgen
