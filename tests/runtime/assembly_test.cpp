// eomrt::assemble against states found by hand: the two assemblies of a four-bar linkage at a
// given crank angle (circle intersection), its rates (a linear solve), a redundant closure, a
// loop that cannot close, given values that do not close it, and the independent speeds of a
// two-wheeled drive.
#include "eomrt/assembly.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <array>
#include <cmath>

namespace {

using Vector3 = Eigen::Matrix<double, 3, 1>;

/// A planar four-bar: crank a at angle q1 about the origin, coupler b at q2, rocker c at q3
/// about (d, 0), all angles absolute from the x-axis; the loop closes where
///   a cos q1 + b cos q2 - c cos q3 - d = 0,   a sin q1 + b sin q2 - c sin q3 = 0.
/// M = diag(J, J, J) (assembly weighs coordinates by M's diagonal; equal weights make the
/// nearest state Euclidean). With `redundant`, the first closure row is stated twice.
template <bool redundant>
struct FourBar {
  static constexpr int nq = 3, nu = 0, nc = redundant ? 3 : 2, nh = nc;
  static constexpr std::array<int, nh> holonomic_rows = [] {
    std::array<int, nh> rows{};
    for (int i = 0; i < nh; ++i) rows[static_cast<std::size_t>(i)] = i;
    return rows;
  }();
  template <class S>
  struct Parameters {
    S a = S(0.3), b = S(1.0), c = S(0.8), d = S(1.1), J = S(0.2);
  };
  template <class S>
  using V = Eigen::Matrix<S, nq, 1>;
  template <class S>
  static void mass_matrix_and_forcing(const S&, const V<S>&, const V<S>&, const Eigen::Matrix<S, nu, 1>&,
                                      const Parameters<S>& p, Eigen::Matrix<S, nq, nq>& M, V<S>& F) {
    M = p.J * Eigen::Matrix<S, nq, nq>::Identity();
    F.setZero();
  }
  template <class S>
  static void constraint_jacobian(const S&, const V<S>& q, const Parameters<S>& p, Eigen::Matrix<S, nc, nq>& Xi) {
    Xi.row(0) << -p.a * std::sin(q(0)), -p.b * std::sin(q(1)), p.c * std::sin(q(2));
    Xi.row(1) << p.a * std::cos(q(0)), p.b * std::cos(q(1)), -p.c * std::cos(q(2));
    if constexpr (redundant) Xi.row(2) = Xi.row(0);
  }
  template <class S>
  static void constraint_rate_term(const S&, const V<S>&, const Parameters<S>&, Eigen::Matrix<S, nc, 1>& Xi_t) {
    Xi_t.setZero();
  }
  template <class S>
  static void constraint_acceleration_term(const S&, const V<S>&, const V<S>&, const Parameters<S>&,
                                           Eigen::Matrix<S, nc, 1>& b) {
    b.setZero();  // not used by assembly
  }
  template <class S>
  static void holonomic_residuals(const S&, const V<S>& q, const Parameters<S>& p, Eigen::Matrix<S, nh, 1>& phi) {
    phi(0) = p.a * std::cos(q(0)) + p.b * std::cos(q(1)) - p.c * std::cos(q(2)) - p.d;
    phi(1) = p.a * std::sin(q(0)) + p.b * std::sin(q(1)) - p.c * std::sin(q(2));
    if constexpr (redundant) phi(2) = phi(0);
  }
  template <class S>
  static S kinetic_energy(const S&, const V<S>&, const V<S>& qd, const Parameters<S>& p) {
    return p.J * qd.squaredNorm() / 2;
  }
  template <class S>
  static S potential_energy(const S&, const V<S>&, const Parameters<S>&) {
    return S(0);
  }
};

/// The two closures at crank angle q1, by circle intersection: the coupler's far end B lies on
/// the circle of radius b about the crank pin A and on the circle of radius c about (d, 0).
std::array<Vector3, 2> closures(double q1, const FourBar<false>::Parameters<double>& p) {
  const Eigen::Vector2d A(p.a * std::cos(q1), p.a * std::sin(q1)), D(p.d, 0);
  const Eigen::Vector2d AD = D - A;
  const double L = AD.norm();
  const double x = (p.b * p.b - p.c * p.c + L * L) / (2 * L);
  const double h = std::sqrt(p.b * p.b - x * x);
  const Eigen::Vector2d e = AD / L, n(-e.y(), e.x());
  std::array<Vector3, 2> out;
  for (int k = 0; k < 2; ++k) {
    const Eigen::Vector2d B = A + x * e + (k == 0 ? h : -h) * n;
    out[static_cast<std::size_t>(k)] << q1, std::atan2(B.y() - A.y(), B.x() - A.x()),
        std::atan2(B.y() - D.y(), B.x() - D.x());
  }
  return out;
}

using Model = FourBar<false>;
using State = Eigen::Matrix<double, 6, 1>;
using Held = eomrt::HeldEntries<Model>;

Held held_entries(std::initializer_list<int> indices) {
  Held h = Held::Constant(false);
  for (int i : indices) h(i) = true;
  return h;
}

double distance(const Vector3& a, const Vector3& b) { return (a - b).norm(); }

TEST(Assembly, HoldsTheGivenCrankAngleAndTakesTheClosureNearestTheGuess) {
  const Model::Parameters<double> p;
  const std::array<Vector3, 2> branches = closures(0.5, p);
  ASSERT_GT(distance(branches[0], branches[1]), 1.0);  // two distinct assemblies
  // guesses near each branch, and guesses in between but nearer one of them
  for (int target = 0; target < 2; ++target) {
    for (double pull : {0.0, 0.3, 0.45}) {
      const Vector3 other = branches[static_cast<std::size_t>(1 - target)];
      const Vector3 mine = branches[static_cast<std::size_t>(target)];
      const Vector3 guess = mine + pull * (other - mine);
      State x;
      x << guess, 1.0, 0.0, 0.0;
      x(0) = 0.5;
      const auto report = eomrt::assemble<Model>(p, 0.0, x, held_entries({0, 3}));
      ASSERT_EQ(report.status, eomrt::AssemblyStatus::ok) << eomrt::describe(report.status);
      EXPECT_EQ(x(0), 0.5) << "the given crank angle is kept exactly";
      EXPECT_NEAR(distance(x.head<3>(), mine), 0.0, 1e-12) << "target " << target << " pull " << pull;
      EXPECT_EQ(x(3), 1.0) << "the given crank rate is kept exactly";
    }
  }
}

TEST(Assembly, SolvesTheRatesFromTheGivenCrankRate) {
  const Model::Parameters<double> p;
  const Vector3 q = closures(0.5, p)[0];
  State x;
  x << q, 1.0, 0.0, 0.0;
  const auto report = eomrt::assemble<Model>(p, 0.0, x, held_entries({0, 1, 2, 3}));
  ASSERT_EQ(report.status, eomrt::AssemblyStatus::ok);
  // by hand: the closure's two rows at q1_dot = 1 give [b s2, -c s3; b c2, -c c3] [q2_dot; q3_dot]
  // = [-a s1; -a c1] (Xi qd = 0), solved by Cramer's rule
  const double s1 = std::sin(q(0)), c1 = std::cos(q(0)), s2 = std::sin(q(1)), c2 = std::cos(q(1)),
               s3 = std::sin(q(2)), c3 = std::cos(q(2));
  const double det = p.b * s2 * (-p.c * c3) - (-p.c * s3) * (p.b * c2);
  const double q2d = ((-p.a * s1) * (-p.c * c3) - (-p.c * s3) * (-p.a * c1)) / det;
  const double q3d = (p.b * s2 * (-p.a * c1) - (-p.a * s1) * (p.b * c2)) / det;
  EXPECT_EQ(x.head<3>(), q) << "consistent coordinates are not moved";
  EXPECT_EQ(x(3), 1.0);
  EXPECT_NEAR(x(4), q2d, 1e-14);
  EXPECT_NEAR(x(5), q3d, 1e-14);
}

TEST(Assembly, MovesGivenValuesThatCannotCloseTheLoopAsLittleAsItMust) {
  const Model::Parameters<double> p;
  const Vector3 q = closures(0.5, p)[0];
  State x;
  x << q + Vector3(0.0, 0.004, -0.003), 0.0, 0.0, 0.0;  // all three given, slightly off
  const State request = x;
  const auto report = eomrt::assemble<Model>(p, 0.0, x, held_entries({0, 1, 2}));
  ASSERT_EQ(report.status, eomrt::AssemblyStatus::held_values_moved);
  EXPECT_TRUE(report.positions_released);
  EXPECT_FALSE(report.rates_released);
  Eigen::Matrix<double, 2, 1> phi;
  Model::holonomic_residuals(0.0, Vector3(x.head<3>()), p, phi);
  EXPECT_LT(phi.cwiseAbs().maxCoeff(), 1e-13);
  // the nearest closure: its displacement from the request is normal to the closure curve,
  // i.e. in the row space of the constraint gradients (equal weights: Euclidean)
  Eigen::Matrix<double, 2, 3> Xi;
  Model::constraint_jacobian(0.0, Vector3(x.head<3>()), p, Xi);
  const Vector3 tangent = Xi.row(0).cross(Xi.row(1)).transpose().normalized();
  EXPECT_NEAR(tangent.dot(x.head<3>() - request.head<3>()), 0.0, 1e-10);
  EXPECT_LT((x.head<3>() - request.head<3>()).norm(), 0.006);
}

TEST(Assembly, TakesARedundantClosureRowInItsStride) {
  using Redundant = FourBar<true>;
  const Redundant::Parameters<double> p;
  const Vector3 expected = closures(0.5, Model::Parameters<double>{})[0];
  State x;
  x << 0.5, expected(1) + 0.1, expected(2) - 0.1, 1.0, 0.0, 0.0;
  const auto report = eomrt::assemble<Redundant>(p, 0.0, x, held_entries({0, 3}));
  ASSERT_EQ(report.status, eomrt::AssemblyStatus::ok) << eomrt::describe(report.status);
  EXPECT_NEAR(distance(x.head<3>(), expected), 0.0, 1e-12);
  Eigen::Matrix<double, 3, 3> Xi;
  Redundant::constraint_jacobian(0.0, Vector3(x.head<3>()), p, Xi);
  EXPECT_LT((Xi * x.tail<3>()).cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_EQ(x(3), 1.0);
}

TEST(Assembly, NamesTheConstraintOfALoopThatCannotClose) {
  Model::Parameters<double> p;
  p.d = 3.0;  // a + b + c = 2.1 < d: the loop cannot close anywhere
  State x;
  x << 0.3, 0.2, 2.5, 0, 0, 0;  // not the stationary point q = 0 of |phi|, where nothing moves
  const State request = x;
  const auto report = eomrt::assemble<Model>(p, 0.0, x, held_entries({}));
  ASSERT_EQ(report.status, eomrt::AssemblyStatus::unreachable);
  EXPECT_TRUE(report.worst_is_position);
  EXPECT_EQ(report.worst_row, 0) << "the row along the ground link is the one that cannot close";
  // stretched straight, the loop falls short by d - (a + b + c) = 0.9
  EXPECT_NEAR(report.worst_residual, -0.9, 1e-6);
  EXPECT_EQ(x, request) << "an unreachable request is left as it was";
}

/// A two-wheeled drive on a line: x_dot = r (phi_l_dot + phi_r_dot) / 2, the wheels' spins
/// declared as the independent speeds. M = diag(m, J, J).
struct TwoWheels {
  static constexpr int nq = 3, nu = 0, nc = 1, nh = 0;
  static constexpr std::array<int, 0> holonomic_rows{};
  static constexpr int ni = 2;
  static constexpr std::array<int, ni> independent_speeds{{1, 2}};
  template <class S>
  struct Parameters {
    S r = S(0.25), m = S(10), J = S(0.05);
  };
  template <class S>
  using V = Eigen::Matrix<S, nq, 1>;
  template <class S>
  static void mass_matrix_and_forcing(const S&, const V<S>&, const V<S>&, const Eigen::Matrix<S, nu, 1>&,
                                      const Parameters<S>& p, Eigen::Matrix<S, nq, nq>& M, V<S>& F) {
    M = Eigen::Matrix<S, nq, 1>(p.m, p.J, p.J).asDiagonal();
    F.setZero();
  }
  template <class S>
  static void constraint_jacobian(const S&, const V<S>&, const Parameters<S>& p, Eigen::Matrix<S, nc, nq>& Xi) {
    Xi << 1, -p.r / 2, -p.r / 2;
  }
  template <class S>
  static void constraint_rate_term(const S&, const V<S>&, const Parameters<S>&, Eigen::Matrix<S, nc, 1>& Xi_t) {
    Xi_t.setZero();
  }
  template <class S>
  static void constraint_acceleration_term(const S&, const V<S>&, const V<S>&, const Parameters<S>&,
                                           Eigen::Matrix<S, nc, 1>& b) {
    b.setZero();
  }
  template <class S>
  static void holonomic_residuals(const S&, const V<S>&, const Parameters<S>&, Eigen::Matrix<S, nh, 1>&) {}
  template <class S>
  static S kinetic_energy(const S&, const V<S>&, const V<S>&, const Parameters<S>&) {
    return S(0);
  }
  template <class S>
  static S potential_energy(const S&, const V<S>&, const Parameters<S>&) {
    return S(0);
  }
};

TEST(Assembly, KeepsUngivenIndependentSpeedsWhereTheConstraintsAllow) {
  const TwoWheels::Parameters<double> p;
  Eigen::Matrix<double, 6, 1> x;
  x << 0, 0, 0, 0, 2.0, 0;  // the left wheel's spin given: x_dot follows, the right wheel stays
  auto report = eomrt::assemble<TwoWheels>(p, 0.0, x, eomrt::HeldEntries<TwoWheels>(
                                                          (Eigen::Array<bool, 6, 1>() << 0, 0, 0, 0, 1, 0).finished()));
  ASSERT_EQ(report.status, eomrt::AssemblyStatus::ok);
  EXPECT_DOUBLE_EQ(x(3), p.r);
  EXPECT_EQ(x(4), 2.0);
  EXPECT_EQ(x(5), 0.0);
}

TEST(Assembly, DrivesStraightWhenOnlyTheForwardSpeedIsGiven) {
  const TwoWheels::Parameters<double> p;
  Eigen::Matrix<double, 6, 1> x;
  x << 0, 0, 0, 1.0, 0, 0;  // x_dot given: the independent speeds must move, and move alike
  auto report = eomrt::assemble<TwoWheels>(p, 0.0, x, eomrt::HeldEntries<TwoWheels>(
                                                          (Eigen::Array<bool, 6, 1>() << 0, 0, 0, 1, 0, 0).finished()));
  ASSERT_EQ(report.status, eomrt::AssemblyStatus::ok);
  EXPECT_EQ(x(3), 1.0);
  EXPECT_NEAR(x(4), 1.0 / p.r, 1e-14);
  EXPECT_NEAR(x(5), 1.0 / p.r, 1e-14);
}

TEST(Assembly, ReleasesGivenRatesThatContradictEachOther) {
  const TwoWheels::Parameters<double> p;
  Eigen::Matrix<double, 6, 1> x;
  x << 0, 0, 0, 1.0, 4.0, 4.1;  // r (4 + 4.1) / 2 = 1.0125, not 1
  auto report = eomrt::assemble<TwoWheels>(p, 0.0, x, eomrt::HeldEntries<TwoWheels>(
                                                          (Eigen::Array<bool, 6, 1>() << 0, 0, 0, 1, 1, 1).finished()));
  ASSERT_EQ(report.status, eomrt::AssemblyStatus::held_values_moved);
  EXPECT_TRUE(report.rates_released);
  EXPECT_NEAR(x(3) - p.r * (x(4) + x(5)) / 2, 0.0, 1e-14);
  // weighted by sqrt(M_jj): the heavy chassis' speed moves least
  EXPECT_LT(std::abs(x(3) - 1.0), std::abs(x(4) - 4.0));
}

}  // namespace
