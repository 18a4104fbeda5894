#pragma once
// A generated model against the symbolic equations it came from, at random parameters and
// states, to 1e-12 relative (M and F against Kane's closed form whichever form was emitted).
#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "eomgen/derivation/equations_of_motion.hpp"
#include "eomgen/derivation/model_equations.hpp"
#include "eomgen/language/model_file.hpp"
#include "support/numeric_checks.hpp"
#include "support/source_dir.hpp"

namespace eomgen::testing {

// the symbolic value as a double; NaN where it is not real (acos(x) with |x| > 1 at random
// parameters), which is what the generated C++ gives there too
inline double value(const GiNaC::ex& e, const GiNaC::exmap& at) {
  const GiNaC::ex v = e.subs(at, GiNaC::subs_options::no_pattern).evalf();
  EXPECT_TRUE(GiNaC::is_a<GiNaC::numeric>(v)) << v;
  const GiNaC::numeric n = GiNaC::ex_to<GiNaC::numeric>(v);
  return n.is_real() ? n.to_double() : std::nan("");
}

// NaN where the symbolic value is NaN (matrices_near_relative counts NaN against NaN as agreeing)
template <class Matrix>
void expect_matches(const Matrix& generated, const GiNaC::matrix& symbolic, const GiNaC::exmap& at, const char* what) {
  Eigen::MatrixXd expected(symbolic.rows(), symbolic.cols());
  for (unsigned i = 0; i < symbolic.rows(); ++i)
    for (unsigned j = 0; j < symbolic.cols(); ++j) expected(i, j) = value(symbolic(i, j), at);
  EXPECT_TRUE(eomgen::testing::matrices_near_relative(generated, expected, 1e-12)) << what;
}

/// Every function of a generated model against the symbolic equations of the shipped model it
/// was generated from (with the same `defines`; models/<name>.eom unless `path` names another
/// file, a robot's URDF say), at random parameters and states.
template <class Model>
void check_against_symbolic(const std::map<std::string, double>& defines = {}, std::string path = {}) {
  if (path.empty()) path = eomgen::testing::shipped_model_path(Model::name);
  const eomgen::Model model = eomgen::load_model(path, defines);
  const eomgen::EquationsOfMotion eom = eomgen::derive_equations(model.system);
  const eomgen::Variables& vars = model.system.variables();
  ASSERT_EQ(static_cast<std::size_t>(Model::nq), vars.coordinate_count());
  // holonomic_rows picks, in order, the rows of Xi that come from holonomic constraints
  std::vector<int> holonomic;
  for (std::size_t i = 0; i < model.system.constraints().size(); ++i)
    if (model.system.constraints()[i].kind == eomgen::Constraint::Kind::holonomic) holonomic.push_back(static_cast<int>(i));
  EXPECT_EQ(std::vector<int>(Model::holonomic_rows.begin(), Model::holonomic_rows.end()), holonomic);
  // independent_speeds as declared in the model: none, or one per degree of freedom
  const std::vector<int> independent(Model::independent_speeds.begin(), Model::independent_speeds.end());
  EXPECT_EQ(independent, std::vector<int>(model.independent_speeds.begin(), model.independent_speeds.end()));
  EXPECT_TRUE(Model::ni == 0 || Model::ni == Model::nq - Model::nc) << Model::ni;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(-1.2, 1.2), positive(0.5, 2.0);
  for (int trial = 0; trial < 4; ++trial) {
    // random parameters too, so no default value hides a wrong coefficient
    typename Model::template Parameters<double> p;
    GiNaC::exmap at;
    const auto fields = p.fields();
    for (std::size_t k = 0; k < fields.size(); ++k) {
      *fields[k] = Model::parameter_defaults[k] * positive(rng);
      at[vars.parameters()[k].symbol] = *fields[k];
    }
    const double t = positive(rng);
    at[vars.time()] = t;
    typename Model::template Vector<double> q, qd;
    typename Model::template Inputs<double> u;
    for (int k = 0; k < Model::nq; ++k) {
      q(k) = uniform(rng);
      qd(k) = uniform(rng);
      at[vars.coordinates()[static_cast<std::size_t>(k)].q] = q(k);
      at[vars.coordinates()[static_cast<std::size_t>(k)].qd] = qd(k);
    }
    for (int k = 0; k < Model::nu; ++k) {
      u(k) = uniform(rng);
      at[vars.inputs()[static_cast<std::size_t>(k)].symbol] = u(k);
    }
    const GiNaC::exmap all = eom.subexpressions.evaluate_all(at);
    typename Model::template MassMatrix<double> M, M2;
    typename Model::template Vector<double> F, F2;
    Model::mass_matrix(t, q, p, M);
    Model::forcing(t, q, qd, u, p, F);
    Model::mass_matrix_and_forcing(t, q, qd, u, p, M2, F2);
    expect_matches(M, eom.mass_matrix, all, "M");
    expect_matches(F, eom.forcing, all, "F");
    // the combined function shares differently, so only rounding may differ
    EXPECT_LE((M - M2).norm(), 1e-13 * (1 + M.norm()));
    EXPECT_LE((F - F2).norm(), 1e-13 * (1 + F.norm()));
    // the articulated-body forward dynamics against M^-1 F of the generated M and F
    if constexpr (Model::has_forward_dynamics) {
      typename Model::template Vector<double> qdd;
      EXPECT_TRUE(Model::forward_dynamics(t, q, qd, u, p, qdd));
      const typename Model::template Vector<double> expected = M.llt().solve(F);
      EXPECT_TRUE(eomgen::testing::matrices_near_relative(qdd, expected, 1e-11)) << "forward_dynamics";
    }
    typename Model::template ConstraintJacobian<double> Xi;
    typename Model::template ConstraintVector<double> Xi_t, b;
    typename Model::template HolonomicVector<double> phi;
    Model::constraint_jacobian(t, q, p, Xi);
    Model::constraint_rate_term(t, q, p, Xi_t);
    Model::constraint_acceleration_term(t, q, qd, p, b);
    Model::holonomic_residuals(t, q, p, phi);
    expect_matches(Xi, eom.constraint_jacobian, all, "Xi");
    expect_matches(Xi_t, eom.constraint_rate_term, all, "Xi_t");
    expect_matches(b, eom.constraint_acceleration_term, all, "constraint_acceleration_term");
    expect_matches(phi, eom.holonomic_residuals, all, "phi");
    // holonomic_rows: row holonomic_rows[i] of Xi is the gradient of phi[i]
    for (int i = 0; i < Model::nh; ++i) {
      const int row = Model::holonomic_rows[static_cast<std::size_t>(i)];
      ASSERT_GE(row, 0);
      ASSERT_LT(row, Model::nc);
      GiNaC::matrix gradient(1, static_cast<unsigned>(Model::nq));
      for (unsigned k = 0; k < static_cast<unsigned>(Model::nq); ++k)
        // through the intermediates phi is written with (the bicycle's contact geometry)
        gradient(0, k) = eom.subexpressions.expand(eom.holonomic_residuals(static_cast<unsigned>(i), 0))
                             .diff(vars.coordinates()[k].q);
      const Eigen::MatrixXd generated_row = Xi.row(row);
      expect_matches(generated_row, gradient, all, "holonomic_rows");
    }
    Eigen::Matrix<double, 1, 1> T, V;
    T(0) = Model::kinetic_energy(t, q, qd, p);
    V(0) = Model::potential_energy(t, q, p);
    expect_matches(T, GiNaC::matrix(1, 1, GiNaC::lst{eom.kinetic_energy}), all, "T");
    expect_matches(V, GiNaC::matrix(1, 1, GiNaC::lst{eom.potential_energy}), all, "V");
    typename Model::template OutputVector<double> y;
    Model::outputs(t, q, qd, u, p, y);
    GiNaC::matrix outputs(static_cast<unsigned>(Model::ny), 1);
    unsigned row = 0;
    for (const auto& o : model.outputs)
      for (const GiNaC::ex& c : o.components) outputs(row++, 0) = c;
    expect_matches(y, outputs, all, "outputs");
    // the declared independent speeds leave a dependent block of Xi that can be solved
    if (Model::ni > 0 && Model::nc > 0) {
      Eigen::MatrixXd dependent(Model::nc, 0);
      for (int k = 0; k < Model::nq; ++k)
        if (std::find(Model::independent_speeds.begin(), Model::independent_speeds.end(), k) ==
            Model::independent_speeds.end()) {
          dependent.conservativeResize(Eigen::NoChange, dependent.cols() + 1);
          dependent.col(dependent.cols() - 1) = Xi.col(k);
        }
      ASSERT_EQ(dependent.cols(), dependent.rows());
      EXPECT_GT(std::fabs(dependent.determinant()), 1e-6) << "dependent block of Xi:\n" << dependent;
    }
  }
}

}  // namespace eomgen::testing
