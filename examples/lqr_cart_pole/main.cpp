// Finite-horizon discrete-time LQR of the cart-pole, from the exact derivatives of one RK4 step.
//
// A discrete-time controller designs on the model it runs: x_{k+1} = Step(x_k, u_k), one RK4 step
// of h = 10 ms with the force held (zero-order hold), x = [cart position, pole angle, their
// rates], the pole upright at angle 0. eomrt::step_derivatives gives Phi = dStep/dx and
// Gamma = dStep/du at the upright equilibrium exactly (the chain rule through the four stages),
// with no continuous-to-discrete conversion. The backward Riccati recursion over N steps,
//
//   K_k = (R + Gamma^T P_{k+1} Gamma)^-1 Gamma^T P_{k+1} Phi,
//   P_k = Q + Phi^T P_{k+1} (Phi - Gamma K_k),     P_N = Q_f,
//
// gives the time-varying gains of u_k = -K_k x_k. The plant is the nonlinear model stepped by the
// runtime's own RK4 (eomrt::rk_step with the forward dynamics), started with the pole 0.3 rad
// from upright and the cart at rest. The run fails unless, after N steps, the pole is within
// 1e-3 rad of upright and the cart within 1 cm of home (they end at 2e-6 rad and 6e-6 m here),
// and unless the same start without control has the pole fallen (the controller is doing the
// work). With the sign of Gamma flipped in the design the closed loop diverges (the cart ends
// 4 m away), and the run fails.
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdio>

#include "cart_pole.hpp"
#include "eomrt/dynamics_unconstrained.hpp"
#include "eomrt/rk_fixed.hpp"
#include "eomrt/step_derivatives.hpp"

namespace {

using Model = eomgen_models::cart_pole::Model;
constexpr int n = 2 * Model::nq;  // 4
using State = Eigen::Matrix<double, n, 1>;
using Gain = Eigen::Matrix<double, Model::nu, n>;
constexpr double h = 0.01;   // [s] the controller's sample time and the integrator's step
constexpr int steps = 500;   // 5 s horizon

/// the plant: one RK4 step of the nonlinear model with the force u held
State plant_step(const Model::Constants<double>& c, eomrt::DynamicsWorkspace<Model>& ws, double t,
                 const State& x, const Model::Inputs<double>& u) {
  const auto f = [&](double time, const State& state, State& dxdt) {
    const Model::Vector<double> q = state.head<Model::nq>(), qd = state.tail<Model::nq>();
    const bool ok = eomrt::forward_dynamics_unconstrained<Model>(c, ws, time, q, qd, u) == eomrt::DynamicsStatus::ok;
    dxdt << qd, ws.qdd;
    return ok;
  };
  State next = x;
  eomrt::RkWorkspace<State, 4> rk(n);
  if (!eomrt::rk_step(eomrt::rk4, f, t, next, h, rk)) next.setConstant(NAN);
  return next;
}

}  // namespace

int main() {
  const Model::Parameters<double> p{};
  const Model::Constants<double> c(p);

  // the discrete-time model at the upright equilibrium, exactly
  static eomrt::StepDerivativesWorkspace<Model, 4> step;
  if (eomrt::step_derivatives<Model>(eomrt::rk4, c, step, 0.0, h, State::Zero().eval(),
                                     Model::Inputs<double>::Zero().eval()) != eomrt::DynamicsStatus::ok) {
    std::fprintf(stderr, "the step's derivatives failed at the equilibrium\n");
    return 1;
  }
  const Eigen::Matrix<double, n, n> Phi = step.Phi;
  const Eigen::Matrix<double, n, 1> Gamma = step.Gamma;

  // the backward Riccati recursion
  Eigen::Matrix<double, n, n> Q = Eigen::Matrix<double, n, n>::Zero();
  Q.diagonal() << 100, 100, 10, 1;
  const double R = 0.1;
  Eigen::Matrix<double, n, n> P = 100 * Q;
  static std::array<Gain, steps> K;
  for (int k = steps - 1; k >= 0; --k) {
    const double S = R + (Gamma.transpose() * P * Gamma).value();
    K[k] = (Gamma.transpose() * P * Phi) / S;
    P = Q + Phi.transpose() * P * (Phi - Gamma * K[k]);
    P = ((P + P.transpose()) / 2).eval();  // kept symmetric against rounding
  }

  // the closed loop on the nonlinear plant, and the same start left alone
  eomrt::DynamicsWorkspace<Model> ws;
  State x = State::Zero(), free = State::Zero();
  x(1) = free(1) = 0.3;  // [rad] the pole tilted
  double largest_force = 0;
  for (int k = 0; k < steps; ++k) {
    const double t = k * h;
    Model::Inputs<double> u = -K[k] * x;
    largest_force = std::max(largest_force, std::abs(u(0)));
    x = plant_step(c, ws, t, x, u);
    free = plant_step(c, ws, t, free, Model::Inputs<double>::Zero());
  }
  std::printf("LQR from step derivatives (rk4, h = %g s, %d steps): first gain K_0 = [%.4g %.4g %.4g %.4g]\n", h,
              steps, K[0](0), K[0](1), K[0](2), K[0](3));
  std::printf("after %g s: cart %.3g m, pole %.3g rad (largest force %.3g N); without control the pole is at "
              "%.3g rad\n",
              steps * h, x(0), x(1), largest_force, free(1));
  const bool upright = std::abs(x(1)) < 1e-3 && std::abs(x(0)) < 1e-2 && x.allFinite();
  const bool fallen = std::abs(free(1)) > 1.0;
  if (!upright) std::fprintf(stderr, "error: the controller did not bring the pole upright and the cart home\n");
  if (!fallen) std::fprintf(stderr, "error: the pole did not fall without control; the check proves nothing\n");
  return upright && fallen ? 0 : 1;
}
