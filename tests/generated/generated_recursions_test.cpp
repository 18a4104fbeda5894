// Long chains, whose generated M and F come from the composite-rigid-body and Newton-Euler
// recursions (the generator keeps them where they take fewer operations than the closed form):
// against Kane's symbolic equations of the same model, as every shipped model is in
// generated_models_test.cpp. The headers are generated at build time with n = 8.
#include <gtest/gtest.h>

#include "planar_chain.hpp"
#include "symbolic_agreement.hpp"
#include "universal_chain.hpp"

namespace {

TEST(GeneratedRecursions, PlanarChainOfEightMatchesKane) {
  eomgen::testing::check_against_symbolic<eomgen_models::planar_chain::Model>({{"n", 8}});
}

TEST(GeneratedRecursions, UniversalChainOfEightMatchesKane) {
  eomgen::testing::check_against_symbolic<eomgen_models::universal_chain::Model>({{"n", 8}});
}

}  // namespace
