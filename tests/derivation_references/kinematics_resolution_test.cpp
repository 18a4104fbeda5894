// The two resolutions of the derivation (KinematicsResolution): the local one gives the closed
// forms of a hand derivation (a rod's own angle cancels, rotations about one axis compound to
// one angle), both give the same numbers on every shipped model, and derive_equations keeps the
// smaller one, the inertial one for long chains.
#include <Eigen/Core>
#include <ginac/ginac.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "eomgen/derivation/equations_of_motion.hpp"
#include "eomgen/language/model_file.hpp"
#include "support/model_lookup.hpp"
#include "support/source_dir.hpp"
#include "support/symbolic_checks.hpp"

namespace eomgen {
namespace {

using GiNaC::cos;
using GiNaC::ex;
using GiNaC::matrix;
using GiNaC::sin;
using testing::equal_after_expansion;
using testing::symbol_named;

Model chain(const char* name, double n) { return load_model(testing::shipped_model_path(name), {{"n", n}}); }

// every entry of m (which may use the intermediates of eom) at the point
Eigen::MatrixXd at(const EquationsOfMotion& eom, const matrix& m, const GiNaC::exmap& point) {
  return testing::value_at(m, eom.subexpressions.evaluate_all(point));
}

matrix scalar(const ex& e) { return matrix(1, 1, GiNaC::lst{e}); }

TEST(LocalResolution, SingleRodMassMatrixIsAConstantWithoutSinesOrCosines) {
  // uniform rod of mass m, length l, radius rd on a hinge at its end: M = m (l^2/3 + rd^2/4), a
  // constant; resolved in the inertial frame it was m (l^2/12 + rd^2/4) + m ((l/2 sin q)^2 +
  // (l/2 cos q)^2), which only sin^2 + cos^2 = 1 reduces
  const Model md = chain("planar_chain", 1);
  const MechanicalSystem& s = md.system;
  const EquationsOfMotion eom = derive_equations(s);
  ASSERT_EQ(eom.resolution, KinematicsResolution::local);
  const ex m = symbol_named(s, "m"), l = symbol_named(s, "l"), rd = symbol_named(s, "rd"), g = symbol_named(s, "g");
  const ex q1 = symbol_named(s, "q1");
  EXPECT_TRUE(equal_after_expansion(eom.subexpressions.expand(eom.mass_matrix(0, 0)), m * (l * l / 3 + rd * rd / 4)));
  EXPECT_TRUE(equal_after_expansion(eom.subexpressions.expand(eom.forcing(0, 0)), -m * g * l / 2 * sin(q1)));
}

TEST(LocalResolution, HingesAboutOneAxisCompoundToOneAngle) {
  // two rods, relative angles: the weight of rod 2 acts through sin(q1 + q2), one call, where the
  // product C3(q2) C3(q1) multiplied out gives sin q1 cos q2 + cos q1 sin q2; and M11 brings the
  // relative angle only, as cos q2 (expansion alone, no trigonometric identity, shows both)
  const Model md = chain("planar_chain", 2);
  const MechanicalSystem& s = md.system;
  const EquationsOfMotion eom = derive_equations(s);
  ASSERT_EQ(eom.resolution, KinematicsResolution::local);
  const ex m = symbol_named(s, "m"), l = symbol_named(s, "l"), rd = symbol_named(s, "rd"), g = symbol_named(s, "g");
  const ex q1 = symbol_named(s, "q1"), q2 = symbol_named(s, "q2");
  const Subexpressions& z = eom.subexpressions;
  EXPECT_TRUE(equal_after_expansion(z.expand(eom.mass_matrix(0, 0)),
                                    m * (ex(5) / 3 * l * l + l * l * cos(q2) + rd * rd / 2)));
  EXPECT_TRUE(equal_after_expansion(z.expand(eom.mass_matrix(1, 1)), m * (l * l / 3 + rd * rd / 4)));
  EXPECT_TRUE(equal_after_expansion(s.variables().at_rest(z.expand(eom.forcing(1, 0))),
                                    -m * g * l / 2 * sin(q1 + q2)));
}

// A random state; for the quaternion model on its unit-norm constraint with rates tangent to it,
// where the two forms must agree (off it C_ba is not orthogonal, and resolving a body torque
// through the inertial frame, C^T C tau, is not tau)
GiNaC::exmap random_consistent_state(const MechanicalSystem& s, unsigned seed) {
  GiNaC::exmap x = testing::random_state(s, seed);
  const auto eta = s.variables().find("eta");
  if (!eta) return x;
  std::vector<ex> q, qd;
  for (const char* name : {"e1", "e2", "e3", "eta"}) {
    const auto& c = s.variables().coordinates()[*s.variables().coordinate_index(symbol_named(s, name))];
    q.push_back(c.q);
    qd.push_back(c.qd);
  }
  double norm2 = 0, radial = 0;
  for (std::size_t i = 0; i < 4; ++i) norm2 += std::pow(testing::to_double(x[q[i]]), 2);
  for (std::size_t i = 0; i < 4; ++i) x[q[i]] = testing::to_double(x[q[i]]) / std::sqrt(norm2);
  for (std::size_t i = 0; i < 4; ++i) radial += testing::to_double(x[q[i]]) * testing::to_double(x[qd[i]]);
  for (std::size_t i = 0; i < 4; ++i)
    x[qd[i]] = testing::to_double(x[qd[i]]) - radial * testing::to_double(x[q[i]]);
  return x;
}

TEST(LocalResolution, TermsWithTheSameStateFactorsShareOneParameterCoefficient) {
  // one rod on a universal joint (C_ba = C2(beta) C1(alpha)): the partial angular velocity of
  // alpha in b is [cos beta, 0, sin beta], that of the mass centre (0, l/2 cos beta, 0), so
  //   M11 = m l^2/4 cos^2 beta + J1 cos^2 beta + J3 sin^2 beta
  //       = m (l^2/3 + rd^2/4) cos^2 beta + m rd^2/2 sin^2 beta:
  // two monomials, each with one coefficient computed once per parameter set
  const Model md = chain("universal_chain", 1);
  const MechanicalSystem& s = md.system;
  const EquationsOfMotion eom = derive_equations(s);
  ASSERT_EQ(eom.resolution, KinematicsResolution::local);
  const ex m = symbol_named(s, "m"), l = symbol_named(s, "l"), rd = symbol_named(s, "rd");
  const ex beta = symbol_named(s, "beta1");
  const ex M11 = eom.mass_matrix(0, 0);
  ASSERT_TRUE(GiNaC::is_a<GiNaC::add>(M11)) << M11;
  EXPECT_EQ(M11.nops(), 2u) << M11;
  EXPECT_TRUE(equal_after_expansion(
      M11, m * (l * l / 3 + rd * rd / 4) * GiNaC::pow(cos(beta), 2) + m * rd * rd / 2 * GiNaC::pow(sin(beta), 2)));
}

class BothResolutions : public ::testing::TestWithParam<std::string> {};

TEST_P(BothResolutions, GiveTheSameEquationsAtRandomStates) {
  const Model md = load_model(testing::shipped_model_path(GetParam()));
  const MechanicalSystem& s = md.system;
  const EquationsOfMotion inertial = derive_equations(s, KinematicsResolution::inertial);
  const EquationsOfMotion local = derive_equations(s, KinematicsResolution::local);
  for (unsigned seed = 3; seed < 6; ++seed) {
    const GiNaC::exmap x = random_consistent_state(s, seed);
    EXPECT_TRUE(testing::matrices_near_relative(at(local, local.mass_matrix, x), at(inertial, inertial.mass_matrix, x),
                                                1e-12));
    EXPECT_TRUE(testing::matrices_near_relative(at(local, local.forcing, x), at(inertial, inertial.forcing, x), 1e-12));
    EXPECT_TRUE(testing::matrices_near_relative(at(local, scalar(local.kinetic_energy), x),
                                                at(inertial, scalar(inertial.kinetic_energy), x), 1e-12));
    EXPECT_TRUE(testing::matrices_near_relative(at(local, scalar(local.potential_energy), x),
                                                at(inertial, scalar(inertial.potential_energy), x), 1e-12));
  }
}

INSTANTIATE_TEST_SUITE_P(ShippedModels, BothResolutions,
                         ::testing::Values("bead_on_hoop", "cart_pole", "cartesian_pendulum", "double_pendulum",
                                           "heavy_top", "knife_edge", "planar_chain", "quaternion_rigid_body",
                                           "rolling_coin", "simple_pendulum", "spacecraft_panel",
                                           "spherical_pendulum", "spring_mass_damper", "universal_chain"));

TEST(ResolutionChoice, KeepsTheFormWithFewerEstimatedOperations) {
  for (double n : {1.0, 2.0, 4.0, 8.0}) {
    const EquationsOfMotion eom = derive_equations(chain("planar_chain", n).system);
    if (std::isnan(eom.estimated_operations_local)) {
      // given up once its entries multiplied out passed 8 times the inertial form's operations
      // (planar 8: it would have taken 2511 against 1546)
      EXPECT_GE(n, 8.0);
      EXPECT_EQ(eom.resolution, KinematicsResolution::inertial) << n;
      continue;
    }
    const bool local_smaller = eom.estimated_operations_local < eom.estimated_operations_inertial;
    EXPECT_EQ(eom.resolution, local_smaller ? KinematicsResolution::local : KinematicsResolution::inertial) << n;
  }
  // a single rod: M is a constant and F one product with a sine in the local form
  const EquationsOfMotion rod = derive_equations(chain("planar_chain", 1).system);
  EXPECT_LT(rod.estimated_operations_local, rod.estimated_operations_inertial);
}

// a long chain's kinematics are resolved in the inertial frame only, and its M and F come from
// the recursions (composite_body_test compares them with Kane's)
TEST(ResolutionChoice, LongChainsAreDerivedInTheInertialFormOnlyWithTheRecursions) {
  const EquationsOfMotion eom = derive_equations(chain("planar_chain", double(local_resolution_limit + 1)).system);
  EXPECT_EQ(eom.resolution, KinematicsResolution::inertial);
  EXPECT_EQ(eom.dynamics, DynamicsForm::recursions);
  EXPECT_TRUE(std::isnan(eom.estimated_operations_local));
  EXPECT_GT(eom.estimated_operations_recursions, 0);
}

}  // namespace
}  // namespace eomgen
