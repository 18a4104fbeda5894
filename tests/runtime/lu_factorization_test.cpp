// LuFactorization (lu_factorization.hpp) against independent references: Eigen's PartialPivLU
// and FullPivLU for solves, the exact one-norm of the inverse for the condition estimate, the
// Hilbert matrices (known condition numbers) on either side of the regularity threshold, and
// the heap left alone with fixed sizes.

#include "runtime/no_malloc.hpp"  // first: it configures Eigen

#include <gtest/gtest.h>

#include <Eigen/LU>

#include <cmath>
#include <limits>
#include <random>

#include "eomrt/lu_factorization.hpp"
#include "eomrt/regularity.hpp"
#include "runtime/scalar_types.hpp"

namespace eomrt {
namespace {

using testing::ScalarName;
using testing::Scalars;

template <class Scalar>
class LuOverScalars : public ::testing::Test {};
TYPED_TEST_SUITE(LuOverScalars, Scalars, ScalarName);

template <class Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> random_matrix(std::mt19937& rng, Eigen::Index rows,
                                                                    Eigen::Index cols) {
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> A(rows, cols);
  for (Eigen::Index j = 0; j < cols; ++j)
    for (Eigen::Index i = 0; i < rows; ++i) A(i, j) = Scalar(u(rng));
  return A;
}

template <class Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> hilbert(Eigen::Index n) {
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> H(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) H(i, j) = Scalar(1) / Scalar(i + j + 1);
  return H;
}

TYPED_TEST(LuOverScalars, SolvesWithTheMatrixAndItsTransposeAgreeWithEigen) {
  using Scalar = TypeParam;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  std::mt19937 rng(7);
  const Scalar eps = std::numeric_limits<Scalar>::epsilon();
  for (Eigen::Index n = 1; n <= 14; ++n) {
    const Matrix A = random_matrix<Scalar>(rng, n, n), B = random_matrix<Scalar>(rng, n, 3);
    LuFactorization<Scalar> lu;
    lu.compute(A);
    Matrix X = B, Y = B;
    lu.solve_in_place(X);
    lu.solve_transposed_in_place(Y);
    const Eigen::PartialPivLU<Matrix> reference(A);
    const Matrix X_ref = reference.solve(B), Y_ref = reference.transpose().solve(B);
    const Scalar scale = Scalar(1) / reference.rcond();  // condition number, as the errors grow with it
    EXPECT_LE((X - X_ref).norm(), 100 * n * eps * scale * X_ref.norm()) << "n = " << n;
    EXPECT_LE((Y - Y_ref).norm(), 100 * n * eps * scale * Y_ref.norm()) << "n = " << n;
    EXPECT_LE((A * X - B).norm(), 100 * n * eps * (A.norm() * X.norm())) << "n = " << n;
    EXPECT_LE((A.transpose() * Y - B).norm(), 100 * n * eps * (A.norm() * Y.norm())) << "n = " << n;
  }
}

TYPED_TEST(LuOverScalars, ConditionEstimateIsBetweenTheExactValueAndThreeTimesIt) {
  using Scalar = TypeParam;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  std::mt19937 rng(11);
  for (Eigen::Index n = 2; n <= 12; ++n) {
    for (const Matrix& A : {random_matrix<Scalar>(rng, n, n), hilbert<Scalar>(std::min<Eigen::Index>(n, 8))}) {
      LuFactorization<Scalar> lu;
      lu.compute(A);
      const Matrix inverse = Eigen::FullPivLU<Matrix>(A).inverse();
      const Scalar exact = Scalar(1) / (A.cwiseAbs().colwise().sum().maxCoeff() *
                                         inverse.cwiseAbs().colwise().sum().maxCoeff());
      // |A^-1|_1 estimated from below: the reciprocal condition from above, and close
      EXPECT_GE(lu.rcond(), exact * (1 - Scalar(1e-9))) << "n = " << A.rows();
      EXPECT_LE(lu.rcond(), 3 * exact) << "n = " << A.rows();
      // never above Eigen's own estimate, which keeps the last (not the largest) of its climb
      EXPECT_LE(lu.rcond(), Eigen::PartialPivLU<Matrix>(A).rcond() * (1 + Scalar(1e-9))) << "n = " << A.rows();
    }
  }
}

TYPED_TEST(LuOverScalars, HilbertMatricesAreRegularUntilTheirConditionPassesTheThreshold) {
  using Scalar = TypeParam;
  const Scalar threshold = default_singular_rcond<Scalar>();  // 1000 eps
  // cond_1 of the Hilbert matrix: 5 -> 9.4e5, 13 -> above 1e18 (beyond double's precision)
  LuFactorization<Scalar> lu;
  lu.compute(hilbert<Scalar>(5));
  EXPECT_TRUE(lu.is_regular(threshold));
  EXPECT_NEAR(std::log10(double(lu.rcond())), -std::log10(9.4366e5), 0.5);
  lu.compute(hilbert<Scalar>(13));
  EXPECT_FALSE(lu.is_regular(Scalar(1000) * Scalar(std::numeric_limits<double>::epsilon())));
}

TEST(LuFactorization, SingularZeroAndNonFiniteMatricesAreNotRegular) {
  using Matrix = Eigen::Matrix3d;
  LuFactorization<double, 3> lu;
  Matrix A;
  A << 1, 2, 3, 4, 5, 6, 7, 8, 9;  // rank 2: the rows are in arithmetic progression
  lu.compute(A);
  EXPECT_FALSE(lu.is_regular(default_singular_rcond<double>()));
  lu.compute(Matrix::Zero());
  EXPECT_FALSE(lu.is_regular(default_singular_rcond<double>()));
  EXPECT_EQ(lu.rcond(), 0.0);
  A(1, 1) = std::numeric_limits<double>::quiet_NaN();
  lu.compute(A);
  EXPECT_FALSE(lu.is_regular(default_singular_rcond<double>()));
  // regular once a row leaves the progression
  A << 1, 2, 3, 4, 5, 6, 7, 8, 10;
  lu.compute(A);
  EXPECT_TRUE(lu.is_regular(default_singular_rcond<double>()));
  LuFactorization<double> empty;
  empty.compute(Eigen::MatrixXd(0, 0));
  EXPECT_TRUE(empty.is_regular(default_singular_rcond<double>()));
}

TEST(LuFactorization, PivotsOnTheLargestEntryOfEachColumn) {
  // without pivoting the first step would divide by 1e-20 and lose every digit of the answer
  Eigen::Matrix2d A;
  A << 1e-20, 1, 1, 1;
  LuFactorization<double, 2> lu;
  lu.compute(A);
  Eigen::Vector2d x(1, 2);  // x2 = 1 - 1e-20 x1, x1 + x2 = 2: x1 = 1 / (1 - 1e-20), x2 = 1
  lu.solve_in_place(x);
  EXPECT_NEAR(x(0), 1.0, 1e-15);
  EXPECT_NEAR(x(1), 1.0, 1e-15);
}

TEST(LuFactorization, FixedSizesNeverTouchTheHeap) {
  Eigen::Matrix<double, 6, 6> A = Eigen::Matrix<double, 6, 6>::Identity();
  A(0, 5) = 2;
  A(4, 1) = -3;
  Eigen::Matrix<double, 6, 2> B = Eigen::Matrix<double, 6, 2>::Ones();
  LuFactorization<double, 6> lu;
  eigen_assert_failures = 0;
  Eigen::internal::set_is_malloc_allowed(false);
  lu.compute(A);
  const bool regular = lu.is_regular(default_singular_rcond<double>());
  lu.solve_in_place(B);
  lu.solve_transposed_in_place(B.col(0));
  Eigen::internal::set_is_malloc_allowed(true);
  EXPECT_EQ(eigen_assert_failures, 0);
  EXPECT_TRUE(regular);
}

}  // namespace
}  // namespace eomrt
