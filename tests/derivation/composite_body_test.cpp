#include "eomgen/derivation/composite_body.hpp"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <string>

#include "eomgen/derivation/equations_of_motion.hpp"
#include "eomgen/language/model_file.hpp"
#include "support/numeric_checks.hpp"
#include "support/source_dir.hpp"
#include "support/symbolic_checks.hpp"
#include "support/test_models.hpp"
#include "support/tree_models.hpp"

namespace eomgen {
namespace {

Model shipped(const std::string& name, std::map<std::string, double> defines = {}) {
  return load_model(testing::shipped_model_path(name), defines);
}

CompositeBodyEquations composite(const MechanicalSystem& s) {
  auto derived = derive_composite_body_equations(s);
  if (const auto* reason = std::get_if<std::string>(&derived)) ADD_FAILURE() << "no recursive M and F: " << *reason;
  return std::get<CompositeBodyEquations>(std::move(derived));
}

// The recursions against Kane's closed form: the same M and F at random states, to round-off
void expect_kane_mass_matrix_and_forcing(const MechanicalSystem& s) {
  auto derived = derive_composite_body_equations(s);
  const auto* reason = std::get_if<std::string>(&derived);
  ASSERT_EQ(reason, nullptr) << "no recursive M and F: " << *reason;
  const CompositeBodyEquations& recursive = std::get<CompositeBodyEquations>(derived);
  const EquationsOfMotion kane = derive_equations(s);
  for (unsigned seed : {3u, 14u, 15u}) {
    const GiNaC::exmap state = testing::random_state(s, seed);
    const GiNaC::exmap ours = recursive.subexpressions.evaluate_all(state);
    const GiNaC::exmap theirs = kane.subexpressions.evaluate_all(state);
    EXPECT_TRUE(testing::matrices_near_relative(testing::value_at(recursive.mass_matrix, ours),
                                                testing::value_at(kane.mass_matrix, theirs), 1e-12))
        << "M at seed " << seed;
    EXPECT_TRUE(testing::matrices_near_relative(testing::value_at(recursive.forcing, ours),
                                                testing::value_at(kane.forcing, theirs), 1e-12))
        << "F at seed " << seed;
  }
}

TEST(CompositeBody, PlanarChainsMatchKane) {
  for (double n : {1, 2, 5}) {
    SCOPED_TRACE(n);
    expect_kane_mass_matrix_and_forcing(shipped("planar_chain", {{"n", n}}).system);
  }
}

TEST(CompositeBody, UniversalChainsMatchKane) {
  for (double n : {1, 3}) {
    SCOPED_TRACE(n);
    expect_kane_mass_matrix_and_forcing(shipped("universal_chain", {{"n", n}}).system);
  }
}

TEST(CompositeBody, ParticlesOnMasslessRodsMatchKane) {
  expect_kane_mass_matrix_and_forcing(shipped("double_pendulum").system);
  expect_kane_mass_matrix_and_forcing(testing::double_pendulum_model().system);
}

TEST(CompositeBody, PrismaticJointAndInputForceMatchKane) {
  expect_kane_mass_matrix_and_forcing(shipped("cart_pole").system);
}

TEST(CompositeBody, PotentialAndCoordinateDamperMatchKane) {
  expect_kane_mass_matrix_and_forcing(shipped("spring_mass_damper").system);
}

TEST(CompositeBody, ForcesMomentsSpringsAndDampersMatchKane) {
  expect_kane_mass_matrix_and_forcing(testing::loaded_double_rod().system);
}

TEST(CompositeBody, BranchedTreeMatchesKane) { expect_kane_mass_matrix_and_forcing(testing::branched_tree().system); }

TEST(CompositeBody, TimeDependentJointsMatchKane) {
  expect_kane_mass_matrix_and_forcing(testing::shaken_pendulum_with_slider().system);
}

// the two pendulums of the branched tree hang from different sides of the carriage: neither
// moves the other, so their entry of M is zero by structure, not by cancellation
TEST(CompositeBody, BranchesThatDoNotMoveEachOtherHaveStructurallyZeroCoupling) {
  const CompositeBodyEquations recursive = composite(testing::branched_tree().system);
  EXPECT_TRUE(recursive.mass_matrix(2, 3).is_zero());
  EXPECT_TRUE(recursive.mass_matrix(3, 2).is_zero());
  EXPECT_FALSE(recursive.mass_matrix(0, 3).is_zero());
}

// constraints enter as Xi^T lambda and leave M and F those of the tree: the recursions give them
// for a constrained tree too (a pendulum held on a circle, the bicycle rolling, a gripper's mimic
// finger), and the same as Kane's
TEST(CompositeBody, ConstrainedTreesHaveTheTreesMAndFWhichMatchKane) {
  expect_kane_mass_matrix_and_forcing(testing::cartesian_pendulum_model().system);
  expect_kane_mass_matrix_and_forcing(shipped("whipple_bicycle").system);
  expect_kane_mass_matrix_and_forcing(
      load_model((testing::source_dir() / "models" / "robots" / "panda.urdf").string()).system);
}

// the reason the recursions exist: M + F of the closed form grow like n^2.5 for a chain, theirs
// like n^2 (M) and n (F): at 32 links they take under half (0.29 when written)
TEST(CompositeBody, LongChainsTakeFewerOperationsThanTheClosedForm) {
  const MechanicalSystem s = shipped("planar_chain", {{"n", 32}}).system;
  const double recursive = composite(s).estimated_operations;
  const EquationsOfMotion kane = derive_equations(s, KinematicsResolution::inertial);
  EXPECT_GT(recursive, 0.0);
  EXPECT_LT(recursive, 0.5 * kane.estimated_operations_inertial);
}

// Beyond local_resolution_limit coordinates a tree's derivation takes M and F from the
// recursions (n^2/2 entries instead of the closed form's n^3/6 terms: a chain of 200 derives in
// seconds): the same M, F, T and V as Kane's closed form at random states
TEST(CompositeBody, LongTreesAreDerivedWithTheRecursionsAndMatchKane) {
  const double n = static_cast<double>(local_resolution_limit + 1);
  for (const char* name : {"planar_chain", "universal_chain"}) {
    SCOPED_TRACE(name);
    const MechanicalSystem s = shipped(name, {{"n", name == std::string("planar_chain") ? n : 7}}).system;
    const EquationsOfMotion eom = derive_equations(s);
    const EquationsOfMotion kane = derive_equations(s, KinematicsResolution::inertial);
    EXPECT_EQ(eom.dynamics, DynamicsForm::recursions);
    EXPECT_EQ(kane.dynamics, DynamicsForm::closed_form);
    EXPECT_GT(eom.estimated_operations_recursions, 0.0);
    EXPECT_LT(eom.estimated_operations_recursions, kane.estimated_operations_inertial);
    EXPECT_TRUE(std::isnan(eom.estimated_operations_inertial));
    for (unsigned seed : {5u, 92u}) {
      const GiNaC::exmap state = testing::random_state(s, seed);
      const GiNaC::exmap ours = eom.subexpressions.evaluate_all(state);
      const GiNaC::exmap theirs = kane.subexpressions.evaluate_all(state);
      EXPECT_TRUE(testing::matrices_near_relative(testing::value_at(eom.mass_matrix, ours),
                                                  testing::value_at(kane.mass_matrix, theirs), 1e-12));
      EXPECT_TRUE(testing::matrices_near_relative(testing::value_at(eom.forcing, ours),
                                                  testing::value_at(kane.forcing, theirs), 1e-12));
      const double T = testing::value_at(kane.kinetic_energy, theirs);
      const double V = testing::value_at(kane.potential_energy, theirs);
      EXPECT_GT(T, 0.0);
      EXPECT_NEAR(testing::value_at(eom.kinetic_energy, ours), T, 1e-12 * T);
      EXPECT_NEAR(testing::value_at(eom.potential_energy, ours), V, 1e-12 * (std::abs(V) + 1));
    }
  }
  // at the limit, the closed form
  EXPECT_EQ(derive_equations(shipped("planar_chain", {{"n", static_cast<double>(local_resolution_limit)}}).system).dynamics,
            DynamicsForm::closed_form);
}

// a long model that is not a tree (a constraint) keeps Kane's closed form
TEST(CompositeBody, LongModelsWithConstraintsKeepTheClosedForm) {
  std::string text = "coordinate x0, y0\npoint p0 = w + x0*a.1 + y0*a.2\nparticle b0(mass = 1, at = p0)\n";
  for (std::size_t i = 1; i <= local_resolution_limit / 2; ++i)
    text += fmt::format("coordinate x{0}, y{0}\npoint p{0} = w + x{0}*a.1 + y{0}*a.2\nparticle b{0}(mass = 1, at = p{0})\n", i);
  text += "gravity = -9.81*a.2\nconstraint rod: x0^2 + y0^2 = 1\n";
  const MechanicalSystem s = parse_model(text, "constrained.eom").system;
  ASSERT_GT(s.variables().coordinate_count(), local_resolution_limit);
  const EquationsOfMotion eom = derive_equations(s);
  EXPECT_EQ(eom.dynamics, DynamicsForm::closed_form);
  EXPECT_EQ(eom.constraint_count, 1u);
  EXPECT_TRUE(std::isnan(eom.estimated_operations_recursions));
}

}  // namespace
}  // namespace eomgen
