// Adaptive control of the UR5 carrying an unknown payload, from the arm's generated header.
//
// The arm tracks a joint trajectory q_d(t) while holding a payload at its tool: a point mass dm
// (2 kg) at r = (0, 0, 0.1 m) in the tool frame (tool0 is the wrist_3_link frame, z along the
// tool's axis). The controller knows the arm's nominal model but not dm, and estimates it online
// with the law of Slotine and Li:
//
//   e = q - q_d,   qd_r = qd_d - Lambda e,   qdd_r = qdd_d - Lambda (qd - qd_d),   s = qd - qd_r
//   tau     = Y(q, qd, qd_r, qdd_r) pi_hat - K s       = M_hat qdd_r + C_hat(q, qd) qd_r + G_hat - K s
//   pi_hat  = pi_0 + dm_hat w
//   dm_hat' = -gamma (Y(q, qd, qd_r, qdd_r) w)^T s
//
// pi is the vector of inertial parameters, ten per body (Model::inertial_parameter_names): its
// mass m, first moment m c and inertia about its link's origin, in its frame. A point mass dm at
// r on the last body adds dm to its m, dm r to its m c and dm (r.r I - r r^T) to its inertia, so
// the true parameters are pi_0 + dm w: linear in dm, with w fixed by r alone. The closed loop is
// M s' + (C + K) s = Y w (dm_hat - dm), and V = s^T M s / 2 + (dm_hat - dm)^2 / (2 gamma) has
// V' = -s^T K s, because dM/dt - 2C is skew-symmetric for the Christoffel C. So s -> 0 (and with
// it e -> 0), and dm_hat -> dm when Y w does not die out along the motion: here the payload's
// weight alone keeps it away from zero, and the trajectory moves every joint.
//
// The regressor of the header gives Y(q, qd, qdd) with Y pi = M qdd + C(q, qd) qd + G(q) (the
// terms of M qdd - F that hold inertial parameters), while the law needs C(q, qd) qd_r with two
// different velocities. The Christoffel form C(q, a) b = sum_ij Gamma_kij a_i b_j is symmetric in
// a and b, so it follows from the quadratic one by polarization, from three calls of the
// regressor:
//
//   Y(q, qd, qd_r, qdd_r) = Y(q, 0, qdd_r) + (Y(q, qd + qd_r, 0) - Y(q, qd - qd_r, 0)) / 4
//
// (the first term is M qdd_r + G, the difference 4 C(q, qd) qd_r, G cancelling). main() checks
// that against mass_matrix, coriolis_matrix and gravity_forces, and checks pi_0 + dm w against
// inertial_parameters of the plant's own parameters, before the loop.
//
// The plant is the generated model with the payload put into the wrist_3_link's mass, centre of
// mass and inertia (Parameters), integrated by RK4 at 1 ms with forward_dynamics; the joint
// torques enter as its inputs u (F holds +u). The controller runs at 1 kHz, holding tau over each
// step and stepping dm_hat by Euler, and allocates nothing: every matrix has a size fixed at
// compile time (EIGEN_RUNTIME_NO_MALLOC with Eigen's assertions on checks it).
//
// The arm starts at rest on the desired motion with dm_hat = 0; the payload's weight pulls it
// off, and the estimate takes it back: dm_hat is within 2% of dm after about 0.9 s and then
// wobbles by under 0.1% (the 1 ms sample-and-hold of the torque, read as payload), the tracking
// error settles below 1e-4 rad. The same run with the adaptation off, dm_hat = 0, shows what
// the payload costs the nominal controller: about 0.15 rad, mostly at the wrist, whose gains
// K are sized for its own small inertia, not the payload's. The run fails if the estimate leaves
// 2% of dm in the last 5 s, if the tracking error there exceeds 1e-3 rad or a tenth of the
// nominal controller's, or if a torque exceeds its joint's limit.
#include <cstdio>
#include <cstdlib>
#define eigen_assert(x) \
  ((x) ? void(0) : (std::fprintf(stderr, "Eigen assertion failed: %s\n", #x), std::abort()))
#define EIGEN_RUNTIME_NO_MALLOC

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <string>

#include "ur5.hpp"

using Model = eomgen_models::ur5::Model;
using Vector = Model::Vector<double>;
using Inputs = Model::Inputs<double>;
using Parameters = Model::Parameters<double>;
using InertialParameters = Eigen::Matrix<double, Model::npi, 1>;
using Regressor = Eigen::Matrix<double, Model::nq, Model::npi>;
using State = Eigen::Matrix<double, 2 * Model::nq, 1>;  // [q; qd]

namespace {

// the payload: its mass (what the controller estimates) and where it sits on the last link
const double payload_mass = 2.0;    // kg
const double payload_offset = 0.1;  // m, along the tool's z axis

// The plant's parameters: the nominal arm with the point mass merged into the wrist_3_link,
// whose URDF inertial has its centre of mass on the z axis and its inertia about that centre.
Parameters with_payload(double dm, double d) {
  Parameters p;
  const double m = p.wrist_3_link_mass, c = p.wrist_3_link_com_z;
  const double mass = m + dm, com = (m * c + dm * d) / mass;
  // parallel axes: both masses sit on the z axis, so x and y gain, z does not
  const double shift = m * (c - com) * (c - com) + dm * (d - com) * (d - com);
  p.wrist_3_link_mass = mass;
  p.wrist_3_link_com_z = com;
  p.wrist_3_link_ixx += shift;
  p.wrist_3_link_iyy += shift;
  return p;
}

// w = d pi / d dm for a point mass at r = (0, 0, d) on the wrist_3_link: m 1, m c r, inertia
// r.r I - r r^T = diag(d^2, d^2, 0); found by name in the header's list of inertial parameters
InertialParameters payload_direction(double d) {
  const std::string body = "wrist_3_link_body.";
  const struct {
    const char* name;
    double value;
  } entries[] = {{"m", 1.0}, {"mz", d}, {"Ixx", d * d}, {"Iyy", d * d}};
  InertialParameters w = InertialParameters::Zero();
  for (const auto& entry : entries) {
    const auto* names = Model::inertial_parameter_names.data();
    const auto* found = std::find_if(names, names + Model::npi,
                                     [&](const char* name) { return body + entry.name == name; });
    if (found == names + Model::npi) {
      std::fprintf(stderr, "no inertial parameter %s%s in the header\n", body.c_str(), entry.name);
      std::exit(1);
    }
    w(found - names) = entry.value;
  }
  return w;
}

// the controller's model (nominal, no payload) and the plant's (with it)
const Model::Constants<double> nominal{Parameters()};
const Model::Constants<double> plant_model{with_payload(payload_mass, payload_offset)};

// Y(q, qd, qd_r, qdd_r) pi = M qdd_r + C(q, qd) qd_r + G, by polarization (see the top)
void slotine_li_regressor(const Vector& q, const Vector& qd, const Vector& qd_r, const Vector& qdd_r,
                          Regressor& Y) {
  Regressor Y_plus, Y_minus;
  Model::regressor(0.0, q, Vector::Zero(), qdd_r, nominal, Y);
  Model::regressor(0.0, q, qd + qd_r, Vector::Zero(), nominal, Y_plus);
  Model::regressor(0.0, q, qd - qd_r, Vector::Zero(), nominal, Y_minus);
  Y += 0.25 * (Y_plus - Y_minus);
}

// the desired motion: from rest at a working posture, every joint swings by 2a at a frequency
// of its own, with no common period over the run, so the arm keeps visiting new configurations
const Vector q_home = (Vector() << 0.0, -1.2, 1.5, -1.87, -1.57, 0.0).finished();
const Vector amplitude = (Vector() << 0.25, 0.15, 0.2, 0.25, 0.25, 0.25).finished();  // rad
const Vector frequency = (Vector() << 0.7, 1.1, 1.3, 1.7, 1.9, 2.3).finished();       // rad/s

void desired(double t, Vector& q, Vector& qd, Vector& qdd) {
  for (int i = 0; i < Model::nq; ++i) {
    const double a = amplitude(i), w = frequency(i);
    q(i) = q_home(i) + a * (1 - std::cos(w * t));
    qd(i) = a * w * std::sin(w * t);
    qdd(i) = a * w * w * std::cos(w * t);
  }
}

// the joints' torque limits from the URDF (effort), to check the commands are ones the arm can give
const Vector effort_limit = (Vector() << 150, 150, 150, 28, 28, 28).finished();  // N m

State plant(double t, const State& x, const Inputs& u) {
  Vector qdd;
  if (!Model::forward_dynamics(t, x.head<Model::nq>(), x.tail<Model::nq>(), u, plant_model, qdd)) {
    std::fprintf(stderr, "forward dynamics failed at t = %g\n", t);
    std::exit(1);
  }
  State dx;
  dx << x.tail<Model::nq>(), qdd;
  return dx;
}

struct Run {
  double dm_hat;                   // the estimate at the end
  double max_error_late;           // max |q - q_d| [rad] over the last 5 s
  double max_estimate_error_late;  // max |dm_hat - dm| / dm over the last 5 s
  double settling_time;            // from when on |dm_hat - dm| / dm stays below 2% [s]
  Vector max_torque;               // max |tau| [N m] per joint
};

// Simulates 20 s from rest on the desired start; adapt = false keeps dm_hat = 0.
Run simulate(bool adapt, const InertialParameters& w, const Vector& K, double lambda, double gamma,
             bool print) {
  InertialParameters pi_0;
  Model::inertial_parameters(nominal, pi_0);
  const double h = 1e-3, t_end = 20.0;
  const int steps = static_cast<int>(std::lround(t_end / h));
  Vector q_d, qd_d, qdd_d;
  desired(0.0, q_d, qd_d, qdd_d);
  State x;
  x << q_d, qd_d;
  double dm_hat = 0.0, max_error_late = 0.0, max_estimate_error_late = 0.0, settling_time = 0.0;
  Vector max_torque = Vector::Zero();

  Eigen::internal::set_is_malloc_allowed(false);  // from here on, any allocation aborts the run
  for (int step = 0; step <= steps; ++step) {
    const double t = step * h;
    const Vector q = x.head<Model::nq>(), qd = x.tail<Model::nq>();
    desired(t, q_d, qd_d, qdd_d);
    const Vector e = q - q_d;
    const double estimate_error = std::abs(dm_hat - payload_mass) / payload_mass;
    if (estimate_error >= 0.02) settling_time = t + h;
    if (t >= t_end - 5.0) {
      max_error_late = std::max(max_error_late, e.cwiseAbs().maxCoeff());
      max_estimate_error_late = std::max(max_estimate_error_late, estimate_error);
    }
    if (print && (step % 2000 == 0 || (t < 2.0 && step % 250 == 0)))
      std::printf("%6.2f %14.3e %12.4f\n", t, e.cwiseAbs().maxCoeff(), dm_hat);
    if (step == steps) break;

    // the controller, once per millisecond
    const Vector qd_r = qd_d - lambda * e, qdd_r = qdd_d - lambda * (qd - qd_d), s = qd - qd_r;
    Regressor Y;
    slotine_li_regressor(q, qd, qd_r, qdd_r, Y);
    const Vector Y_w = Y * w;  // how the torque changes with the payload mass
    const Inputs tau = Y * pi_0 + dm_hat * Y_w - K.cwiseProduct(s);
    if (adapt) dm_hat -= h * gamma * Y_w.dot(s);
    max_torque = max_torque.cwiseMax(tau.cwiseAbs());

    const State k1 = plant(t, x, tau), k2 = plant(t + h / 2, x + h / 2 * k1, tau);
    const State k3 = plant(t + h / 2, x + h / 2 * k2, tau), k4 = plant(t + h, x + h * k3, tau);
    x += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  Eigen::internal::set_is_malloc_allowed(true);
  return {dm_hat, max_error_late, max_estimate_error_late, settling_time, max_torque};
}

}  // namespace

int main() {
  const InertialParameters w = payload_direction(payload_offset);
  bool ok = true;

  // 1. The payload is linear in pi: the plant's own inertial parameters are pi_0 + dm w.
  {
    InertialParameters pi_0, pi_plant;
    Model::inertial_parameters(nominal, pi_0);
    Model::inertial_parameters(plant_model, pi_plant);
    const double mismatch = (pi_plant - pi_0 - payload_mass * w).cwiseAbs().maxCoeff();
    std::printf("check: pi(plant) - pi_0 - dm w = %.1e\n", mismatch);
    if (!(mismatch < 1e-12)) ok = false;
  }
  // 2. The polarized regressor is M qdd_r + C(q, qd) qd_r + G with the header's M, C and G, at
  //    a state with every entry different from zero.
  {
    const Vector q = (Vector() << 0.3, -1.0, 1.2, -1.5, -1.2, 0.4).finished();
    const Vector qd = (Vector() << 0.5, -0.4, 0.3, 0.8, -0.6, 0.2).finished();
    const Vector qd_r = (Vector() << -0.2, 0.7, -0.5, 0.1, 0.9, -0.3).finished();
    const Vector qdd_r = (Vector() << 1.0, -0.5, 0.8, -1.2, 0.6, 1.5).finished();
    Regressor Y;
    slotine_li_regressor(q, qd, qd_r, qdd_r, Y);
    InertialParameters pi_0;
    Model::inertial_parameters(nominal, pi_0);
    Model::MassMatrix<double> M, C;
    Vector G;
    Model::mass_matrix(0.0, q, nominal, M);
    Model::coriolis_matrix(q, qd, nominal, C);
    Model::gravity_forces(q, nominal, G);
    const Vector expected = M * qdd_r + C * qd_r + G;
    const double mismatch = (Y * pi_0 - expected).norm() / expected.norm();
    std::printf("check: |Y(q, qd, qd_r, qdd_r) pi_0 - (M qdd_r + C qd_r + G)| / |..| = %.1e\n", mismatch);
    if (!(mismatch < 1e-12)) ok = false;
  }
  if (!ok) {
    std::fprintf(stderr, "FAILED: a check of the header's functions failed\n");
    return 1;
  }

  // Gains. K in proportion to the nominal inertia each joint sees at the working posture (from
  // 2.3 kg m^2 at the shoulder down to 1.3e-4 kg m^2 at the last wrist joint), so that every
  // joint's s decays at about 100/s: one K for all would make the light wrist unstable at a 1 ms
  // sample (K h / M above 2) or leave the shoulder limp. With Lambda = 20 the error then obeys
  // about e'' + 120 e' + 2000 e = 0. gamma sets how fast dm_hat follows.
  Model::MassMatrix<double> M_home;
  Model::mass_matrix(0.0, q_home, nominal, M_home);
  const Vector K = 100.0 * M_home.diagonal();
  const double lambda = 20.0, gamma = 5.0;

  std::printf("true payload %.3f kg at %.2f m on the tool axis\n", payload_mass, payload_offset);
  std::printf("%6s %14s %12s\n", "t [s]", "max|e| [rad]", "dm_hat [kg]");
  const Run adaptive = simulate(true, w, K, lambda, gamma, true);
  const Run fixed = simulate(false, w, K, lambda, gamma, false);
  std::printf("payload estimate: %.4f kg after 20 s (true %.4f kg), within 2%% from t = %.3f s on, "
              "within %.2f%% over the last 5 s\n",
              adaptive.dm_hat, payload_mass, adaptive.settling_time, 100 * adaptive.max_estimate_error_late);
  std::printf("max tracking error over the last 5 s: %.3e rad adaptive, %.3e rad with dm_hat = 0\n",
              adaptive.max_error_late, fixed.max_error_late);
  std::printf("peak |tau| [N m]:");
  for (int i = 0; i < Model::nq; ++i) std::printf(" %.2f", adaptive.max_torque(i));
  std::printf("\n");

  // tolerances: the estimate within 2% of the payload over the whole of the last 5 s; tracking
  // below 1e-3 rad (about a millimetre at the tool) and ten times better than the nominal
  // controller's; torques within the joints' limits
  if (!(adaptive.max_estimate_error_late < 0.02)) {
    std::fprintf(stderr, "FAILED: the payload estimate is off by up to %.2f%% over the last 5 s (tolerance 2%%)\n",
                 100 * adaptive.max_estimate_error_late);
    ok = false;
  }
  if (!(adaptive.max_error_late < 1e-3 && adaptive.max_error_late < 0.1 * fixed.max_error_late)) {
    std::fprintf(stderr, "FAILED: tracking error %.3e rad (tolerance 1e-3 rad and a tenth of %.3e rad)\n",
                 adaptive.max_error_late, fixed.max_error_late);
    ok = false;
  }
  for (int i = 0; i < Model::nq; ++i) {
    if (adaptive.max_torque(i) > effort_limit(i)) {
      std::fprintf(stderr, "FAILED: joint %s needs %.1f N m, over its limit %.0f N m\n",
                   Model::coordinate_names[i], adaptive.max_torque(i), effort_limit(i));
      ok = false;
    }
  }
  if (ok) std::printf("payload estimated within 2%%, tracking within 1e-3 rad: OK\n");
  return ok ? 0 : 1;
}
