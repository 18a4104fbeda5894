#include "eomgen/derivation/composite_body.hpp"

#include <gtest/gtest.h>

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

TEST(CompositeBody, ModelsWithConstraintsHaveNone) {
  auto derived = derive_composite_body_equations(testing::cartesian_pendulum_model().system);
  ASSERT_TRUE(std::holds_alternative<std::string>(derived));
  EXPECT_EQ(std::get<std::string>(derived), "the model has constraints");
}

// the reason the recursions exist: M + F of the closed form grow like n^2.5 for a chain, theirs
// like n^2 (M) and n (F): at 32 links they take under half (0.29 when written)
TEST(CompositeBody, LongChainsTakeFewerOperationsThanTheClosedForm) {
  const MechanicalSystem s = shipped("planar_chain", {{"n", 32}}).system;
  const double recursive = composite(s).estimated_operations;
  const EquationsOfMotion kane = derive_equations(s);
  EXPECT_GT(recursive, 0.0);
  EXPECT_LT(recursive, 0.5 * kane.estimated_operations_inertial);
}

}  // namespace
}  // namespace eomgen
