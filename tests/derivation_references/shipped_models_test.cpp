// The shipped model files (models/*.eom): every one loads and derives, has a symmetric
// positive semi-definite mass matrix (definite on the constraint), and the classic ones give
// the same equations as the system built through the C++ API, the hand closed forms and the
// course notes' results (equation A.14 / Example A.20, Example 3.1, section 3.7.0.2).
//
// Conventions (docs/conventions.md): v_b = C_ba v_a; C3(x) = [[c, s, 0], [-s, c, 0], [0, 0, 1]];
// Euler i-j-k: C_ba = Ck(t3) Cj(t2) Ci(t1); M(q) qdd = F(q, qd, t, u) + Xi^T lambda.
#include <Eigen/Dense>
#include <ginac/ginac.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "eomgen/derivation/equations_of_motion.hpp"
#include "eomgen/mechanics/mechanical_system.hpp"
#include "eomgen/derivation/model_equations.hpp"
#include "eomgen/language/model_file.hpp"
#include "eomgen/mechanics/rotation.hpp"
#include "eomgen/symbolic/simplify.hpp"
#include "support/model_lookup.hpp"
#include "support/symbolic_checks.hpp"
#include "support/source_dir.hpp"

namespace {

namespace fs = std::filesystem;
using eomgen::EquationsOfMotion;
using eomgen::FrameId;
using eomgen::MechanicalSystem;
using eomgen::Model;
using eomgen::PointId;
using eomgen::Rotation;
using eomgen::Subexpressions;
using eomgen::Vector;
using eomgen::testing::equal_after_simplification;
using eomgen::testing::find_output;
using eomgen::testing::matrices_near_relative;
using eomgen::testing::near_relative;
using eomgen::testing::symbol_named;
using eomgen::testing::value_at;
using GiNaC::cos;
using GiNaC::ex;
using GiNaC::exmap;
using GiNaC::matrix;
using GiNaC::pow;
using GiNaC::sin;

// The repository's models/ folder.
fs::path models_dir() { return eomgen::testing::source_dir() / "models"; }

fs::path model_path(const std::string& name) { return models_dir() / (name + ".eom"); }

std::vector<fs::path> shipped_models() {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(models_dir()))
    if (entry.is_regular_file() && entry.path().extension() == ".eom") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

Model load(const std::string& name, const std::map<std::string, double>& overrides = {}) {
  return eomgen::load_model(model_path(name).string(), overrides);
}

// ---------------------------------------------------------------------------------------------
// Numeric evaluation. A state is given by name so that two systems with their own symbols (the
// parsed model and the one built through the API) can be compared at the same point.

using NamedState = std::map<std::string, double>;

/// Coordinates and rates in [-1.5, 1.5], parameters in [0.5, 2] (not the defaults, so that a
/// swapped parameter shows), inputs in [-2, 2], t in [0, 3].
NamedState random_named_state(const MechanicalSystem& s, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> angle(-1.5, 1.5), positive(0.5, 2.0), input(-2.0, 2.0), time(0.0, 3.0);
  NamedState v;
  v["t"] = time(rng);
  for (const auto& c : s.variables().coordinates()) {
    v[c.name] = angle(rng);
    v[c.name + "_dot"] = angle(rng);
  }
  for (const auto& p : s.variables().parameters()) v[p.name] = positive(rng);
  for (const auto& u : s.variables().inputs()) v[u.name] = input(rng);
  return v;
}

exmap substitution(const MechanicalSystem& s, const NamedState& v) {
  exmap m;
  m[s.variables().time()] = v.at("t");
  for (const auto& c : s.variables().coordinates()) {
    m[c.q] = v.at(c.name);
    m[c.qd] = v.at(c.name + "_dot");
  }
  for (const auto& p : s.variables().parameters()) m[p.symbol] = v.at(p.name);
  for (const auto& u : s.variables().inputs()) m[u.symbol] = v.at(u.name);
  return m;
}

// ---------------------------------------------------------------------------------------------
// Every shipped model.

TEST(ShippedModels, DirectoryHoldsTheEighteenDocumentedModels) {
  std::vector<std::string> names;
  for (const auto& f : shipped_models()) names.push_back(f.stem().string());
  for (const char* expected :
       {"simple_pendulum", "double_pendulum", "cart_pole", "spherical_pendulum", "heavy_top", "quaternion_rigid_body",
        "cartesian_pendulum", "knife_edge", "rolling_coin", "bead_on_hoop", "spring_mass_damper", "spacecraft_panel",
        "planar_chain", "universal_chain", "whipple_bicycle", "four_bar", "planar_3rrr", "two_wheeled_robot"})
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected << ".eom is missing";
  EXPECT_EQ(names.size(), 18u) << "README.md counts the shipped models";
}

TEST(ShippedModels, EveryModelOpensWithACommentBlockAndNamesItselfAfterItsFile) {
  const auto files = shipped_models();
  ASSERT_FALSE(files.empty()) << "no .eom files in " << models_dir();
  for (const auto& file : files) {
    SCOPED_TRACE(file.string());
    std::ifstream in(file);
    std::string first;
    std::getline(in, first);
    EXPECT_EQ(first.rfind("#", 0), 0u) << "first line: " << first;
    const Model m = eomgen::load_model(file.string());
    EXPECT_EQ(m.name, file.stem().string());
    EXPECT_FALSE(m.description.empty());
    EXPECT_FALSE(m.outputs.empty());
  }
}

TEST(ShippedModels, EveryModelLoadsAndDerivesWithConsistentShapes) {
  for (const auto& file : shipped_models()) {
    SCOPED_TRACE(file.string());
    const Model m = eomgen::load_model(file.string());
    const EquationsOfMotion eom = eomgen::derive_equations(m.system);
    const std::size_t n = m.system.variables().coordinate_count();
    ASSERT_GT(n, 0u);
    EXPECT_EQ(eom.coordinate_count, n);
    EXPECT_EQ(eom.mass_matrix.rows(), n);
    EXPECT_EQ(eom.mass_matrix.cols(), n);
    EXPECT_EQ(eom.forcing.rows(), n);
    EXPECT_EQ(eom.constraint_count, m.system.constraints().size());
    EXPECT_EQ(eom.constraint_jacobian.rows(), eom.constraint_count);
    EXPECT_EQ(m.coordinate_locations.size(), n);
  }
}

TEST(ShippedModels, OnlyTheNonholonomicModelsDeclareIndependentSpeeds) {
  // the holonomic ones leave the choice to the runtime's QR null space
  const std::map<std::string, std::vector<std::size_t>> declared = {{"knife_edge", {0, 2}},        // x, theta
                                                                    {"rolling_coin", {2, 3, 4}},   // psi, theta, phi
                                                                    {"whipple_bicycle", {3, 6, 5}}};  // phi, delta, theta_r
  for (const auto& file : shipped_models()) {
    SCOPED_TRACE(file.string());
    const Model m = eomgen::load_model(file.string());
    const auto it = declared.find(file.stem().string());
    EXPECT_EQ(m.independent_speeds, it == declared.end() ? std::vector<std::size_t>{} : it->second);
  }
}

TEST(ShippedModels, MassMatrixIsSymmetricPositiveSemiDefiniteAndDefiniteOnTheConstraints) {
  for (const auto& file : shipped_models()) {
    SCOPED_TRACE(file.string());
    const Model m = eomgen::load_model(file.string());
    const EquationsOfMotion eom = eomgen::derive_equations(m.system);
    for (unsigned seed : {3u, 17u, 29u}) {
      const exmap all = eom.subexpressions.evaluate_all(eomgen::testing::random_state(m.system, seed));
      const Eigen::MatrixXd M = value_at(eom.mass_matrix, all);
      const double scale = M.norm();
      ASSERT_GT(scale, 0.0);
      EXPECT_LE((M - M.transpose()).norm(), 1e-12 * scale) << "seed " << seed;
      const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(M);
      EXPECT_GE(eig.eigenvalues().minCoeff(), -1e-12 * scale) << "seed " << seed << "\n" << M;
      // restricted to the admissible rates (Xi qd = 0) the mass matrix is definite
      Eigen::MatrixXd upsilon = Eigen::MatrixXd::Identity(M.rows(), M.cols());
      if (eom.constraint_count > 0) {
        const Eigen::MatrixXd xi = value_at(eom.constraint_jacobian, all);
        const Eigen::JacobiSVD<Eigen::MatrixXd> svd(xi, Eigen::ComputeFullV);
        // independent rows but for the redundant ones the model notes (two wheels on one axle)
        ASSERT_EQ(static_cast<std::size_t>(svd.rank()) + m.redundant_constraints.size(), eom.constraint_count)
            << "dependent constraints";
        upsilon = svd.matrixV().rightCols(M.cols() - svd.rank());
      }
      const Eigen::MatrixXd reduced = upsilon.transpose() * M * upsilon;
      const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> reduced_eig(reduced);
      EXPECT_GT(reduced_eig.eigenvalues().minCoeff(), 1e-9 * scale) << "seed " << seed << "\n" << reduced;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Parsed model == the same system built through the C++ API (independently: other frame chains
// where it is natural), compared at random states with random parameter values.

void expect_same_equations(const MechanicalSystem& parsed, const MechanicalSystem& api) {
  std::vector<std::string> parsed_names, api_names;
  for (const auto& c : parsed.variables().coordinates()) parsed_names.push_back(c.name);
  for (const auto& c : api.variables().coordinates()) api_names.push_back(c.name);
  ASSERT_EQ(parsed_names, api_names) << "coordinates differ (names or order)";
  ASSERT_EQ(parsed.variables().parameters().size(), api.variables().parameters().size());
  ASSERT_EQ(parsed.variables().inputs().size(), api.variables().inputs().size());
  ASSERT_EQ(parsed.constraints().size(), api.constraints().size());
  const EquationsOfMotion a = eomgen::derive_equations(parsed);
  const EquationsOfMotion b = eomgen::derive_equations(api);
  for (unsigned seed : {5u, 8u, 13u, 21u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const NamedState state = random_named_state(api, seed);
    const exmap pa = a.subexpressions.evaluate_all(substitution(parsed, state));
    const exmap pb = b.subexpressions.evaluate_all(substitution(api, state));
    EXPECT_TRUE(matrices_near_relative(value_at(a.mass_matrix, pa), value_at(b.mass_matrix, pb), 1e-12)) << "M";
    EXPECT_TRUE(matrices_near_relative(value_at(a.forcing, pa), value_at(b.forcing, pb), 1e-12)) << "F";
    EXPECT_TRUE(near_relative(value_at(a.kinetic_energy, pa), value_at(b.kinetic_energy, pb), 1e-12)) << "T";
    EXPECT_TRUE(near_relative(value_at(a.potential_energy, pa), value_at(b.potential_energy, pb), 1e-12)) << "V";
  }
}

matrix diag3(const ex& a, const ex& b, const ex& c) { return matrix{{a, 0, 0}, {0, b, 0}, {0, 0, c}}; }

TEST(ShippedDoublePendulum, EqualsTheSystemBuiltThroughTheApi) {
  // built with absolute frames and positions written in a: rod 2 at angle theta1 + theta2
  MechanicalSystem s;
  const auto th1 = s.add_coordinate("theta1"), th2 = s.add_coordinate("theta2");
  const ex m1 = s.add_parameter("m1", 1), m2 = s.add_parameter("m2", 1);
  const ex l1 = s.add_parameter("l1", 1), l2 = s.add_parameter("l2", 1);
  const ex g = s.add_parameter("g", 9.81);
  const FrameId a = s.inertial_frame();
  const PointId p1 = s.add_point("p1", s.origin(), Vector(a, l1 * sin(th1.q), -l1 * cos(th1.q), 0));
  const FrameId c = s.add_frame("c", a, Rotation::principal(3, th1.q + th2.q));
  const PointId p2 = s.add_point("p2", p1, Vector(c, 0, -l2, 0));
  s.add_particle("bob1", m1, p1);
  s.add_particle("bob2", m2, p2);
  s.set_gravity(Vector(a, 0, -g, 0));
  expect_same_equations(load("double_pendulum").system, s);
}

TEST(ShippedCartPole, EqualsTheSystemBuiltThroughTheApi) {
  MechanicalSystem s;
  const auto x = s.add_coordinate("x"), th = s.add_coordinate("theta");
  const ex mc = s.add_parameter("mc", 1), mp = s.add_parameter("mp", 1), l = s.add_parameter("l", 1);
  const ex rp = s.add_parameter("rp", 0.01), g = s.add_parameter("g", 9.81);
  const ex u = s.add_input("u");
  const FrameId a = s.inertial_frame();
  const FrameId b = s.add_frame("b", a, Rotation::principal(3, th.q));
  const PointId hinge = s.add_point("hinge", s.origin(), Vector(a, x.q, 0, 0));
  // the pole's centre written in a: l/2 b.2 = l/2 [-sin(theta), cos(theta), 0]_a
  const PointId centre = s.add_point("centre", hinge, Vector(a, -l / 2 * sin(th.q), l / 2 * cos(th.q), 0));
  const ex transverse = mp * (l * l / 12 + rp * rp / 4);
  s.add_particle("cart", mc, hinge);
  s.add_rigid_body("pole", mp, centre, b, diag3(transverse, mp * rp * rp / 2, transverse));
  s.set_gravity(Vector(a, 0, -g, 0));
  s.add_force(hinge, Vector(a, u, 0, 0));
  expect_same_equations(load("cart_pole").system, s);
}

TEST(ShippedHeavyTop, EqualsTheSystemBuiltThroughTheApiWithThreePrincipalRotations) {
  // C_ba = C3(phi) C1(theta) C3(psi) as three chained principal rotations
  MechanicalSystem s;
  const auto psi = s.add_coordinate("psi"), th = s.add_coordinate("theta"), phi = s.add_coordinate("phi");
  const ex m = s.add_parameter("m", 1), l = s.add_parameter("l", 1);
  const ex J1 = s.add_parameter("J1", 1), J3 = s.add_parameter("J3", 1), g = s.add_parameter("g", 9.81);
  const FrameId a = s.inertial_frame();
  const FrameId n1 = s.add_frame("n1", a, Rotation::principal(3, psi.q));
  const FrameId n2 = s.add_frame("n2", n1, Rotation::principal(1, th.q));
  const FrameId b = s.add_frame("b", n2, Rotation::principal(3, phi.q));
  // b.3 = n2.3 (the third rotation is about it)
  const PointId centre = s.add_point("centre", s.origin(), Vector(n2, 0, 0, l));
  s.add_rigid_body("top", m, centre, b, diag3(J1, J1, J3));
  s.set_gravity(Vector(a, 0, 0, -g));
  expect_same_equations(load("heavy_top").system, s);
}

TEST(ShippedSimplePendulum, MatchesTheHandClosedForm) {
  const Model md = load("simple_pendulum");
  const auto& s = md.system;
  const EquationsOfMotion eom = eomgen::derive_equations(s);
  const ex m = symbol_named(s, "m"), l = symbol_named(s, "l"), g = symbol_named(s, "g"), th = symbol_named(s, "theta");
  EXPECT_TRUE(equal_after_simplification(eom.subexpressions.expand(eom.mass_matrix(0, 0)), m * l * l));
  EXPECT_TRUE(equal_after_simplification(eom.subexpressions.expand(eom.forcing(0, 0)), -m * g * l * sin(th)));
}

// ---------------------------------------------------------------------------------------------
// Chains: the const n sets the number of links.

TEST(ShippedPlanarChain, ConstNSetsTheNumberOfLinks) {
  EXPECT_EQ(load("planar_chain").system.variables().coordinate_count(), 4u);
  for (double n : {2.0, 8.0}) {
    const Model m = load("planar_chain", {{"n", n}});
    EXPECT_EQ(m.system.variables().coordinate_count(), static_cast<std::size_t>(n));
    EXPECT_EQ(m.system.rigid_bodies().size(), static_cast<std::size_t>(n));
    const EquationsOfMotion eom = eomgen::derive_equations(m.system);
    EXPECT_EQ(eom.mass_matrix.rows(), static_cast<unsigned>(n));
  }
}

TEST(ShippedPlanarChain, TwoLinkChainMatchesTheCompoundDoublePendulumClosedForm) {
  // two uniform rods (mass m, length l, radius rd), relative angles, hanging at rest:
  //   M11 = m (5/3 l^2 + l^2 cos q2 + rd^2/2), M12 = m (l^2/3 + l^2/2 cos q2 + rd^2/4),
  //   M22 = m (l^2/3 + rd^2/4); at rest F1 = -m g l (3/2 sin q1 + 1/2 sin(q1 + q2)),
  //   F2 = -1/2 m g l sin(q1 + q2).
  const Model md = load("planar_chain", {{"n", 2}});
  const auto& s = md.system;
  const EquationsOfMotion eom = eomgen::derive_equations(s);
  const auto& z = eom.subexpressions;
  const ex m = symbol_named(s, "m"), l = symbol_named(s, "l"), rd = symbol_named(s, "rd"), g = symbol_named(s, "g");
  const ex q1 = symbol_named(s, "q1"), q2 = symbol_named(s, "q2");
  EXPECT_TRUE(equal_after_simplification(z.expand(eom.mass_matrix(0, 0)),
                                         m * (ex(5) / 3 * l * l + l * l * cos(q2) + rd * rd / 2)));
  EXPECT_TRUE(
      equal_after_simplification(z.expand(eom.mass_matrix(0, 1)), m * (l * l / 3 + l * l / 2 * cos(q2) + rd * rd / 4)));
  EXPECT_TRUE(equal_after_simplification(z.expand(eom.mass_matrix(1, 1)), m * (l * l / 3 + rd * rd / 4)));
  const ex F1 = s.variables().at_rest(z.expand(eom.forcing(0, 0)));
  const ex F2 = s.variables().at_rest(z.expand(eom.forcing(1, 0)));
  EXPECT_TRUE(equal_after_simplification(
      F1, -m * g * l * (ex(3) / 2 * sin(q1) + sin(q1) * cos(q2) / 2 + cos(q1) * sin(q2) / 2)));
  EXPECT_TRUE(equal_after_simplification(F2, -m * g * l * (sin(q1) * cos(q2) + cos(q1) * sin(q2)) / 2));
}

TEST(ShippedUniversalChain, HasTwoJointAnglesPerBody) {
  for (double n : {1.0, 3.0, 5.0}) {
    const Model m = n == 3.0 ? load("universal_chain") : load("universal_chain", {{"n", n}});
    EXPECT_EQ(m.system.variables().coordinate_count(), static_cast<std::size_t>(2 * n));
    EXPECT_EQ(m.system.rigid_bodies().size(), static_cast<std::size_t>(n));
  }
}

// ---------------------------------------------------------------------------------------------
// The course notes.

TEST(ShippedSpringMassDamper, ReproducesEquationA14Exactly) {
  // m q'' + d q' + (k1 + k2 q^2) q = 0  =>  M = m,  F = -d q' - (k1 + k2 q^2) q
  const Model md = load("spring_mass_damper");
  const auto& s = md.system;
  const EquationsOfMotion eom = eomgen::derive_equations(s);
  const auto& z = eom.subexpressions;
  const ex m = symbol_named(s, "m"), d = symbol_named(s, "d"), k1 = symbol_named(s, "k1"), k2 = symbol_named(s, "k2");
  const ex q = symbol_named(s, "q"), qd = symbol_named(s, "q_dot");
  ASSERT_EQ(eom.coordinate_count, 1u);
  EXPECT_EQ(eom.constraint_count, 0u);
  EXPECT_TRUE(s.variables().inputs().empty()) << "(A.14) has no input";
  EXPECT_TRUE((GiNaC::expand(z.expand(eom.mass_matrix(0, 0)) - m)).is_zero());
  EXPECT_TRUE((GiNaC::expand(z.expand(eom.forcing(0, 0)) - (-d * qd - (k1 + k2 * q * q) * q))).is_zero())
      << z.expand(eom.forcing(0, 0));
  // the Lyapunov function of Example A.21 is T + V
  EXPECT_TRUE((GiNaC::expand(z.expand(eom.kinetic_energy + eom.potential_energy) -
                             (m * qd * qd / 2 + k1 * q * q / 2 + k2 * pow(q, 4) / 4)))
                  .is_zero());
}

TEST(ShippedSpringMassDamper, LinearizesAboutTheOriginAsInExampleA20) {
  // x = [q, q']: f = [x2, F/M]; at the only real equilibrium x = 0,
  // A = [[0, 1], [-k1/m, -d/m]].
  const Model md = load("spring_mass_damper");
  const auto& s = md.system;
  const EquationsOfMotion eom = eomgen::derive_equations(s);
  const ex m = symbol_named(s, "m"), d = symbol_named(s, "d"), k1 = symbol_named(s, "k1");
  const ex q = symbol_named(s, "q"), qd = symbol_named(s, "q_dot");
  const ex f2 = eom.subexpressions.expand(eom.forcing(0, 0)) / eom.subexpressions.expand(eom.mass_matrix(0, 0));
  const exmap origin{{q, 0}, {qd, 0}};
  EXPECT_TRUE(f2.subs(origin).is_zero()) << "x = 0 is an equilibrium";
  EXPECT_TRUE(equal_after_simplification(f2.diff(GiNaC::ex_to<GiNaC::symbol>(q)).subs(origin), -k1 / m));
  EXPECT_TRUE(equal_after_simplification(f2.diff(GiNaC::ex_to<GiNaC::symbol>(qd)).subs(origin), -d / m));
}

TEST(ShippedSpacecraftPanel, TipVelocityOutputEqualsExample31) {
  //   v^{ew/a} = F_p^T [theta' l_ef - cos(theta) gamma' l_fh, sin(theta) gamma' l_ef,
  //                     -sin(theta) gamma' l_fh]
  const Model md = load("spacecraft_panel");
  const auto& s = md.system;
  const ex th = symbol_named(s, "theta"), thd = symbol_named(s, "theta_dot"), gd = symbol_named(s, "gamma_dot");
  const ex lef = symbol_named(s, "l_ef"), lfh = symbol_named(s, "l_fh");
  const eomgen::Output* v = find_output(md, "tip_velocity");
  ASSERT_NE(v, nullptr);
  ASSERT_EQ(v->components.size(), 3u);
  EXPECT_TRUE(equal_after_simplification(v->components[0], thd * lef - cos(th) * gd * lfh)) << v->components[0];
  EXPECT_TRUE(equal_after_simplification(v->components[1], sin(th) * gd * lef)) << v->components[1];
  EXPECT_TRUE(equal_after_simplification(v->components[2], -sin(th) * gd * lfh)) << v->components[2];
  // and the panel's angular velocity of the example, omega_p^pa = [-sin(theta) gamma', theta', cos(theta) gamma']
  const eomgen::Output* w = find_output(md, "omega_panel");
  ASSERT_NE(w, nullptr);
  EXPECT_TRUE(equal_after_simplification(w->components[0], -sin(th) * gd));
  EXPECT_TRUE(equal_after_simplification(w->components[1], thd));
  EXPECT_TRUE(equal_after_simplification(w->components[2], cos(th) * gd));
}

TEST(ShippedBeadOnHoop, ForcingHasTheCentrifugalTerm) {
  // m R^2 theta'' = m R^2 Omega^2 sin(theta) cos(theta) - m g R sin(theta)
  const Model md = load("bead_on_hoop");
  const auto& s = md.system;
  const EquationsOfMotion eom = eomgen::derive_equations(s);
  const auto& z = eom.subexpressions;
  const ex m = symbol_named(s, "m"), R = symbol_named(s, "R"), W = symbol_named(s, "Omega"), g = symbol_named(s, "g");
  const ex th = symbol_named(s, "theta");
  EXPECT_TRUE(equal_after_simplification(z.expand(eom.mass_matrix(0, 0)), m * R * R));
  EXPECT_TRUE(equal_after_simplification(z.expand(eom.forcing(0, 0)),
                                         m * R * R * W * W * sin(th) * cos(th) - m * g * R * sin(th)))
      << z.expand(eom.forcing(0, 0));
}

TEST(ShippedRollingCoin, RollConstraintsGiveTheNotesCentreRates) {
  // section 3.7.0.2: x' = r (c_th c_psi th' + s_psi phi' - s_psi s_th psi'),
  //                  y' = r (c_th s_psi th' - c_psi phi' + c_psi s_th psi'),  z' = -r s_th th'
  const Model md = load("rolling_coin");
  const auto& s = md.system;
  const EquationsOfMotion eom = eomgen::derive_equations(s);
  ASSERT_EQ(eom.constraint_count, 2u);
  for (const auto& c : s.constraints()) EXPECT_EQ(c.kind, eomgen::Constraint::Kind::nonholonomic) << c.name;
  const std::vector<std::string> names = {"x", "y", "psi", "theta", "phi"};
  ASSERT_EQ(s.variables().coordinate_count(), names.size());
  for (std::size_t k = 0; k < names.size(); ++k) EXPECT_EQ(s.variables().coordinates()[k].name, names[k]);

  for (unsigned seed : {2u, 7u, 19u, 31u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const NamedState v = random_named_state(s, seed);
    const exmap all = eom.subexpressions.evaluate_all(substitution(s, v));
    const Eigen::MatrixXd xi = value_at(eom.constraint_jacobian, all);
    EXPECT_LE(value_at(eom.constraint_rate_term, all).norm(), 1e-14) << "scleronomic";
    // solve Xi qd = 0 for (x', y') given the angle rates
    const Eigen::Matrix2d B = xi.leftCols(2);
    ASSERT_GT(std::fabs(B.determinant()), 1e-6) << "the centre rates must follow from the constraints";
    const Eigen::Vector3d angle_rates(v.at("psi_dot"), v.at("theta_dot"), v.at("phi_dot"));
    const Eigen::Vector2d centre_rates = -B.inverse() * (xi.rightCols(3) * angle_rates);
    const double r = v.at("r"), cps = std::cos(v.at("psi")), sps = std::sin(v.at("psi"));
    const double cth = std::cos(v.at("theta")), sth = std::sin(v.at("theta"));
    const double psd = v.at("psi_dot"), thd = v.at("theta_dot"), phd = v.at("phi_dot");
    const Eigen::Vector2d notes(r * (cth * cps * thd + sps * phd - sps * sth * psd),
                                r * (cth * sps * thd - cps * phd + cps * sth * psd));
    EXPECT_TRUE(matrices_near_relative(centre_rates, notes, 1e-12));
    // the vertical rate of the centre follows from its height r cos(theta)
    const eomgen::Output* vz = find_output(md, "centre_velocity");
    ASSERT_NE(vz, nullptr);
    EXPECT_TRUE(near_relative(value_at(vz->components[2], all), -sth * r * thd, 1e-12));
  }
}

// ---------------------------------------------------------------------------------------------
// Constraints of the other constrained models.

TEST(ShippedCartesianPendulum, LengthConstraintIsHolonomicWithGradientTwoXTwoY) {
  const Model md = load("cartesian_pendulum");
  const auto& s = md.system;
  const EquationsOfMotion eom = eomgen::derive_equations(s);
  ASSERT_EQ(eom.constraint_count, 1u);
  EXPECT_EQ(s.constraints()[0].kind, eomgen::Constraint::Kind::holonomic);
  const ex x = symbol_named(s, "x"), y = symbol_named(s, "y"), l = symbol_named(s, "l");
  EXPECT_TRUE(equal_after_simplification(eom.subexpressions.expand(eom.constraint_jacobian(0, 0)), 2 * x));
  EXPECT_TRUE(equal_after_simplification(eom.subexpressions.expand(eom.constraint_jacobian(0, 1)), 2 * y));
  EXPECT_TRUE(
      equal_after_simplification(eom.subexpressions.expand(eom.holonomic_residuals(0, 0)), x * x + y * y - l * l));
}

TEST(ShippedKnifeEdge, NoSideSlipIsOneNonholonomicConstraint) {
  const Model md = load("knife_edge");
  const auto& s = md.system;
  const EquationsOfMotion eom = eomgen::derive_equations(s);
  ASSERT_EQ(eom.constraint_count, 1u);
  EXPECT_EQ(s.constraints()[0].kind, eomgen::Constraint::Kind::nonholonomic);
  const ex th = symbol_named(s, "theta");
  EXPECT_TRUE(equal_after_simplification(eom.subexpressions.expand(eom.constraint_jacobian(0, 0)), -sin(th)));
  EXPECT_TRUE(equal_after_simplification(eom.subexpressions.expand(eom.constraint_jacobian(0, 1)), cos(th)));
  EXPECT_TRUE(equal_after_simplification(eom.subexpressions.expand(eom.constraint_jacobian(0, 2)), 0));
}

TEST(ShippedQuaternionRigidBody, UnitNormConstraintAndTorqueFreeMotionAlongTheQuaternion) {
  const Model md = load("quaternion_rigid_body");
  const auto& s = md.system;
  const EquationsOfMotion eom = eomgen::derive_equations(s);
  ASSERT_EQ(eom.constraint_count, 1u);
  EXPECT_EQ(s.constraints()[0].kind, eomgen::Constraint::Kind::holonomic);
  const std::vector<std::string> names = {"e1", "e2", "e3", "eta"};
  for (std::size_t k = 0; k < names.size(); ++k) {
    EXPECT_EQ(s.variables().coordinates()[k].name, names[k]);
    EXPECT_TRUE(equal_after_simplification(eom.subexpressions.expand(eom.constraint_jacobian(0, k)),
                                           2 * symbol_named(s, names[k])));
  }
  EXPECT_EQ(s.variables().inputs().size(), 3u);
  // the quaternion itself spans the null space of M: M q = 0 (omega does not see d|q|/dt)
  for (unsigned seed : {4u, 9u}) {
    const NamedState v = random_named_state(s, seed);
    const exmap all = eom.subexpressions.evaluate_all(substitution(s, v));
    const Eigen::MatrixXd M = value_at(eom.mass_matrix, all);
    const Eigen::Vector4d q(v.at("e1"), v.at("e2"), v.at("e3"), v.at("eta"));
    EXPECT_LE((M * q).norm(), 1e-12 * M.norm() * q.norm());
  }
}

}  // namespace
