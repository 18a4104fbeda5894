// PivotedQr (pivoted_qr.hpp) and MinimumNormSolver (minimum_norm.hpp) against independent
// references: the product Q R rebuilt and compared with A P, Q's orthogonality, ranks of
// matrices built with a known rank, Eigen's ColPivHouseholderQR for the rank and first pivot,
// Eigen's CompleteOrthogonalDecomposition and the normal equations for minimum-norm solutions.

#include "runtime/no_malloc.hpp"  // first: it configures Eigen

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <Eigen/QR>

#include <cmath>
#include <limits>
#include <random>

#include "eomrt/minimum_norm.hpp"
#include "eomrt/pivoted_qr.hpp"
#include "eomrt/regularity.hpp"

namespace eomrt {
namespace {

using Matrix = Eigen::MatrixXd;

Matrix random_matrix(std::mt19937& rng, Eigen::Index rows, Eigen::Index cols) {
  std::uniform_real_distribution<double> u(-1, 1);
  Matrix A(rows, cols);
  for (Eigen::Index j = 0; j < cols; ++j)
    for (Eigen::Index i = 0; i < rows; ++i) A(i, j) = u(rng);
  return A;
}

/// Q of a factorization, one column per unit vector
Matrix q_of(const PivotedQr<double, Eigen::Dynamic, Eigen::Dynamic>& qr, Eigen::Index rows) {
  Matrix Q = Matrix::Identity(rows, rows);
  for (Eigen::Index j = 0; j < rows; ++j) qr.apply_q(Q.col(j).data());
  return Q;
}

TEST(PivotedQr, RebuildsTheColumnPermutedMatrixWithAnOrthogonalQ) {
  std::mt19937 rng(3);
  for (const auto& [m, n] : {std::pair{5, 3}, {3, 5}, {4, 4}, {8, 1}, {1, 6}, {9, 5}}) {
    const Matrix A = random_matrix(rng, m, n);
    PivotedQr<double, Eigen::Dynamic, Eigen::Dynamic> qr;
    qr.compute(A);
    const Matrix Q = q_of(qr, m);
    EXPECT_LE((Q.transpose() * Q - Matrix::Identity(m, m)).norm(), 1e-14) << m << " x " << n;
    const Matrix R = qr.packed().triangularView<Eigen::Upper>();
    Matrix AP(m, n);
    for (Eigen::Index k = 0; k < n; ++k) AP.col(k) = A.col(qr.column(k));
    EXPECT_LE((Q * R - AP).norm(), 1e-14 * A.norm()) << m << " x " << n;
    // column pivoting: |R_kk| does not grow down the diagonal
    for (Eigen::Index k = 1; k < std::min(m, n); ++k)
      EXPECT_LE(std::abs(R(k, k)), std::abs(R(k - 1, k - 1)) * (1 + 1e-12)) << m << " x " << n;
    EXPECT_EQ(qr.rank(), std::min(m, n));
    const Eigen::ColPivHouseholderQR<Matrix> reference(A);
    EXPECT_EQ(qr.column(0), reference.colsPermutation().indices()(0)) << m << " x " << n;
  }
}

TEST(PivotedQr, RankOfMatricesBuiltWithAKnownRank) {
  std::mt19937 rng(5);
  for (int rank = 0; rank <= 4; ++rank) {
    const Matrix A = random_matrix(rng, 7, rank) * random_matrix(rng, rank, 5);  // 7 x 5 of that rank
    PivotedQr<double, 7, 5> qr;
    qr.set_threshold(default_singular_rcond<double>());
    qr.compute(A);
    EXPECT_EQ(qr.rank(), rank);
    Eigen::ColPivHouseholderQR<Matrix> reference(A);
    reference.setThreshold(default_singular_rcond<double>());
    EXPECT_EQ(qr.rank(), reference.rank());
  }
  // two wheels on one axle: the same sideways-slip row twice
  Eigen::Matrix<double, 3, 4> Xi;
  Xi << 1, 0, 0.5, 0, 0, 1, 0, -2, 1, 0, 0.5, 0;
  PivotedQr<double, 4, 3> rows;
  rows.set_threshold(default_singular_rcond<double>());
  rows.compute(Xi.transpose());
  EXPECT_EQ(rows.rank(), 2);
  // the left-out row is one of the pair, either may go
  EXPECT_NE(rows.column(2), 1);
}

TEST(MinimumNormSolver, FullRankSystemsGetThePseudoInverseSolution) {
  std::mt19937 rng(9);
  for (const auto& [m, n] : {std::pair{1, 4}, {2, 3}, {3, 8}, {5, 8}, {4, 4}}) {
    const Matrix A = random_matrix(rng, m, n);
    const Eigen::VectorXd b = random_matrix(rng, m, 1);
    MinimumNormSolver<Matrix> solver;
    solver.set_threshold(default_singular_rcond<double>());
    solver.compute(A);
    Eigen::VectorXd x;
    solver.solve(b, x);
    // x = A^T (A A^T)^-1 b, the least-norm solution, by the normal equations
    const Eigen::VectorXd expected = A.transpose() * (A * A.transpose()).partialPivLu().solve(b);
    EXPECT_LE((x - expected).norm(), 1e-12 * expected.norm()) << m << " x " << n;
    EXPECT_LE((A * x - b).norm(), 1e-13) << m << " x " << n;
    EXPECT_EQ(solver.rank(), m);
  }
}

TEST(MinimumNormSolver, RedundantRowsAreLeftOutAndTheSolutionIsTheLeastNormOne) {
  std::mt19937 rng(13);
  Matrix A = random_matrix(rng, 4, 7);
  A.row(3) = 2 * A.row(0) - A.row(2);  // a redundant closure
  Eigen::VectorXd b = random_matrix(rng, 4, 1);
  b(3) = 2 * b(0) - b(2);  // consistent with it
  MinimumNormSolver<Eigen::Matrix<double, 4, 7>> solver;
  solver.set_threshold(default_singular_rcond<double>());
  solver.compute(A);
  EXPECT_EQ(solver.rank(), 3);
  Eigen::Matrix<double, 7, 1> x;
  solver.solve(b, x);
  Eigen::CompleteOrthogonalDecomposition<Matrix> reference(A);
  const Eigen::VectorXd expected = reference.solve(b);
  EXPECT_LE((x - expected).norm(), 1e-12 * expected.norm());
  EXPECT_LE((A * x - b).norm(), 1e-13);
}

TEST(MinimumNormSolver, ARankZeroSystemLeavesEverythingAtZero) {
  MinimumNormSolver<Eigen::Matrix<double, 2, 3>> solver;
  solver.compute(Eigen::Matrix<double, 2, 3>::Zero());
  EXPECT_EQ(solver.rank(), 0);
  Eigen::Vector3d x = Eigen::Vector3d::Constant(5);
  solver.solve(Eigen::Vector2d(1, 2), x);
  EXPECT_EQ(x, Eigen::Vector3d::Zero());
}

TEST(MinimumNormSolver, FixedSizesNeverTouchTheHeap) {
  Eigen::Matrix<double, 3, 6> A;
  A << 1, 2, 0, 0, 1, 0, 0, 1, 1, 0, 0, 2, 1, 3, 1, 0, 1, 2;  // row 3 = row 1 + row 2
  const Eigen::Vector3d b(1, 2, 3);
  Eigen::Matrix<double, 6, 1> x;
  MinimumNormSolver<Eigen::Matrix<double, 3, 6>> solver;
  solver.set_threshold(default_singular_rcond<double>());
  eigen_assert_failures = 0;
  Eigen::internal::set_is_malloc_allowed(false);
  solver.compute(A);
  solver.solve(b, x);
  Eigen::internal::set_is_malloc_allowed(true);
  EXPECT_EQ(eigen_assert_failures, 0);
  EXPECT_EQ(solver.rank(), 2);
  EXPECT_LE((A * x - b).norm(), 1e-14);
}

}  // namespace
}  // namespace eomrt
