// Every shipped model's generated header against the symbolic equations it came from, at
// random states, to 1e-12 relative, and its overloads taking Constants against those taking
// Parameters. The headers are generated at build time by
// eomgen_add_model(), so this also exercises the CMake function.
#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "bead_on_hoop.hpp"
#include "cart_pole.hpp"
#include "cartesian_pendulum.hpp"
#include "double_pendulum.hpp"
#include "eomgen/derivation/equations_of_motion.hpp"
#include "eomgen/derivation/model_equations.hpp"
#include "eomgen/language/model_file.hpp"
#include "four_bar.hpp"
#include "generated_strict_compile.hpp"
#include "heavy_top.hpp"
#include "knife_edge.hpp"
#include "planar_3rrr.hpp"
#include "two_wheeled_robot.hpp"
#include "planar_chain.hpp"
#include "quaternion_rigid_body.hpp"
#include "rolling_coin.hpp"
#include "simple_pendulum.hpp"
#include "spacecraft_panel.hpp"
#include "spherical_pendulum.hpp"
#include "spring_mass_damper.hpp"
#include "universal_chain.hpp"
#include "whipple_bicycle.hpp"
#include "support/numeric_checks.hpp"
#include "symbolic_agreement.hpp"

namespace {

// equal entry by entry, bit for bit (NaN where the other is NaN)
template <class Matrix>
bool same_bits(const Matrix& a, const Matrix& b) {
  for (Eigen::Index i = 0; i < a.size(); ++i)
    if (!(a(i) == b(i) || (std::isnan(a(i)) && std::isnan(b(i))))) return false;
  return true;
}

// The overloads taking Constants against those taking Parameters, at random parameters and
// states: the same numbers to the bit, as the Parameters overloads forward to them through
// Constants built for the call; and the Constants keep a copy of the parameters, not a view.
template <class Model>
void check_constants_overloads() {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> uniform(-1.2, 1.2), positive(0.5, 2.0);
  for (int trial = 0; trial < 4; ++trial) {
    typename Model::template Parameters<double> p;
    const auto fields = p.fields();
    for (std::size_t k = 0; k < fields.size(); ++k) *fields[k] = Model::parameter_defaults[k] * positive(rng);
    const typename Model::template Constants<double> c(p);
    const double t = positive(rng);
    typename Model::template Vector<double> q, qd;
    typename Model::template Inputs<double> u;
    for (int k = 0; k < Model::nq; ++k) q(k) = uniform(rng), qd(k) = uniform(rng);
    for (int k = 0; k < Model::nu; ++k) u(k) = uniform(rng);
    typename Model::template MassMatrix<double> M, Mc, M2, M2c;
    typename Model::template Vector<double> F, Fc, F2, F2c;
    Model::mass_matrix(t, q, p, M);
    Model::mass_matrix(t, q, c, Mc);
    Model::forcing(t, q, qd, u, p, F);
    Model::forcing(t, q, qd, u, c, Fc);
    Model::mass_matrix_and_forcing(t, q, qd, u, p, M2, F2);
    Model::mass_matrix_and_forcing(t, q, qd, u, c, M2c, F2c);
    EXPECT_TRUE(same_bits(M, Mc) && same_bits(F, Fc) && same_bits(M2, M2c) && same_bits(F2, F2c)) << Model::name;
    typename Model::template ConstraintJacobian<double> Xi, Xic;
    typename Model::template ConstraintVector<double> Xi_t, Xi_tc, b, bc;
    typename Model::template HolonomicVector<double> phi, phic;
    Model::constraint_jacobian(t, q, p, Xi);
    Model::constraint_jacobian(t, q, c, Xic);
    Model::constraint_rate_term(t, q, p, Xi_t);
    Model::constraint_rate_term(t, q, c, Xi_tc);
    Model::constraint_acceleration_term(t, q, qd, p, b);
    Model::constraint_acceleration_term(t, q, qd, c, bc);
    Model::holonomic_residuals(t, q, p, phi);
    Model::holonomic_residuals(t, q, c, phic);
    EXPECT_TRUE(same_bits(Xi, Xic) && same_bits(Xi_t, Xi_tc) && same_bits(b, bc) && same_bits(phi, phic))
        << Model::name;
    typename Model::template OutputVector<double> y, yc;
    Model::outputs(t, q, qd, u, p, y);
    Model::outputs(t, q, qd, u, c, yc);
    EXPECT_TRUE(same_bits(y, yc)) << Model::name;
    const Eigen::Vector2d energies(Model::kinetic_energy(t, q, qd, p), Model::potential_energy(t, q, p));
    const Eigen::Vector2d energies_c(Model::kinetic_energy(t, q, qd, c), Model::potential_energy(t, q, c));
    EXPECT_TRUE(same_bits(energies, energies_c)) << Model::name;
    if constexpr (Model::has_forward_dynamics) {
      typename Model::template Vector<double> qdd, qdd_c;
      EXPECT_EQ(Model::forward_dynamics(t, q, qd, u, p, qdd), Model::forward_dynamics(t, q, qd, u, c, qdd_c));
      EXPECT_TRUE(same_bits(qdd, qdd_c)) << Model::name;
    }
    // the copy: changing p afterwards changes nothing the Constants give
    auto copy = c.parameters();
    for (std::size_t k = 0; k < fields.size(); ++k) EXPECT_EQ(*copy.fields()[k], *fields[k]) << Model::name;
    for (double* f : fields) *f *= 2;
    Model::mass_matrix_and_forcing(t, q, qd, u, c, M2c, F2c);
    EXPECT_TRUE(same_bits(M2, M2c) && same_bits(F2, F2c)) << Model::name;
  }
}

#define GENERATED_CONSTANTS_TEST(name)                                              \
  TEST(GeneratedModel, name##GivesTheSameBitsThroughConstantsAndParameters) {      \
    check_constants_overloads<eomgen_models::name::Model>();                       \
  }
GENERATED_CONSTANTS_TEST(simple_pendulum)
GENERATED_CONSTANTS_TEST(double_pendulum)
GENERATED_CONSTANTS_TEST(cart_pole)
GENERATED_CONSTANTS_TEST(spherical_pendulum)
GENERATED_CONSTANTS_TEST(heavy_top)
GENERATED_CONSTANTS_TEST(quaternion_rigid_body)
GENERATED_CONSTANTS_TEST(cartesian_pendulum)
GENERATED_CONSTANTS_TEST(knife_edge)
GENERATED_CONSTANTS_TEST(rolling_coin)
GENERATED_CONSTANTS_TEST(bead_on_hoop)
GENERATED_CONSTANTS_TEST(spring_mass_damper)
GENERATED_CONSTANTS_TEST(spacecraft_panel)
GENERATED_CONSTANTS_TEST(planar_chain)
GENERATED_CONSTANTS_TEST(universal_chain)

// F = -m g l sin(theta) (models/simple_pendulum.eom): Constants built from parameters with
// another g give F changed by -m (g2 - g1) l sin(theta); those built before keep the old g
TEST(GeneratedModel, ConstantsBuiltFromChangedParametersGiveTheNewValues) {
  using Model = eomgen_models::simple_pendulum::Model;
  Model::Parameters<double> p;
  p.m = 1.3;
  p.l = 0.7;
  p.g = 9.81;
  const Model::Constants<double> before(p);
  p.g = 1.62;
  const Model::Constants<double> after(p);
  const Model::Vector<double> q(0.4), qd(-0.3);
  const Model::Inputs<double> u;
  Model::MassMatrix<double> M;
  Model::Vector<double> F_before, F_after;
  Model::mass_matrix_and_forcing(0.0, q, qd, u, before, M, F_before);
  Model::mass_matrix_and_forcing(0.0, q, qd, u, after, M, F_after);
  EXPECT_NEAR(F_before(0), -1.3 * 9.81 * 0.7 * std::sin(0.4), 1e-14);
  EXPECT_NEAR(F_after(0) - F_before(0), -1.3 * (1.62 - 9.81) * 0.7 * std::sin(0.4), 1e-14);
  EXPECT_NEAR(M(0, 0), 1.3 * 0.7 * 0.7, 1e-15);
  EXPECT_EQ(before.parameters().g, 9.81);
  EXPECT_EQ(after.parameters().g, 1.62);
}

// trees without constraints have forward_dynamics(); the rest keep M and F only
static_assert(eomgen_models::planar_chain::Model::has_forward_dynamics);
static_assert(eomgen_models::universal_chain::Model::has_forward_dynamics);
static_assert(eomgen_models::cart_pole::Model::has_forward_dynamics);
static_assert(eomgen_models::double_pendulum::Model::has_forward_dynamics);
static_assert(eomgen_models::spring_mass_damper::Model::has_forward_dynamics);
static_assert(!eomgen_models::cartesian_pendulum::Model::has_forward_dynamics);
static_assert(!eomgen_models::rolling_coin::Model::has_forward_dynamics);
static_assert(!eomgen_models::four_bar::Model::has_forward_dynamics);
static_assert(!eomgen_models::planar_3rrr::Model::has_forward_dynamics);
static_assert(!eomgen_models::two_wheeled_robot::Model::has_forward_dynamics);

TEST(GeneratedModel, EveryModelRunsInDoubleAndFloatFromAStrictlyCompiledUnit) {
  EXPECT_TRUE(generated_models_failing_in_double_or_float().empty());
}

#define GENERATED_MODEL_TEST(name)                                                  \
  TEST(GeneratedModel, name##MatchesSymbolicEquations) {                           \
    eomgen::testing::check_against_symbolic<eomgen_models::name::Model>();                          \
  }

GENERATED_MODEL_TEST(simple_pendulum)
GENERATED_MODEL_TEST(double_pendulum)
GENERATED_MODEL_TEST(cart_pole)
GENERATED_MODEL_TEST(spherical_pendulum)
GENERATED_MODEL_TEST(heavy_top)
GENERATED_MODEL_TEST(quaternion_rigid_body)
GENERATED_MODEL_TEST(cartesian_pendulum)
GENERATED_MODEL_TEST(knife_edge)
GENERATED_MODEL_TEST(rolling_coin)
GENERATED_MODEL_TEST(bead_on_hoop)
GENERATED_MODEL_TEST(spring_mass_damper)
GENERATED_MODEL_TEST(spacecraft_panel)
GENERATED_MODEL_TEST(planar_chain)
GENERATED_MODEL_TEST(universal_chain)
GENERATED_MODEL_TEST(whipple_bicycle)
GENERATED_MODEL_TEST(four_bar)
GENERATED_MODEL_TEST(planar_3rrr)
GENERATED_MODEL_TEST(two_wheeled_robot)

}  // namespace
