// Tests for the one KKT solve (kkt_system.hpp) and the regularity tests (regularity.hpp), with
// fixed sizes as the runtime uses them and dynamic ones as the generator does: a system solved
// by hand, dependent constraints, a singular M whose KKT matrix is regular (a quaternion), and
// the Cholesky pivot test on either side of its threshold.

#include "runtime/no_malloc.hpp"  // first: it configures Eigen

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "eomrt/kkt_system.hpp"
#include "eomrt/regularity.hpp"
#include "runtime/scalar_types.hpp"

namespace eomrt {
namespace {

using testing::ScalarName;
using testing::Scalars;

template <class Scalar>
class KktOverScalars : public ::testing::Test {};
TYPED_TEST_SUITE(KktOverScalars, Scalars, ScalarName);

// [[2, 0, -1], [0, 4, -1], [-1, -1, 0]] [x; y] = [2; 4; 1], by hand: 2 x1 - y = 2 and
// 4 x2 - y = 4 give x1 = 1 + y/2, x2 = 1 + y/4; -(x1 + x2) = 1 then gives y = -4, x = (-1, 0)
template <class Kkt, class Scalar>
void expect_hand_solution(Kkt& kkt, const Scalar& scale) {
  Eigen::Matrix<Scalar, 2, 2> M;
  M << 2, 0, 0, 4;
  const Eigen::Matrix<Scalar, 1, 2> Xi(1, 1);
  ASSERT_EQ(kkt.compute(scale * M, Xi), DynamicsStatus::ok);
  Eigen::Matrix<Scalar, Kkt::nk, 1> x(3);  // fixed or dynamic, as the system
  x << 2 * scale, 4 * scale, 1;
  kkt.solve_in_place(x);
  const Scalar tol = 64 * std::numeric_limits<Scalar>::epsilon();
  EXPECT_NEAR(x(0), Scalar(-1), tol);
  EXPECT_NEAR(x(1), Scalar(0), tol);
  // the multiplier scales with M (sigma undoes the scaling of the constraint block)
  EXPECT_NEAR(x(2) / scale, Scalar(-4), tol);
}

TYPED_TEST(KktOverScalars, SolvesTheHandSolvedSystemWithFixedAndDynamicSizes) {
  using Scalar = TypeParam;
  KktSystem<Scalar, 2, 1> fixed;
  KktSystem<Scalar> dynamic;
  for (const Scalar scale : {Scalar(1), Scalar(1e-6), Scalar(1e4)}) {
    SCOPED_TRACE(static_cast<double>(scale));
    expect_hand_solution(fixed, scale);
    expect_hand_solution(dynamic, scale);
  }
}

TYPED_TEST(KktOverScalars, SolvesSeveralRightSidesAtOnce) {
  using Scalar = TypeParam;
  Eigen::Matrix<Scalar, 2, 2> M;
  M << 2, 0, 0, 4;
  const Eigen::Matrix<Scalar, 1, 2> Xi(1, 1);
  KktSystem<Scalar, 2, 1> kkt;
  ASSERT_EQ(kkt.compute(M, Xi), DynamicsStatus::ok);
  Eigen::Matrix<Scalar, 3, 2> rhs;
  rhs << 2, 0, 4, 1, 1, 0;
  const Eigen::Matrix<Scalar, 3, 2> original = rhs;
  kkt.solve_in_place(rhs);
  Eigen::Matrix<Scalar, 3, 3> K;
  K << 2, 0, -1, 0, 4, -1, -1, -1, 0;
  EXPECT_LT((K * rhs - original).cwiseAbs().maxCoeff(), 64 * std::numeric_limits<Scalar>::epsilon());
  EXPECT_NEAR(rhs(2, 0), Scalar(-4), 64 * std::numeric_limits<Scalar>::epsilon());
}

// a redundant row (twice the first): an independent row is kept, the other gets lambda = 0, and
// the accelerations are those of the one constraint: M qdd = F + Xi1^T lambda1, Xi1 qdd = -b1
TEST(KktSystem, ARedundantRowIsLeftOutWithAZeroMultiplier) {
  Eigen::Matrix3d M = Eigen::Matrix3d::Identity();
  Eigen::Matrix<double, 2, 3> Xi;
  Xi << 1, 2, 0, 2, 4, 0;
  KktSystem<double, 3, 2> fixed;
  ASSERT_EQ(fixed.compute(M, Xi), DynamicsStatus::ok);
  EXPECT_TRUE(fixed.left_rows_out());
  Eigen::Matrix<double, 5, 1> rhs;
  rhs << 1, 0, 3, -0.5, -1.0;  // [F; b], b2 = 2 b1 as the rows are
  fixed.solve_in_place(rhs);
  // whichever row is kept, the constraint force Xi^T lambda is unique: M qdd = F + Xi^T lambda
  const Eigen::Vector3d qdd = rhs.head<3>();
  const Eigen::Vector2d lambda = rhs.tail<2>();
  EXPECT_TRUE(lambda(0) == 0 || lambda(1) == 0);
  EXPECT_NEAR((Xi.row(0) * qdd)(0), 0.5, 1e-14);    // -Xi1 qdd = b1
  EXPECT_NEAR((Xi.row(1) * qdd)(0), 1.0, 1e-14);    // the row left out holds too
  const Eigen::Vector3d force = Xi.transpose() * lambda;
  EXPECT_LT((M * qdd - Eigen::Vector3d(1, 0, 3) - force).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_NEAR(force(2), 0.0, 1e-15);                 // along Xi1 only
  KktSystem<double> dynamic;
  EXPECT_EQ(dynamic.compute(Eigen::MatrixXd(M), Eigen::MatrixXd(Xi)), DynamicsStatus::ok);
}

TEST(KktSystem, DependentConstraintsAreSingularOnlyWhereNoRowIsLeft) {
  Eigen::Matrix3d M = Eigen::Matrix3d::Identity();
  Eigen::Matrix<double, 2, 3> Xi;
  KktSystem<double, 3, 2> fixed;
  KktSystem<double> dynamic;
  // nearly dependent: the KKT matrix's smallest singular value goes with the square of Xi's,
  // (sigma 1e-9)^2 far below the threshold, (sigma 1e-3)^2 far above it
  Xi << 1, 2, 0, 1, 2, 1e-9;
  EXPECT_EQ(fixed.compute(M, Xi), DynamicsStatus::singular_kkt_matrix);
  Xi << 1, 2, 0, 1, 2, 1e-3;
  EXPECT_EQ(fixed.compute(M, Xi), DynamicsStatus::ok);
  EXPECT_EQ(dynamic.compute(Eigen::MatrixXd(M), Eigen::MatrixXd(Xi)), DynamicsStatus::ok);
  // no constraint direction at all (a Cartesian pendulum's bob on the pivot: Xi = 0)
  KktSystem<double, 3, 1> one_constraint;
  EXPECT_EQ(one_constraint.compute(M, Eigen::RowVector3d::Zero()), DynamicsStatus::singular_kkt_matrix);
}

// M = 1 - e e^T is singular along the unit quaternion e (a rate along e does not turn the
// body), but positive definite on the null space of Xi = e^T: the KKT matrix is regular
TYPED_TEST(KktOverScalars, SingularMassMatrixWithARegularKktMatrixSolves) {
  using Scalar = TypeParam;
  using Vector4 = Eigen::Matrix<Scalar, 4, 1>;
  const Vector4 e = Vector4(Scalar(0.1), Scalar(-0.3), Scalar(0.5), Scalar(0.8)).normalized();
  const Eigen::Matrix<Scalar, 4, 4> M = Eigen::Matrix<Scalar, 4, 4>::Identity() - e * e.transpose();
  const Eigen::Matrix<Scalar, 1, 4> Xi = e.transpose();
  EXPECT_FALSE(cholesky_is_regular(Eigen::LLT<Eigen::Matrix<Scalar, 4, 4>>(M), default_singular_rcond<Scalar>()));
  KktSystem<Scalar, 4, 1> kkt;
  ASSERT_EQ(kkt.compute(M, Xi), DynamicsStatus::ok);
  Eigen::Matrix<Scalar, 5, 1> x;
  x << Scalar(1), Scalar(-2), Scalar(0.5), Scalar(3), Scalar(0.25);
  const Eigen::Matrix<Scalar, 4, 1> f = x.template head<4>();
  const Scalar g = x(4);
  kkt.solve_in_place(x);
  const Scalar tol = 256 * std::numeric_limits<Scalar>::epsilon();
  // M x - Xi^T y = f and -Xi x = g
  EXPECT_LT((M * x.template head<4>() - Xi.transpose() * x(4) - f).cwiseAbs().maxCoeff(), tol);
  EXPECT_NEAR(-Xi.dot(x.template head<4>()), g, tol);
  // f's part along e can only be held by the multiplier: y = -e . f
  EXPECT_NEAR(x(4), -e.dot(f), tol);
}

TYPED_TEST(KktOverScalars, CholeskyTestSeparatesAtTheThreshold) {
  using Scalar = TypeParam;
  const Scalar threshold = default_singular_rcond<Scalar>();
  EXPECT_EQ(threshold, Scalar(1000) * std::numeric_limits<Scalar>::epsilon());
  using Matrix2 = Eigen::Matrix<Scalar, 2, 2>;
  const auto regular = [&](Scalar smallest) {
    Matrix2 M;
    M << 1, 0, 0, smallest;  // pivots 1 and sqrt(smallest): the ratio squared is smallest
    return cholesky_is_regular(Eigen::LLT<Matrix2>(M), threshold);
  };
  EXPECT_TRUE(regular(Scalar(2) * threshold));
  EXPECT_FALSE(regular(threshold / Scalar(2)));
  EXPECT_FALSE(regular(Scalar(0)));
  EXPECT_FALSE(regular(Scalar(-1)));  // indefinite: the factorization fails
  // the same test on a dynamic matrix, as the generator uses it
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> rank_one(2, 2);
  rank_one.setConstant(3);
  EXPECT_FALSE(cholesky_is_regular(Eigen::LLT<decltype(rank_one)>(rank_one), threshold));
}

TEST(KktSystem, FixedSizesAllocateNothing) {
  Eigen::Matrix2d M;
  M << 2, 0.5, 0.5, 4;
  Eigen::RowVector2d Xi(0.3, -0.7);
  KktSystem<double, 2, 1> kkt;
  Eigen::Matrix<double, 3, 5> rhs;
  rhs.setOnes();
  eigen_assert_failures = 0;
  Eigen::internal::set_is_malloc_allowed(false);
  const DynamicsStatus status = kkt.compute(M, Xi);
  kkt.solve_in_place(rhs);
  Eigen::internal::set_is_malloc_allowed(true);
  EXPECT_EQ(status, DynamicsStatus::ok);
  EXPECT_EQ(eigen_assert_failures, 0);
  EXPECT_TRUE(rhs.allFinite());
}

}  // namespace
}  // namespace eomrt
