// The functions a controller calls, in every shipped header where they apply, against the
// header's own M and F and against finite differences: inverse_dynamics = M qdd - F (with
// constraints: tau + Xi^T lambda = M qdd - F, tau orthogonal to the rows of Xi), G = dV/dq,
// dM/dt - 2 C skew-symmetric and C qd + G = -F where gravity and springs are the only loads,
// the output Jacobians and their biases, and the regressor: Y pi reproduces M qdd - F up to
// terms free of the inertial parameters. Then the signatures: blocks, Maps, Inputs::Zero(),
// float and an automatic-differentiation scalar.
#include <Eigen/Core>
#include <Eigen/LU>
#include <gtest/gtest.h>
#include <unsupported/Eigen/AutoDiff>

#include <cmath>
#include <random>
#include <string>
#include <type_traits>

#include "bead_on_hoop.hpp"
#include "cart_pole.hpp"
#include "cartesian_pendulum.hpp"
#include "double_pendulum.hpp"
#include "heavy_top.hpp"
#include "iiwa14.hpp"
#include "knife_edge.hpp"
#include "panda.hpp"
#include "planar_chain.hpp"
#include "quaternion_rigid_body.hpp"
#include "rolling_coin.hpp"
#include "simple_pendulum.hpp"
#include "spacecraft_panel.hpp"
#include "spherical_pendulum.hpp"
#include "spring_mass_damper.hpp"
#include "two_arm_torso.hpp"
#include "universal_chain.hpp"
#include "ur5.hpp"
#include "whipple_bicycle.hpp"

namespace {

template <class...>
using void_t = void;

template <class Model, class = void>
struct has_coriolis : std::false_type {};
template <class Model>
struct has_coriolis<Model, void_t<decltype(Model::coriolis_matrix(
                               std::declval<typename Model::template Vector<double>>(),
                               std::declval<typename Model::template Vector<double>>(),
                               std::declval<const typename Model::template Constants<double>&>(),
                               std::declval<typename Model::template MassMatrix<double>&>()))>> : std::true_type {};

template <class Model, class = void>
struct has_regressor : std::false_type {};
template <class Model>
struct has_regressor<Model, void_t<decltype(Model::npi)>> : std::true_type {};

// the largest entry of a, relative to 1 + the largest of b
template <class A, class B>
double relative_error(const A& a, const B& b) {
  return (a - b).cwiseAbs().maxCoeff() / (1 + b.cwiseAbs().maxCoeff());
}

// A random state of a model (q, qd, qdd, u at the default parameters).
template <class Model>
struct State {
  double t = 0;
  typename Model::template Vector<double> q, qd, qdd;
  typename Model::template Inputs<double> u;
  explicit State(std::mt19937& rng) {
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    t = 0.5 + uniform(rng) * 0.25;
    for (int k = 0; k < Model::nq; ++k) q(k) = uniform(rng), qd(k) = uniform(rng), qdd(k) = uniform(rng);
    for (int k = 0; k < Model::nu; ++k) u(k) = uniform(rng);
  }
};

template <class Model>
typename Model::template Vector<double> M_qdd_minus_F(const State<Model>& s, const typename Model::template Constants<double>& c) {
  typename Model::template MassMatrix<double> M;
  typename Model::template Vector<double> F;
  Model::mass_matrix_and_forcing(s.t, s.q, s.qd, s.u, c, M, F);
  return M * s.qdd - F;
}

// tau = M qdd - F; with constraints tau + Xi^T lambda = M qdd - F and Xi tau = 0
template <class Model>
void check_inverse_dynamics() {
  const typename Model::template Constants<double> c{typename Model::template Parameters<double>()};
  std::mt19937 rng(11);
  for (int trial = 0; trial < 5; ++trial) {
    const State<Model> s(rng);
    const typename Model::template Vector<double> expected = M_qdd_minus_F<Model>(s, c);
    typename Model::template Vector<double> tau;
    if constexpr (Model::nc == 0) {
      Model::inverse_dynamics(s.t, s.q, s.qd, s.qdd, s.u, c, tau);
      EXPECT_LT(relative_error(tau, expected), 1e-12) << Model::name;
    } else {
      typename Model::template ConstraintVector<double> lambda;
      typename Model::template ConstraintJacobian<double> Xi;
      Model::inverse_dynamics(s.t, s.q, s.qd, s.qdd, s.u, c, tau, lambda);
      Model::constraint_jacobian(s.t, s.q, c, Xi);
      EXPECT_LT(relative_error(tau + Xi.transpose() * lambda, expected), 1e-12) << Model::name;
      EXPECT_LT((Xi * tau).cwiseAbs().maxCoeff(), 1e-10 * (1 + expected.cwiseAbs().maxCoeff())) << Model::name;
    }
  }
}

// G = dV/dq (central differences), dM/dt - 2 C skew-symmetric (dM/dt by central differences
// along qd), and where gravity and springs are the only loads, C qd + G = -F at u = 0
template <class Model>
void check_coriolis_and_gravity(bool only_conservative_loads) {
  static_assert(has_coriolis<Model>::value);
  const typename Model::template Constants<double> c{typename Model::template Parameters<double>()};
  using Vector = typename Model::template Vector<double>;
  using Matrix = typename Model::template MassMatrix<double>;
  std::mt19937 rng(13);
  const double h = 1e-6;
  for (int trial = 0; trial < 5; ++trial) {
    const State<Model> s(rng);
    Vector G;
    Matrix C, M_plus, M_minus;
    Model::gravity_forces(s.q, c, G);
    Model::coriolis_matrix(s.q, s.qd, c, C);
    Vector dV;
    for (int k = 0; k < Model::nq; ++k) {
      Vector plus = s.q, minus = s.q;
      plus(k) += h;
      minus(k) -= h;
      dV(k) = (Model::potential_energy(s.t, plus, c) - Model::potential_energy(s.t, minus, c)) / (2 * h);
    }
    EXPECT_LT(relative_error(G, dV), 1e-7) << Model::name;
    Model::mass_matrix(s.t, Vector(s.q + h * s.qd), c, M_plus);
    Model::mass_matrix(s.t, Vector(s.q - h * s.qd), c, M_minus);
    const Matrix N = (M_plus - M_minus) / (2 * h) - 2 * C;
    EXPECT_LT((N + N.transpose()).cwiseAbs().maxCoeff() / (1 + C.cwiseAbs().maxCoeff()), 1e-7) << Model::name;
    if (only_conservative_loads) {
      Vector F;
      Model::forcing(s.t, s.q, s.qd, Model::template Inputs<double>::Zero(), c, F);
      EXPECT_LT(relative_error(Vector(C * s.qd + G), Vector(-F)), 1e-12) << Model::name;
    }
  }
}

// Y pi = M qdd - F - r, r free of the inertial parameters and of qdd: zero where gravity is the
// only load (and the inputs are zero)
template <class Model>
void check_regressor(bool only_gravity) {
  static_assert(has_regressor<Model>::value);
  const typename Model::template Constants<double> c{typename Model::template Parameters<double>()};
  Eigen::Matrix<double, Model::npi, 1> pi;
  Model::inertial_parameters(c, pi);
  std::mt19937 rng(17);
  Eigen::Matrix<double, Model::nq, Model::npi> Y;
  for (int trial = 0; trial < 5; ++trial) {
    State<Model> s(rng);
    if (only_gravity) s.u.setZero();
    Model::regressor(s.t, s.q, s.qd, s.qdd, c, Y);
    const typename Model::template Vector<double> rest = M_qdd_minus_F<Model>(s, c) - Y * pi;
    if (only_gravity) {
      EXPECT_LT(rest.cwiseAbs().maxCoeff(), 1e-12 * (1 + (Y * pi).cwiseAbs().maxCoeff())) << Model::name;
    } else {
      State<Model> other = s;
      other.qdd *= -3;
      Model::regressor(other.t, other.q, other.qd, other.qdd, c, Y);
      const typename Model::template Vector<double> other_rest = M_qdd_minus_F<Model>(other, c) - Y * pi;
      EXPECT_LT(relative_error(other_rest, rest), 1e-11) << Model::name;
    }
  }
}

// the first component of the named output in output_names ("tip" is "tip_1", "tip_2", "tip_3")
template <class Model>
int first_component(const std::string& output) {
  for (int k = 0; k < Model::ny; ++k) {
    const std::string label = Model::output_names[static_cast<std::size_t>(k)];
    if (label == output || label == output + "_1") return k;
  }
  ADD_FAILURE() << "no output " << output;
  return 0;
}

// J against central differences of the outputs in q (a position) or qd (a velocity), and
// J qdd + bias against the second (position) or first (velocity) derivative of the output along
// q(s) = q + s qd + s^2/2 qdd, qd(s) = qd + s qdd, t + s
template <class Model, int rows, class Jacobian, class Bias>
void check_output_jacobian(const std::string& output, bool velocity, Jacobian jacobian, Bias bias) {
  const typename Model::template Constants<double> c{typename Model::template Parameters<double>()};
  using Vector = typename Model::template Vector<double>;
  using Outputs = typename Model::template OutputVector<double>;
  const int first = first_component<Model>(output);
  std::mt19937 rng(19);
  for (int trial = 0; trial < 5; ++trial) {
    const State<Model> s(rng);
    const auto y = [&](double ds, const Vector& q, const Vector& qd) {
      Outputs out;
      Model::outputs(s.t + ds, q, qd, s.u, c, out);
      return Eigen::Matrix<double, rows, 1>(out.template segment<rows>(first));
    };
    Eigen::Matrix<double, rows, Model::nq> J, differences;
    Eigen::Matrix<double, rows, 1> b;
    jacobian(s.t, s.q, c, J);
    bias(s.t, s.q, s.qd, c, b);
    const double h = 1e-6;
    for (int k = 0; k < Model::nq; ++k) {
      Vector step = Vector::Zero();
      step(k) = h;
      differences.col(k) = velocity ? (y(0, s.q, s.qd + step) - y(0, s.q, s.qd - step)) / (2 * h)
                                    : (y(0, s.q + step, s.qd) - y(0, s.q - step, s.qd)) / (2 * h);
    }
    EXPECT_LT(relative_error(J, differences), 1e-7) << Model::name << " " << output;
    const auto along = [&](double ds) {
      return y(ds, Vector(s.q + ds * s.qd + 0.5 * ds * ds * s.qdd), Vector(s.qd + ds * s.qdd));
    };
    const double d = velocity ? 1e-6 : 1e-4;
    const Eigen::Matrix<double, rows, 1> rate =
        velocity ? Eigen::Matrix<double, rows, 1>((along(d) - along(-d)) / (2 * d))
                 : Eigen::Matrix<double, rows, 1>((along(d) - 2 * along(0) + along(-d)) / (d * d));
    EXPECT_LT(relative_error(Eigen::Matrix<double, rows, 1>(J * s.qdd + b), rate), velocity ? 1e-7 : 1e-5)
        << Model::name << " " << output;
  }
}

#define EXPECT_OUTPUT_JACOBIAN(model, output, rows, velocity)                                                  \
  check_output_jacobian<eomgen_models::model::Model, rows>(                                                   \
      #output, velocity,                                                                                      \
      [](const auto& t, const auto& q, const auto& c, auto& J) {                                              \
        eomgen_models::model::Model::output_jacobian_##output(t, q, c, J);                                    \
      },                                                                                                      \
      [](const auto& t, const auto& q, const auto& qd, const auto& c, auto& b) {                              \
        eomgen_models::model::Model::output_bias_##output(t, q, qd, c, b);                                    \
      })

TEST(InverseDynamics, IsMassMatrixTimesAccelerationLessForcingInEveryShippedHeader) {
  using namespace eomgen_models;
  check_inverse_dynamics<simple_pendulum::Model>();
  check_inverse_dynamics<double_pendulum::Model>();
  check_inverse_dynamics<cart_pole::Model>();
  check_inverse_dynamics<planar_chain::Model>();
  check_inverse_dynamics<universal_chain::Model>();
  check_inverse_dynamics<spring_mass_damper::Model>();
  check_inverse_dynamics<spherical_pendulum::Model>();
  check_inverse_dynamics<heavy_top::Model>();
  check_inverse_dynamics<spacecraft_panel::Model>();
  check_inverse_dynamics<bead_on_hoop::Model>();
  check_inverse_dynamics<ur5::Model>();
  check_inverse_dynamics<iiwa14::Model>();
  check_inverse_dynamics<two_arm_torso::Model>();
}

TEST(InverseDynamics, WithConstraintsSplitsOffTheConstraintForcesAndLeavesTheLeastTau) {
  using namespace eomgen_models;
  check_inverse_dynamics<cartesian_pendulum::Model>();
  check_inverse_dynamics<knife_edge::Model>();
  check_inverse_dynamics<rolling_coin::Model>();
  check_inverse_dynamics<quaternion_rigid_body::Model>();
  check_inverse_dynamics<whipple_bicycle::Model>();
  check_inverse_dynamics<panda::Model>();
}

TEST(CoriolisAndGravity, GravityIsTheGradientOfVAndMdotLessTwoCIsSkewSymmetric) {
  using namespace eomgen_models;
  check_coriolis_and_gravity<simple_pendulum::Model>(true);
  check_coriolis_and_gravity<double_pendulum::Model>(true);
  check_coriolis_and_gravity<planar_chain::Model>(true);
  check_coriolis_and_gravity<universal_chain::Model>(true);
  check_coriolis_and_gravity<spherical_pendulum::Model>(true);
  check_coriolis_and_gravity<heavy_top::Model>(true);
  check_coriolis_and_gravity<cart_pole::Model>(false);
  check_coriolis_and_gravity<spring_mass_damper::Model>(false);
  check_coriolis_and_gravity<ur5::Model>(false);
  check_coriolis_and_gravity<iiwa14::Model>(false);
  check_coriolis_and_gravity<two_arm_torso::Model>(false);
  // the hoop turns at a prescribed rate: the centrifugal term of that motion is one of F's other loads
  check_coriolis_and_gravity<bead_on_hoop::Model>(false);
}

TEST(Regressor, TimesTheModelsInertialParametersReproducesTheInverseDynamics) {
  using namespace eomgen_models;
  check_regressor<simple_pendulum::Model>(true);
  check_regressor<double_pendulum::Model>(true);
  check_regressor<planar_chain::Model>(true);
  check_regressor<universal_chain::Model>(true);
  check_regressor<heavy_top::Model>(true);
  check_regressor<cart_pole::Model>(false);
  check_regressor<spring_mass_damper::Model>(false);
  check_regressor<ur5::Model>(false);
  check_regressor<iiwa14::Model>(false);
  check_regressor<two_arm_torso::Model>(false);
  check_regressor<panda::Model>(false);
}

TEST(OutputJacobian, MatchesFiniteDifferencesAndItsBiasTheAccelerationAtZeroQdd) {
  EXPECT_OUTPUT_JACOBIAN(double_pendulum, tip, 3, false);
  EXPECT_OUTPUT_JACOBIAN(double_pendulum, elbow, 3, false);
  EXPECT_OUTPUT_JACOBIAN(double_pendulum, tip_velocity, 3, true);
  EXPECT_OUTPUT_JACOBIAN(double_pendulum, absolute_angle2, 1, false);
  EXPECT_OUTPUT_JACOBIAN(cart_pole, tip, 3, false);
  EXPECT_OUTPUT_JACOBIAN(heavy_top, omega, 3, true);
  EXPECT_OUTPUT_JACOBIAN(heavy_top, axis, 3, false);
  EXPECT_OUTPUT_JACOBIAN(bead_on_hoop, bead_pos, 3, false);  // the hoop's prescribed turn: terms in t
  EXPECT_OUTPUT_JACOBIAN(bead_on_hoop, bead_vel, 3, true);
  EXPECT_OUTPUT_JACOBIAN(universal_chain, tip, 3, false);
  EXPECT_OUTPUT_JACOBIAN(rolling_coin, omega, 3, true);
  EXPECT_OUTPUT_JACOBIAN(whipple_bicycle, front_contact_position, 3, false);
  EXPECT_OUTPUT_JACOBIAN(ur5, tool0_position, 3, false);
  EXPECT_OUTPUT_JACOBIAN(iiwa14, iiwa_link_ee_position, 3, false);
  EXPECT_OUTPUT_JACOBIAN(panda, panda_hand_tcp_position, 3, false);
}

// ---- the signatures: any Eigen expression in, any writable one out ----

using Ur5 = eomgen_models::ur5::Model;

TEST(GeneratedSignatures, TakeBlocksOfAStateMapsOverPlainArraysAndZeroExpressions) {
  const Ur5::Constants<double> c{Ur5::Parameters<double>()};
  std::mt19937 rng(23);
  const State<Ur5> s(rng);
  Ur5::MassMatrix<double> M_expected;
  Ur5::Vector<double> F_expected;
  Ur5::mass_matrix_and_forcing(s.t, s.q, s.qd, Ur5::Inputs<double>(Ur5::Inputs<double>::Zero()), c, M_expected, F_expected);

  // the state as one vector x = [q; qd], M into a block of a larger matrix, F through a Map
  Eigen::Matrix<double, 2 * Ur5::nq, 1> x;
  x << s.q, s.qd;
  Eigen::Matrix<double, Ur5::nq + 2, Ur5::nq + 3> big = Eigen::Matrix<double, Ur5::nq + 2, Ur5::nq + 3>::Zero();
  double forcing[Ur5::nq];
  Ur5::mass_matrix_and_forcing(s.t, x.head<Ur5::nq>(), x.tail<Ur5::nq>(), Ur5::Inputs<double>::Zero(), c,
                               big.block<Ur5::nq, Ur5::nq>(1, 2), Eigen::Map<Ur5::Vector<double>>(forcing));
  EXPECT_EQ(Ur5::MassMatrix<double>(big.block<Ur5::nq, Ur5::nq>(1, 2)), M_expected);
  EXPECT_EQ(Ur5::Vector<double>(Eigen::Map<Ur5::Vector<double>>(forcing)), F_expected);
  EXPECT_EQ(big.row(0).cwiseAbs().sum(), 0.0);  // nothing written outside the block

  // the state from a controller's plain array, with dynamic sizes
  double q_array[Ur5::nq], qd_array[Ur5::nq];
  for (int k = 0; k < Ur5::nq; ++k) q_array[k] = s.q(k), qd_array[k] = s.qd(k);
  Eigen::VectorXd qdd(Ur5::nq);
  ASSERT_TRUE(Ur5::forward_dynamics(s.t, Eigen::Map<const Eigen::VectorXd>(q_array, Ur5::nq),
                                    Eigen::Map<const Eigen::VectorXd>(qd_array, Ur5::nq), Ur5::Inputs<double>::Zero(),
                                    c, qdd));
  EXPECT_LT(relative_error(Ur5::Vector<double>(M_expected * qdd), F_expected), 1e-12);
  // the inverse dynamics of that qdd, into the tail of a state-sized vector
  Eigen::Matrix<double, 2 * Ur5::nq, 1> out = Eigen::Matrix<double, 2 * Ur5::nq, 1>::Zero();
  Ur5::inverse_dynamics(s.t, x.head<Ur5::nq>(), x.tail<Ur5::nq>(), qdd, Ur5::Inputs<double>::Zero(), c,
                        out.tail<Ur5::nq>());
  EXPECT_LT(out.tail<Ur5::nq>().cwiseAbs().maxCoeff(), 1e-10 * (1 + F_expected.cwiseAbs().maxCoeff()));
  EXPECT_EQ(out.head<Ur5::nq>().cwiseAbs().sum(), 0.0);
}

TEST(GeneratedSignatures, FloatAndAutomaticDifferentiationScalarsGiveTheRightValues) {
  std::mt19937 rng(29);
  const State<Ur5> s(rng);
  const Ur5::Constants<double> c{Ur5::Parameters<double>()};
  Ur5::Vector<double> G;
  Ur5::gravity_forces(s.q, c, G);

  // float: the same G to float precision
  const Ur5::Constants<float> cf{Ur5::Parameters<float>()};
  Ur5::Vector<float> Gf;
  Ur5::gravity_forces(s.q.cast<float>(), cf, Gf);
  EXPECT_LT(relative_error(Gf.cast<double>(), G), 1e-5);

  // AutoDiffScalar: the derivative of V along q equals G (V's gradient), exactly as generated
  using AD = Eigen::AutoDiffScalar<Eigen::Matrix<double, Ur5::nq, 1>>;
  Ur5::Vector<AD> q_ad;
  for (int k = 0; k < Ur5::nq; ++k) q_ad(k) = AD(s.q(k), Ur5::nq, k);
  Ur5::Parameters<AD> p_ad;
  for (std::size_t k = 0; k < p_ad.fields().size(); ++k) *p_ad.fields()[k] = AD(Ur5::parameter_defaults[k]);
  const AD V = Ur5::potential_energy(AD(s.t), q_ad, Ur5::Constants<AD>(p_ad));
  EXPECT_LT(relative_error(V.derivatives(), G), 1e-12);
  Ur5::Vector<AD> G_ad;
  Ur5::gravity_forces(q_ad, Ur5::Constants<AD>(p_ad), G_ad);
  for (int k = 0; k < Ur5::nq; ++k) EXPECT_NEAR(G_ad(k).value(), G(k), 1e-12 * (1 + std::abs(G(k))));
}

}  // namespace
