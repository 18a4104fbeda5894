#include "eomgen/derivation/articulated_body.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <string>

#include "eomgen/derivation/equations_of_motion.hpp"
#include "eomgen/language/model_file.hpp"
#include "eomgen/urdf/urdf_import.hpp"
#include "support/numeric_checks.hpp"
#include "support/source_dir.hpp"
#include "support/test_models.hpp"
#include "support/tree_models.hpp"

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

// both forms (the recursion, and M's factors), each against Kane's M^-1 F
void expect_kane_accelerations(const MechanicalSystem& s, int states = 3) {
  const EquationsOfMotion eom = derive_equations(s);
  for (const ForwardDynamics::Form form : {ForwardDynamics::Form::articulated_body, ForwardDynamics::Form::mass_matrix}) {
    SCOPED_TRACE(form == ForwardDynamics::Form::articulated_body ? "articulated body" : "mass matrix");
    auto derived = derive_forward_dynamics(s, form);
    const auto* reason = std::get_if<std::string>(&derived);
    ASSERT_EQ(reason, nullptr) << *reason;
    const ForwardDynamics& fd = std::get<ForwardDynamics>(derived);
    EXPECT_EQ(fd.form, form);
    std::mt19937 rng(14);
    for (int k = 0; k < states; ++k) {
      const GiNaC::exmap state = random_state(s, rng);
      EXPECT_TRUE(testing::matrices_near_relative(articulated(fd, state), reference(eom, state), 1e-12));
    }
  }
}

std::string rejection(const MechanicalSystem& s) {
  auto derived = derive_forward_dynamics(s);
  const auto* reason = std::get_if<std::string>(&derived);
  return reason ? *reason : "(a forward dynamics)";
}

// The recursion grows linearly with the links and M's factors cubically: short chains take
// the factors, long ones the recursion; the choice is the form of fewer weighted operations
TEST(ArticulatedBody, ShortChainsTakeTheFactorsOfMAndLongOnesTheRecursion) {
  for (const auto& [n, expected] : std::vector<std::pair<double, ForwardDynamics::Form>>{
           {2, ForwardDynamics::Form::mass_matrix}, {24, ForwardDynamics::Form::articulated_body}}) {
    SCOPED_TRACE(n);
    auto derived = derive_forward_dynamics(shipped("planar_chain", {{"n", n}}).system);
    const ForwardDynamics& fd = std::get<ForwardDynamics>(derived);
    EXPECT_EQ(fd.form, expected);
    EXPECT_GT(fd.estimated_operations, 0);
    const double recursion = expected == ForwardDynamics::Form::articulated_body ? fd.estimated_operations
                                                                                  : fd.estimated_operations_other;
    const double factors = expected == ForwardDynamics::Form::mass_matrix ? fd.estimated_operations
                                                                          : fd.estimated_operations_other;
    EXPECT_EQ(factors < 1.15 * recursion, expected == ForwardDynamics::Form::mass_matrix)
        << "factors " << factors << ", recursion " << recursion;
  }
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

TEST(ArticulatedBody, ForcesMomentsSpringsAndDampersMatchKane) { expect_kane_accelerations(testing::loaded_double_rod().system); }

// A force and a moment on the last link of a seven-joint arm: its velocity is large enough that
// its partial derivatives take the graph path of graph_calculus.hpp, which once read the rate
// symbol through a reference to a freed copy (eomgen generate crashed on such a model)
TEST(ArticulatedBody, LoadsOnADeepLinkMatchKane) {
  const std::string arm = (testing::source_dir() / "models" / "robots" / "iiwa14.urdf").string();
  const std::string text = urdf::import_urdf(arm).text +
                           "force push(at = iiwa_link_7_com, force = 30*a.3 - 20*iiwa_link_7.1)\n"
                           "moment twist(on = iiwa_link_7, moment = 2*iiwa_link_7.3 + a.1)\n";
  expect_kane_accelerations(parse_model(text, "iiwa14_loaded.eom").system, 1);
}

TEST(ArticulatedBody, BranchedTreeMatchesKane) { expect_kane_accelerations(testing::branched_tree().system); }

TEST(ArticulatedBody, TimeDependentJointsMatchKane) { expect_kane_accelerations(testing::shaken_pendulum_with_slider().system); }

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
