#pragma once
/// \file
/// The minimum-norm solution of an underdetermined linear system A x = b (m x n, m <= n in use),
/// rank-revealing: rows of A that depend on the others at this state are left out, and the
/// solution satisfies the independent rows with the least |x|.
///
/// From a column-pivoted QR of A^T (pivoted_qr.hpp): A^T P = Q R, R11 the leading r x r block of
/// rank r. Then A = P R^T Q^T, and with z = Q^T x the independent rows read
/// R11^T z1 = (P^T b)_1; |x| = |z| is least at z2 = 0. The same answer as a complete orthogonal
/// decomposition's wherever the system is consistent (the only case assembly keeps: its
/// results are checked against the constraints), and a different one only where dependent rows
/// contradict the others. Eigen's CompleteOrthogonalDecomposition took 7 to 10 s of g++'s time
/// on each simulation program of a constrained model; this compiles in a fraction of a second.
/// With fixed sizes nothing touches the heap.
#include <Eigen/Core>

#include "eomrt/pivoted_qr.hpp"

namespace eomrt {

template <class Matrix>
class MinimumNormSolver {
 public:
  using Scalar = typename Matrix::Scalar;
  using Solution = Eigen::Matrix<Scalar, Matrix::ColsAtCompileTime, 1>;

  /// The relative size below which a pivot counts as zero (PivotedQr::set_threshold).
  void set_threshold(const Scalar& threshold) { qr_.set_threshold(threshold); }

  /// Factorizes A (QR of A^T with column pivoting).
  void compute(const Matrix& A) { qr_.compute(A.transpose()); }

  /// The rank compute() found.
  Eigen::Index rank() const { return qr_.rank(); }

  /// x of least norm satisfying A's independent rows: x = Q [R11^-T (P^T b)_1; 0].
  /// \param[in]  b  right side (m rows)
  /// \param[out] x  solution (n rows)
  template <class Rhs, class Out>
  void solve(const Eigen::MatrixBase<Rhs>& b, Eigen::MatrixBase<Out>& x) {
    const auto& R = qr_.packed();
    const Eigen::Index r = qr_.rank();
    z_.setZero(R.rows());
    // forward substitution with R11^T (lower triangular), on the rows in pivot order
    for (Eigen::Index i = 0; i < r; ++i) {
      Scalar s = b(qr_.column(i));
      for (Eigen::Index j = 0; j < i; ++j) s -= R(j, i) * z_(j);
      z_(i) = s / R(i, i);
    }
    qr_.apply_q(z_.data());
    x = z_;
  }

 private:
  PivotedQr<Scalar, Matrix::ColsAtCompileTime, Matrix::RowsAtCompileTime> qr_;
  Solution z_;
};

}  // namespace eomrt
