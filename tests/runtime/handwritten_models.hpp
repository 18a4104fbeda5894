#pragma once
// Models written by hand against the runtime's model contract (model_traits.hpp), so that the
// runtime is tested without the generator: each is small enough to check on paper.
#include <Eigen/Core>
#include <array>
#include <cmath>

namespace eomrt::testing {

/// The constraint functions of a model without constraints (nc = nh = 0), inherited.
template <int nq>
struct Unconstrained {
  static constexpr int nc = 0, nh = 0;
  static constexpr std::array<int, 0> holonomic_rows{};
  template <class S, class P>
  static void constraint_jacobian(const S&, const Eigen::Matrix<S, nq, 1>&, const P&, Eigen::Matrix<S, 0, nq>&) {}
  template <class S, class P>
  static void constraint_rate_term(const S&, const Eigen::Matrix<S, nq, 1>&, const P&, Eigen::Matrix<S, 0, 1>&) {}
  template <class S, class P>
  static void constraint_acceleration_term(const S&, const Eigen::Matrix<S, nq, 1>&, const Eigen::Matrix<S, nq, 1>&,
                                           const P&, Eigen::Matrix<S, 0, 1>&) {}
  template <class S, class P>
  static void holonomic_residuals(const S&, const Eigen::Matrix<S, nq, 1>&, const P&, Eigen::Matrix<S, 0, 1>&) {}
};

/// Planar pendulum in Cartesian coordinates (x, y) of the bob, gravity -g along y, rod length
/// l: phi = x^2 + y^2 - l^2, Xi = [2x, 2y], b = 2 (xd^2 + yd^2).
struct CartesianPendulum {
  static constexpr int nq = 2, nu = 0, nc = 1, nh = 1;
  static constexpr std::array<int, nh> holonomic_rows{{0}};
  template <class S>
  struct Parameters {
    S m = S(1.5), l = S(0.8), g = S(9.81);
  };
  template <class S>
  using V = Eigen::Matrix<S, nq, 1>;
  template <class S>
  static void mass_matrix_and_forcing(const S&, const V<S>&, const V<S>&,
                                      const Eigen::Matrix<S, nu, 1>&, const Parameters<S>& p,
                                      Eigen::Matrix<S, nq, nq>& M, V<S>& F) {
    M << p.m, 0, 0, p.m;
    F << 0, -p.m * p.g;
  }
  template <class S>
  static void constraint_jacobian(const S&, const V<S>& q, const Parameters<S>&,
                                  Eigen::Matrix<S, nc, nq>& Xi) {
    Xi << 2 * q(0), 2 * q(1);
  }
  template <class S>
  static void constraint_rate_term(const S&, const V<S>&, const Parameters<S>&,
                                   Eigen::Matrix<S, nc, 1>& Xi_t) {
    Xi_t.setZero();
  }
  template <class S>
  static void constraint_acceleration_term(const S&, const V<S>&, const V<S>& qd,
                                           const Parameters<S>&, Eigen::Matrix<S, nc, 1>& b) {
    b(0) = 2 * qd.squaredNorm();
  }
  template <class S>
  static void holonomic_residuals(const S&, const V<S>& q, const Parameters<S>& p,
                                  Eigen::Matrix<S, nh, 1>& phi) {
    phi(0) = q.squaredNorm() - p.l * p.l;
  }
  template <class S>
  static S kinetic_energy(const S&, const V<S>&, const V<S>& qd, const Parameters<S>& p) {
    return p.m * qd.squaredNorm() / 2;
  }
  template <class S>
  static S potential_energy(const S&, const V<S>& q, const Parameters<S>& p) {
    return p.m * p.g * q(1);
  }
};

/// Harmonic oscillator m qdd = -k q + u, unconstrained, one input.
struct Oscillator : Unconstrained<1> {
  static constexpr int nq = 1, nu = 1;
  template <class S>
  struct Parameters {
    S m = S(2), k = S(8);
  };
  template <class S>
  using V = Eigen::Matrix<S, nq, 1>;
  template <class S>
  static void mass_matrix_and_forcing(const S&, const V<S>& q, const V<S>&,
                                      const Eigen::Matrix<S, nu, 1>& u, const Parameters<S>& p,
                                      Eigen::Matrix<S, nq, nq>& M, V<S>& F) {
    M(0, 0) = p.m;
    F(0) = -p.k * q(0) + u(0);
  }
  template <class S>
  static S kinetic_energy(const S&, const V<S>&, const V<S>& qd, const Parameters<S>& p) {
    return p.m * qd(0) * qd(0) / 2;
  }
  template <class S>
  static S potential_energy(const S&, const V<S>& q, const Parameters<S>& p) {
    return p.k * q(0) * q(0) / 2;
  }
};

/// The oscillator with its own forward dynamics, as a generated tree has (false when m <= 0).
struct OscillatorWithForwardDynamics : Oscillator {
  template <class S>
  static bool forward_dynamics(const S&, const V<S>& q, const V<S>&, const Eigen::Matrix<S, nu, 1>& u,
                               const Parameters<S>& p, V<S>& qdd) {
    qdd(0) = (-p.k * q(0) + u(0)) / p.m;
    return p.m > S(0);
  }
};

/// The same, declaring that M, F and a Cholesky solve are cheaper than its forward_dynamics()
/// (as a generated small model does): the runtime keeps the mass-matrix path.
struct OscillatorPreferringMassMatrix : OscillatorWithForwardDynamics {
  static constexpr bool prefers_forward_dynamics = false;
};

/// A mass described redundantly by two coordinates, T = m (xd1 + xd2)^2 / 2 (M of rank 1, as
/// for a quaternion), pulled by a spring k (x1 + x2) and tied by the constraint x1 - x2 = 0
/// (Constrained) or not at all (the unconstrained variant, whose M is singular).
template <bool Constrained>
struct RedundantMass {
  static constexpr int nq = 2, nu = 0, nc = Constrained ? 1 : 0, nh = nc;
  static constexpr std::array<int, nh> holonomic_rows{};  // {0} when constrained
  template <class S>
  struct Parameters {
    S m = S(3), k = S(12);
  };
  template <class S>
  using V = Eigen::Matrix<S, nq, 1>;
  template <class S>
  static void mass_matrix_and_forcing(const S&, const V<S>& q, const V<S>&,
                                      const Eigen::Matrix<S, nu, 1>&, const Parameters<S>& p,
                                      Eigen::Matrix<S, nq, nq>& M, V<S>& F) {
    M.setConstant(p.m);
    F.setConstant(-p.k * (q(0) + q(1)));
  }
  template <class S>
  static void constraint_jacobian(const S&, const V<S>&, const Parameters<S>&,
                                  Eigen::Matrix<S, nc, nq>& Xi) {
    if constexpr (Constrained) Xi << 1, -1;
  }
  template <class S>
  static void constraint_rate_term(const S&, const V<S>&, const Parameters<S>&,
                                   Eigen::Matrix<S, nc, 1>& Xi_t) {
    Xi_t.setZero();
  }
  template <class S>
  static void constraint_acceleration_term(const S&, const V<S>&, const V<S>&,
                                           const Parameters<S>&, Eigen::Matrix<S, nc, 1>& b) {
    b.setZero();
  }
  template <class S>
  static void holonomic_residuals(const S&, const V<S>& q, const Parameters<S>&,
                                  Eigen::Matrix<S, nh, 1>& phi) {
    if constexpr (Constrained) phi(0) = q(0) - q(1);
  }
  template <class S>
  static S kinetic_energy(const S&, const V<S>&, const V<S>& qd, const Parameters<S>& p) {
    return p.m * (qd(0) + qd(1)) * (qd(0) + qd(1)) / 2;
  }
  template <class S>
  static S potential_energy(const S&, const V<S>& q, const Parameters<S>& p) {
    return p.k * (q(0) + q(1)) * (q(0) + q(1)) / 2;
  }
};
/// qdd = qd^2 from qd(0) = 1: qd = 1 / (1 - t) blows up at t = 1 (a finite-time singularity).
struct BlowUp : Unconstrained<1> {
  static constexpr int nq = 1, nu = 0;
  template <class S>
  struct Parameters {};
  template <class S>
  using V = Eigen::Matrix<S, nq, 1>;
  template <class S>
  static void mass_matrix_and_forcing(const S&, const V<S>&, const V<S>& qd,
                                      const Eigen::Matrix<S, nu, 1>&, const Parameters<S>&,
                                      Eigen::Matrix<S, nq, nq>& M, V<S>& F) {
    M(0, 0) = 1;
    F(0) = qd(0) * qd(0);
  }
  template <class S>
  static S kinetic_energy(const S&, const V<S>&, const V<S>& qd, const Parameters<S>&) {
    return qd(0) * qd(0) / 2;
  }
  template <class S>
  static S potential_energy(const S&, const V<S>&, const Parameters<S>&) {
    return S(0);
  }
};

}  // namespace eomrt::testing
