// The derivatives of the forward dynamics (header_functions.hpp, forward_dynamics_derivatives) of
// every shipped model without constraints, in each form the model admits, in numbers at random
// states: against central differences of qdd = M^-1 F evaluated from the derived equations, and
// against the full-state A and B of linearize() (an independent path: the linearization's terms
// solved with Eigen at the point's own accelerations).
#include <gtest/gtest.h>

#include <Eigen/Cholesky>

#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "eomgen/derivation/header_functions.hpp"
#include "eomgen/derivation/linearization.hpp"
#include "eomgen/derivation/model_equations.hpp"
#include "eomgen/derivation/numeric_evaluation.hpp"
#include "eomgen/language/model_file.hpp"
#include "support/numeric_checks.hpp"
#include "support/source_dir.hpp"

namespace eomgen {
namespace {

using Form = ForwardDynamicsDerivatives::Form;
using testing::matrices_near_relative;

const Form every_form[] = {Form::chain_rule_through_recursion, Form::mass_matrix_and_linearization,
                           Form::mass_matrix_and_newton_euler};

// models/*.eom and models/robots/*.urdf, sorted
std::vector<std::string> shipped_models() {
  std::vector<std::string> paths;
  for (const char* folder : {"models", "models/robots"})
    for (const auto& entry : std::filesystem::directory_iterator(testing::source_dir() / folder))
      if (entry.path().extension() == ".eom" || entry.path().extension() == ".urdf") paths.push_back(entry.path().string());
  std::sort(paths.begin(), paths.end());
  return paths;
}

// A random state by name: coordinates and rates in [-1, 1], inputs in [-2, 2], t in [0, 2].
NamedValues random_point(const Model& model, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0), input(-2.0, 2.0), time(0.0, 2.0);
  NamedValues at{{"t", time(rng)}};
  for (const Coordinate& c : model.system.variables().coordinates()) at[c.name] = value(rng), at[c.name + "_dot"] = value(rng);
  for (const Input& u : model.system.variables().inputs()) at[u.name] = input(rng);
  return at;
}

// qdd = M^-1 F of the derived equations at a point
Eigen::VectorXd accelerations(const Model& model, const ModelEquations& eom, const NamedValues& at) {
  const NumericEquations e = evaluate_equations(model, eom, at);
  return e.mass_matrix.llt().solve(e.forcing);
}

// [dqdd/dq, dqdd/dqd, dqdd/du] by central differences of accelerations()
Eigen::MatrixXd central_differences(const Model& model, const ModelEquations& eom, const NamedValues& at) {
  std::vector<std::string> names;
  for (const Coordinate& c : model.system.variables().coordinates()) names.push_back(c.name);
  for (const Coordinate& c : model.system.variables().coordinates()) names.push_back(c.name + "_dot");
  for (const Input& u : model.system.variables().inputs()) names.push_back(u.name);
  Eigen::MatrixXd d(static_cast<Eigen::Index>(model.system.variables().coordinate_count()),
                    static_cast<Eigen::Index>(names.size()));
  for (std::size_t k = 0; k < names.size(); ++k) {
    const double x = at.at(names[k]), h = 1e-6 * std::max(1.0, std::abs(x));
    NamedValues plus = at, minus = at;
    plus[names[k]] = x + h;
    minus[names[k]] = x - h;
    d.col(static_cast<Eigen::Index>(k)) = (accelerations(model, eom, plus) - accelerations(model, eom, minus)) / (2 * h);
  }
  return d;
}

// [dqdd/dq, dqdd/dqd, dqdd/du] of the header functions in numbers; the symbols qdd and lambda of
// the linearization's own intermediates are NaN, so an entry that reached one would be NaN
Eigen::MatrixXd derivatives_at(const Model& model, const ModelEquations& eom, const HeaderFunctions& h,
                               const NamedValues& at) {
  DoubleEvaluator eval = evaluator_at(model, eom, at);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const Coordinate& c : model.system.variables().coordinates()) eval.set(c.qdd, nan);
  for (const GiNaC::realsymbol& lambda : h.linearization->lambda) eval.set(lambda, nan);
  const std::vector<const Subexpressions*> sets = h.intermediates();
  for (std::size_t s = 1; s < sets.size(); ++s)  // the first, the equations', evaluator_at has done
    for (const Subexpressions::Definition& d : sets[s]->definitions())
      eval.set(d.symbol, eval.value(d.value, d.symbol.get_name()));
  const ForwardDynamicsDerivatives& d = *h.forward_dynamics_derivatives;
  const Eigen::MatrixXd by_q = evaluate_matrix(d.by_coordinates, eval, "dqdd/dq");
  const Eigen::MatrixXd by_qd = evaluate_matrix(d.by_rates, eval, "dqdd/dqd");
  const Eigen::MatrixXd by_u = evaluate_matrix(d.by_inputs, eval, "dqdd/du");
  Eigen::MatrixXd all(by_q.rows(), by_q.cols() + by_qd.cols() + by_u.cols());
  all << by_q, by_qd, by_u;
  for (const GiNaC::ex& pivot : d.pivots) EXPECT_GT(eval.value(pivot, "pivot"), 0.0);
  // qdd itself, which the header's overload writes before the derivatives
  EXPECT_TRUE(matrices_near_relative(evaluate_matrix(d.accelerations, eval, "qdd"),
                                     Eigen::MatrixXd(accelerations(model, eom, at)), 1e-12))
      << to_string(d.form);
  return all;
}

class EveryShippedModel : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryShippedModel, DerivativesInEveryFormMatchDifferencesAndLinearize) {
  const Model model = load_model(GetParam());
  const ModelEquations eom = derive_equations(model);
  const SymbolicLinearization lin = linearize_symbolic(model, eom);
  if (eom.constraint_count > 0) {
    const HeaderFunctions h = derive_header_functions(model, eom, &lin);
    EXPECT_FALSE(h.forward_dynamics_derivatives);
    EXPECT_NE(h.no_forward_dynamics_derivatives.find("constraints"), std::string::npos);
    return;
  }
  const Eigen::Index n = static_cast<Eigen::Index>(model.system.variables().coordinate_count());
  int forms = 0;
  for (Form form : every_form) {
    HeaderOptions options;
    options.controller_functions = false;
    options.forward_dynamics_derivatives_form = form;
    const HeaderFunctions h = derive_header_functions(model, eom, &lin, options);
    if (!h.forward_dynamics_derivatives) {
      // only the chain rule needs a recursion, only Newton-Euler a tree of bodies
      EXPECT_NE(form, Form::mass_matrix_and_linearization) << h.no_forward_dynamics_derivatives;
      continue;
    }
    ++forms;
    EXPECT_EQ(h.forward_dynamics_derivatives->form, form);
    for (unsigned seed : {1u, 2u}) {
      const NamedValues at = random_point(model, seed);
      const Eigen::MatrixXd derived = derivatives_at(model, eom, h, at);
      EXPECT_TRUE(matrices_near_relative(derived, central_differences(model, eom, at), 1e-6))
          << to_string(form) << ", seed " << seed;
      const LinearModel linear = linearize(model, eom, lin, at);
      Eigen::MatrixXd expected(n, linear.A_full.cols() + linear.B_full.cols());
      expected << linear.A_full.bottomRows(n), linear.B_full.bottomRows(n);
      EXPECT_TRUE(matrices_near_relative(derived, expected, 1e-12)) << to_string(form) << ", seed " << seed;
    }
  }
  EXPECT_GE(forms, 1);
}

INSTANTIATE_TEST_SUITE_P(ForwardDynamicsDerivatives, EveryShippedModel, ::testing::ValuesIn(shipped_models()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return std::filesystem::path(info.param).stem().string();
                         });

// The form emitted is the one of the fewest estimated operations among those derived, and every
// form a model admits is among them
TEST(ForwardDynamicsDerivatives, TheFormOfFewestEstimatedOperationsIsKept) {
  const Model model = load_model((testing::source_dir() / "models" / "robots" / "ur5.urdf").string());
  const ModelEquations eom = derive_equations(model);
  const SymbolicLinearization lin = linearize_symbolic(model, eom);
  const HeaderFunctions h = derive_header_functions(model, eom, &lin);
  ASSERT_TRUE(h.forward_dynamics_derivatives) << h.no_forward_dynamics_derivatives;
  const ForwardDynamicsDerivatives& d = *h.forward_dynamics_derivatives;
  ASSERT_EQ(d.candidates.size(), 3u);
  for (const auto& [form, operations] : d.candidates) {
    EXPECT_GT(operations, 0.0) << to_string(form);
    EXPECT_LE(d.estimated_operations, operations) << to_string(form);
    if (form == d.form) {
      EXPECT_EQ(d.estimated_operations, operations);
    }
  }
}

// Without a linearization the header has neither the derivatives nor a reason
TEST(ForwardDynamicsDerivatives, OnlyWithALinearization) {
  const Model model = load_model(testing::shipped_model_path("cart_pole"));
  const ModelEquations eom = derive_equations(model);
  const HeaderFunctions h = derive_header_functions(model, eom);
  EXPECT_FALSE(h.forward_dynamics_derivatives);
  EXPECT_TRUE(h.no_forward_dynamics_derivatives.empty());
}

}  // namespace
}  // namespace eomgen
