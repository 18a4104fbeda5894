#include "eomgen/derivation/header_functions.hpp"

#include <gtest/gtest.h>

#include <Eigen/QR>

#include <cmath>
#include <random>
#include <string>

#include "eomgen/derivation/model_equations.hpp"
#include "eomgen/derivation/numeric_evaluation.hpp"
#include "eomgen/language/model_file.hpp"
#include "support/source_dir.hpp"
#include "support/symbolic_checks.hpp"

namespace eomgen {
namespace {

Model shipped(const std::string& name) { return load_model(testing::shipped_model_path(name)); }

// Every intermediate of the functions valued at `state` (a random state with the defaults), the
// accelerations given as well.
class Values {
 public:
  Values(const HeaderFunctions& h, GiNaC::exmap state) : values_(std::move(state)) {
    for (const Subexpressions* z : h.intermediates()) values_ = z->evaluate_all(values_);
  }
  double operator()(const GiNaC::ex& e) const {
    return GiNaC::ex_to<GiNaC::numeric>(e.subs(values_, GiNaC::subs_options::no_pattern).evalf()).to_double();
  }
  double of(const GiNaC::ex& symbol) const { return (*this)(symbol); }

 private:
  GiNaC::exmap values_;
};

// the double pendulum's state with accelerations, and its symbols by name
struct DoublePendulum {
  Model model = shipped("double_pendulum");
  ModelEquations eom = derive_equations(model);
  HeaderFunctions h = derive_header_functions(model, eom);
  GiNaC::exmap state;
  DoublePendulum() {
    state = testing::random_state(model.system, 5);
    state[model.system.variables().coordinates()[0].qdd] = 0.7;
    state[model.system.variables().coordinates()[1].qdd] = -1.3;
  }
  double value(const std::string& name) const {
    for (const auto& p : model.system.variables().parameters())
      if (p.name == name) return p.default_value;
    const auto& c = model.system.variables().coordinates();
    for (const auto& coordinate : c) {
      if (coordinate.name == name) return Values(h, state).of(coordinate.q);
      if (coordinate.name + "_dot" == name) return Values(h, state).of(coordinate.qd);
    }
    ADD_FAILURE() << name;
    return 0;
  }
};

// By hand, for bobs m1, m2 on rods l1, l2 at relative angles theta1, theta2 (s12 = sin(theta1 +
// theta2)): V = -(m1 + m2) g l1 cos(theta1) - m2 g l2 cos(theta1 + theta2), M11 = m1 l1^2 +
// m2 (l1^2 + l2^2 + 2 l1 l2 cos(theta2)), M12 = m2 (l2^2 + l1 l2 cos(theta2)), M22 = m2 l2^2.
TEST(HeaderFunctions, DoublePendulumGravityAndCoriolisMatchTheHandDerivation) {
  const DoublePendulum p;
  ASSERT_TRUE(p.h.gravity_forces && p.h.coriolis_matrix) << p.h.no_coriolis_and_gravity;
  const Values at(p.h, p.state);
  const double m1 = p.value("m1"), m2 = p.value("m2"), l1 = p.value("l1"), l2 = p.value("l2"), g = p.value("g");
  const double t1 = p.value("theta1"), t2 = p.value("theta2"), w1 = p.value("theta1_dot"), w2 = p.value("theta2_dot");
  const GiNaC::matrix& G = *p.h.gravity_forces;
  EXPECT_NEAR(at(G(0, 0)), (m1 + m2) * g * l1 * std::sin(t1) + m2 * g * l2 * std::sin(t1 + t2), 1e-12);
  EXPECT_NEAR(at(G(1, 0)), m2 * g * l2 * std::sin(t1 + t2), 1e-12);
  // h = m2 l1 l2 sin(theta2): C = [[-h w2, -h (w1 + w2)], [h w1, 0]]
  const double hh = m2 * l1 * l2 * std::sin(t2);
  const GiNaC::matrix& C = *p.h.coriolis_matrix;
  EXPECT_NEAR(at(C(0, 0)), -hh * w2, 1e-12);
  EXPECT_NEAR(at(C(0, 1)), -hh * (w1 + w2), 1e-12);
  EXPECT_NEAR(at(C(1, 0)), hh * w1, 1e-12);
  EXPECT_NEAR(at(C(1, 1)), 0.0, 1e-12);
}

// tip = (l1 s1 + l2 s12, -l1 c1 - l2 c12, 0): J and its acceleration at qdd = 0, by hand
TEST(HeaderFunctions, DoublePendulumTipJacobianAndBiasMatchTheHandDerivation) {
  const DoublePendulum p;
  const Values at(p.h, p.state);
  const OutputJacobian* tip = nullptr;
  for (const OutputJacobian& j : p.h.output_jacobians)
    if (p.model.outputs[j.output].name == "tip") tip = &j;
  ASSERT_NE(tip, nullptr);
  EXPECT_EQ(tip->level, OutputJacobian::Level::position);
  const double l1 = p.value("l1"), l2 = p.value("l2");
  const double t1 = p.value("theta1"), t2 = p.value("theta2"), w1 = p.value("theta1_dot"), w2 = p.value("theta2_dot");
  const double c1 = std::cos(t1), s1 = std::sin(t1), c12 = std::cos(t1 + t2), s12 = std::sin(t1 + t2);
  EXPECT_NEAR(at(tip->jacobian(0, 0)), l1 * c1 + l2 * c12, 1e-12);
  EXPECT_NEAR(at(tip->jacobian(0, 1)), l2 * c12, 1e-12);
  EXPECT_NEAR(at(tip->jacobian(1, 0)), l1 * s1 + l2 * s12, 1e-12);
  EXPECT_NEAR(at(tip->jacobian(1, 1)), l2 * s12, 1e-12);
  EXPECT_NEAR(at(tip->bias(0, 0)), -l1 * s1 * w1 * w1 - l2 * s12 * (w1 + w2) * (w1 + w2), 1e-12);
  EXPECT_NEAR(at(tip->bias(1, 0)), l1 * c1 * w1 * w1 + l2 * c12 * (w1 + w2) * (w1 + w2), 1e-12);
  EXPECT_NEAR(at(tip->bias(2, 0)), 0.0, 1e-12);
  // a velocity output: J of tip_velocity is the same matrix (dv/dqd = dr/dq), its bias the same
  for (const OutputJacobian& j : p.h.output_jacobians)
    if (p.model.outputs[j.output].name == "tip_velocity") {
      EXPECT_EQ(j.level, OutputJacobian::Level::velocity);
      for (unsigned r = 0; r < 3; ++r) {
        EXPECT_NEAR(at(j.bias(r, 0)), at(tip->bias(r, 0)), 1e-12);
        for (unsigned c = 0; c < 2; ++c) EXPECT_NEAR(at(j.jacobian(r, c)), at(tip->jacobian(r, c)), 1e-12);
      }
    }
}

// The regressor is free of the masses (the only inertial parameters of point masses) and
// Y pi = M qdd - F; the inverse dynamics is M qdd - F whichever form it took
TEST(HeaderFunctions, RegressorIsFreeOfTheMassesAndReproducesTheInverseDynamics) {
  const DoublePendulum p;
  ASSERT_TRUE(p.h.regressor) << p.h.no_regressor;
  ASSERT_EQ(p.h.inertial_parameter_names.size(), 20u);
  EXPECT_EQ(p.h.inertial_parameter_names[0], "bob1.m");
  EXPECT_EQ(p.h.inertial_parameter_names[13], "bob2.mz");
  const Values at(p.h, p.state);
  const auto& vars = p.model.system.variables();
  for (unsigned i = 0; i < 2; ++i) {
    double M_qdd_minus_F = -at(p.h.forcing(i, 0)), Y_pi = 0;
    for (unsigned j = 0; j < 2; ++j) M_qdd_minus_F += at(p.h.mass_matrix(i, j)) * at(vars.coordinates()[j].qdd);
    for (unsigned k = 0; k < 20; ++k) Y_pi += at((*p.h.regressor)(i, k)) * at(p.h.inertial_parameters(k, 0));
    EXPECT_NEAR(Y_pi, M_qdd_minus_F, 1e-12);
    EXPECT_NEAR(at(p.h.inverse_dynamics(i, 0)), M_qdd_minus_F, 1e-12);
  }
  // twice the masses: pi doubles, Y does not change
  GiNaC::exmap heavier = p.state;
  for (const auto& parameter : vars.parameters())
    if (parameter.name == "m1" || parameter.name == "m2") heavier[parameter.symbol] = 2 * parameter.default_value;
  const Values heavy(p.h, heavier);
  for (unsigned i = 0; i < 2; ++i)
    for (unsigned k = 0; k < 20; ++k) EXPECT_EQ(heavy((*p.h.regressor)(i, k)), at((*p.h.regressor)(i, k)));
}

// The UR5's inverse dynamics by Newton-Euler: cheaper than M qdd - F of the recursions' M and F
TEST(HeaderFunctions, ArmsTakeTheInverseDynamicsFromNewtonEuler) {
  const Model model = load_model((testing::source_dir() / "models" / "robots" / "ur5.urdf").string());
  const ModelEquations eom = derive_equations(model);
  const HeaderFunctions h = derive_header_functions(model, eom);
  EXPECT_EQ(h.inverse_dynamics_form.form, FunctionForm::recursions);
  EXPECT_LT(h.inverse_dynamics_form.estimated_operations, h.inverse_dynamics_form.estimated_operations_other);
  EXPECT_EQ(h.mass_matrix_form.form, FunctionForm::recursions);
  ASSERT_TRUE(h.forward_dynamics.has_value());
  EXPECT_TRUE(h.prefers_forward_dynamics);
  // a frame's angular velocity is a velocity output: its Jacobian is that of the tool frame
  bool angular = false;
  for (const OutputJacobian& j : h.output_jacobians)
    angular = angular || (model.outputs[j.output].name == "tool0_angular_velocity" && j.level == OutputJacobian::Level::velocity);
  EXPECT_TRUE(angular);
}

// Where the potential or M moves with time there is no C and G; a model with constraints keeps
// its M qdd - F as inverse dynamics and gets the split in the header
TEST(HeaderFunctions, ConstrainedModelsKeepTheirInverseDynamicsAndRegressor) {
  const Model model = shipped("rolling_coin");
  const ModelEquations eom = derive_equations(model);
  const HeaderFunctions h = derive_header_functions(model, eom);
  EXPECT_TRUE(h.regressor.has_value()) << h.no_regressor;
  EXPECT_FALSE(h.forward_dynamics.has_value());
  EXPECT_EQ(h.no_forward_dynamics, "the model has constraints");
  EXPECT_EQ(h.inverse_dynamics.rows(), eom.mass_matrix.rows());
}

// The UR5's base parameters: Y_base has full column rank on stacked random states, and
// Y pi = Y_base pi_base there (pi_base = combination pi)
TEST(HeaderFunctions, BaseParametersOfAnArmHaveFullRankAndReproduceTheRegressor) {
  const Model model = load_model((testing::source_dir() / "models" / "robots" / "ur5.urdf").string());
  const ModelEquations eom = derive_equations(model);
  HeaderOptions options;
  options.base_regressor = true;
  const HeaderFunctions h = derive_header_functions(model, eom, nullptr, options);
  ASSERT_TRUE(h.base_parameters.has_value());
  const BaseParameters& base = *h.base_parameters;
  const auto r = static_cast<Eigen::Index>(base.names.size());
  // 6 revolute joints, 7 bodies (the base moves with nothing): far fewer than 70, at least one per joint
  EXPECT_LT(r, 70);
  EXPECT_GE(r, 6);
  const Eigen::Index n = 6;
  Eigen::MatrixXd stacked(0, r);
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int s = 0; s < 12; ++s) {
    NamedValues at;
    for (const auto& c : model.system.variables().coordinates()) at[c.name] = uniform(rng), at[c.name + "_dot"] = uniform(rng);
    Eigen::VectorXd qdd(n);
    for (Eigen::Index k = 0; k < n; ++k) qdd(k) = uniform(rng);
    const NumericControllerFunctions f = evaluate_controller_functions(model, eom, h, at, qdd);
    Eigen::MatrixXd Y_base(n, r);
    for (Eigen::Index k = 0; k < r; ++k) Y_base.col(k) = f.regressor.col(base.independent[static_cast<std::size_t>(k)]);
    const Eigen::VectorXd pi_base = base.combination * f.inertial_parameters;
    EXPECT_LT((Y_base * pi_base - f.regressor * f.inertial_parameters).cwiseAbs().maxCoeff(),
              1e-9 * (1 + (f.regressor * f.inertial_parameters).cwiseAbs().maxCoeff()));
    stacked.conservativeResize(stacked.rows() + n, Eigen::NoChange);
    stacked.bottomRows(n) = Y_base;
  }
  EXPECT_EQ(Eigen::ColPivHouseholderQR<Eigen::MatrixXd>(stacked).rank(), r);
}

// Where the combinations move with the model's lengths, they are refused, naming the lengths
TEST(HeaderFunctions, BaseParametersOfAGeometryOfParametersAreRefusedNamingThem) {
  const Model model = shipped("double_pendulum");
  const ModelEquations eom = derive_equations(model);
  HeaderOptions options;
  options.base_regressor = true;
  try {
    derive_header_functions(model, eom, nullptr, options);
    FAIL() << "expected a DerivationError";
  } catch (const DerivationError& e) {
    EXPECT_NE(std::string(e.what()).find("depend on the parameters l1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace eomgen
