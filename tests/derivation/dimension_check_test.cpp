// check_dimensions: the derived equations of a model with units against them. The language checks
// what a model writes, so this can fail only on a bug; here the units are falsified after the
// language checked them, as such a bug would.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "eomgen/base/error.hpp"
#include "eomgen/derivation/dimension_check.hpp"
#include "eomgen/derivation/model_equations.hpp"
#include "eomgen/language/model_file.hpp"

namespace eomgen {
namespace {

const std::string pendulum =
    "parameter m = 1 [kg]\nparameter l = 0.5 [m]\nparameter g = 9.81 [m/s^2]\ncoordinate theta\n"
    "frame b = rotate(a, 3, theta)\npoint p = w + l*b.1\nparticle bob(mass = m, at = p)\ngravity = g*a.1\n";

TEST(DimensionCheck, TheEquationsOfAModelWithUnitsPass) {
  const Model model = parse_model(pendulum, "h.eom");
  const EquationsOfMotion eom = derive_equations(model.system);
  EXPECT_NO_THROW(check_dimensions(eom, model.system.variables(), model.dimensions));
}

TEST(DimensionCheck, AModelWithoutUnitsIsNotChecked) {
  const Model model = parse_model("coordinate x\npoint p = w + x*a.1\nparticle bob(mass = 1, at = p)\n", "h.eom");
  EXPECT_TRUE(model.dimensions.empty());
  EXPECT_NO_THROW(check_dimensions(derive_equations(model.system), model.system.variables(), model.dimensions));
}

TEST(DimensionCheck, ABrokenRowIsNamedWithItsTermAndBothDimensions) {
  Model model = parse_model(pendulum, "h.eom");
  // as if the mass were a mass times a length
  model.dimensions[*model.system.variables().find("m")] = Dimension::mass() * Dimension::length();
  try {
    derive_equations(model);
    ADD_FAILURE() << "expected a DerivationError";
  } catch (const DerivationError& e) {
    EXPECT_THAT(e.what(), ::testing::StartsWith("the derived equations break the model's units (a bug in eomgen): "
                                                "M(1, 1), row of 'theta', column of 'theta': the term '"));
    EXPECT_THAT(e.what(), ::testing::EndsWith("' has dimension kg m^3, expected kg m^2"));
  }
}

}  // namespace
}  // namespace eomgen
