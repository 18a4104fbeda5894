// The shipped robots (models/robots/*.urdf), generated from their URDF files at build time:
// every function against the symbolic equations of the imported model, at random parameters and
// states, and the recursive forward dynamics against M^-1 F where the header has it.
#include <gtest/gtest.h>

#include <string>

#include "iiwa14.hpp"
#include "panda.hpp"
#include "support/source_dir.hpp"
#include "symbolic_agreement.hpp"
#include "two_arm_torso.hpp"
#include "ur5.hpp"

namespace {

std::string robot_path(const std::string& name) {
  return (eomgen::testing::source_dir() / "models" / "robots" / (name + ".urdf")).string();
}

#define GENERATED_ROBOT_TEST(name)                                                            \
  TEST(GeneratedRobot, name##MatchesTheSymbolicEquationsOfItsURDF) {                          \
    eomgen::testing::check_against_symbolic<eomgen_models::name::Model>({}, robot_path(#name)); \
  }

GENERATED_ROBOT_TEST(ur5)
GENERATED_ROBOT_TEST(iiwa14)
GENERATED_ROBOT_TEST(panda)
GENERATED_ROBOT_TEST(two_arm_torso)

// the arms without constraints carry the recursive forward dynamics; the Panda's mimic finger
// is a constraint, which the recursions do not take
static_assert(eomgen_models::ur5::Model::has_forward_dynamics);
static_assert(eomgen_models::iiwa14::Model::has_forward_dynamics);
static_assert(eomgen_models::two_arm_torso::Model::has_forward_dynamics);
static_assert(!eomgen_models::panda::Model::has_forward_dynamics);
static_assert(eomgen_models::panda::Model::nc == 1);

}  // namespace
