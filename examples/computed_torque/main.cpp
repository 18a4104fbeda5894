// Computed-torque tracking control of the double pendulum from its generated header.
//
// The plant is M(q) qdd = F(q, qd) + tau (joint torques as generalized forces). The control
// law tau = M(q) (qdd_ref + Kd (qd_ref - qd) + Kp (q_ref - q)) - F(q, qd) cancels the
// dynamics, so the tracking error obeys e'' + Kd e' + Kp e = 0 and decays. The loop is
// integrated with classical RK4 at 1 ms; the controller calls mass_matrix_and_forcing once
// per evaluation, with no heap allocation, through the model's Constants: the values that
// depend on the parameters only, computed once before the loop.
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <cmath>
#include <cstdio>

#include "double_pendulum.hpp"

using Model = eomgen_models::double_pendulum::Model;
using Vector = Model::Vector<double>;
using State = Eigen::Matrix<double, 2 * Model::nq, 1>;

namespace {

const Model::Constants<double> constants{Model::Parameters<double>()};
const double kp = 100.0, kd = 20.0;  // critically damped: e'' + 20 e' + 100 e = 0

// reference trajectory: both joints swing sinusoidally
void reference(double t, Vector& q, Vector& qd, Vector& qdd) {
  const double w = 2.0;
  q << 0.5 * std::sin(w * t), 0.3 * std::cos(w * t);
  qd << 0.5 * w * std::cos(w * t), -0.3 * w * std::sin(w * t);
  qdd << -0.5 * w * w * std::sin(w * t), -0.3 * w * w * std::cos(w * t);
}

// closed-loop state derivative [qd; qdd]
State closed_loop(double t, const State& x) {
  const Vector q = x.head<Model::nq>(), qd = x.tail<Model::nq>();
  Model::MassMatrix<double> M;
  Vector F;
  Model::mass_matrix_and_forcing(t, q, qd, Model::Inputs<double>(), constants, M, F);
  Vector q_ref, qd_ref, qdd_ref;
  reference(t, q_ref, qd_ref, qdd_ref);
  const Vector tau = M * (qdd_ref + kd * (qd_ref - qd) + kp * (q_ref - q)) - F;
  State dx;
  dx << qd, M.llt().solve(F + tau);
  return dx;
}

}  // namespace

int main() {
  State x = State::Zero();  // start at rest, hanging: 0.3 rad away from the reference
  const double h = 1e-3;
  double t = 0.0;
  std::printf("%6s %12s\n", "t [s]", "|q - q_ref|");
  for (int step = 0; step <= 5000; ++step) {
    if (step % 1000 == 0) {
      Vector q_ref, qd_ref, qdd_ref;
      reference(t, q_ref, qd_ref, qdd_ref);
      std::printf("%6.2f %12.3e\n", t, (x.head<Model::nq>() - q_ref).norm());
    }
    if (step == 5000) break;
    const State k1 = closed_loop(t, x), k2 = closed_loop(t + h / 2, x + h / 2 * k1);
    const State k3 = closed_loop(t + h / 2, x + h / 2 * k2), k4 = closed_loop(t + h, x + h * k3);
    x += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    t += h;
  }
  Vector q_ref, qd_ref, qdd_ref;
  reference(t, q_ref, qd_ref, qdd_ref);
  const double error = (x.head<Model::nq>() - q_ref).norm();
  std::printf("final tracking error %.3e rad (%s)\n", error, error < 1e-6 ? "converged" : "NOT converged");
  return error < 1e-6 ? 0 : 1;
}
