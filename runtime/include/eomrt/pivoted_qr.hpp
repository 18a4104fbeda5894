#pragma once
/// \file
/// PivotedQr: A P = Q R of an m x n matrix by Householder reflections with column pivoting,
/// rank-revealing. The runtime asks it which rows of a constraint Jacobian are independent at a
/// state (a QR of Xi^T: the leading columns of P), and for minimum-norm solutions
/// (minimum_norm.hpp).
///
/// Written here, unblocked, over runtime sizes and compiled once per scalar type, for the reason
/// lu_factorization.hpp gives: Eigen's ColPivHouseholderQR costs g++ 2 to 5 s for each fixed
/// size a simulation program meets. At a constraint Jacobian's sizes the column norms are
/// recomputed at every step instead of downdated, which is exact and costs O(m n) per step.
/// With fixed sizes nothing touches the heap.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <utility>

namespace eomrt {

namespace detail {

/// Factorizes the column-major m x n matrix a (a(i, j) = a[i + j m]) in place: R on and above
/// the diagonal, each reflector's essential part below it, its coefficient in tau[k]
/// (H_k = I - tau_k v v^T, v = [1; essential]); permutation[k] is the column of A that is column
/// k of R.
template <class Scalar>
void pivoted_qr_factorize(Scalar* a, Eigen::Index m, Eigen::Index n, Scalar* tau, int* permutation) {
  using std::sqrt;
  for (Eigen::Index j = 0; j < n; ++j) permutation[j] = static_cast<int>(j);
  const Eigen::Index steps = m < n ? m : n;
  for (Eigen::Index k = 0; k < steps; ++k) {
    // the remaining column of largest norm below row k
    Eigen::Index p = k;
    Scalar largest = -1;
    for (Eigen::Index j = k; j < n; ++j) {
      Scalar s = 0;
      for (Eigen::Index i = k; i < m; ++i) s += a[i + j * m] * a[i + j * m];
      if (s > largest) largest = s, p = j;
    }
    if (p != k) {
      for (Eigen::Index i = 0; i < m; ++i) std::swap(a[i + k * m], a[i + p * m]);
      std::swap(permutation[k], permutation[p]);
    }
    // the reflection taking a(k:m, k) to beta e_1
    Scalar* x = a + k + k * m;
    Scalar tail = 0;
    for (Eigen::Index i = 1; i < m - k; ++i) tail += x[i] * x[i];
    if (tail == Scalar(0)) {
      tau[k] = 0;
      continue;
    }
    Scalar beta = sqrt(x[0] * x[0] + tail);
    if (x[0] >= Scalar(0)) beta = -beta;
    const Scalar scale = Scalar(1) / (x[0] - beta);
    for (Eigen::Index i = 1; i < m - k; ++i) x[i] *= scale;
    tau[k] = (beta - x[0]) / beta;
    x[0] = beta;
    // applied to the columns to the right: y <- y - tau v (v^T y)
    for (Eigen::Index j = k + 1; j < n; ++j) {
      Scalar* y = a + k + j * m;
      Scalar w = y[0];
      for (Eigen::Index i = 1; i < m - k; ++i) w += x[i] * y[i];
      w *= tau[k];
      y[0] -= w;
      for (Eigen::Index i = 1; i < m - k; ++i) y[i] -= w * x[i];
    }
  }
}

/// y <- Q y = H_0 H_1 ... H_{s-1} y, from pivoted_qr_factorize's reflectors.
template <class Scalar>
void pivoted_qr_apply_q(const Scalar* a, Eigen::Index m, Eigen::Index n, const Scalar* tau, Scalar* y) {
  const Eigen::Index steps = m < n ? m : n;
  for (Eigen::Index k = steps - 1; k >= 0; --k) {
    if (tau[k] == Scalar(0)) continue;
    const Scalar* v = a + k + k * m;
    Scalar w = y[k];
    for (Eigen::Index i = 1; i < m - k; ++i) w += v[i] * y[k + i];
    w *= tau[k];
    y[k] -= w;
    for (Eigen::Index i = 1; i < m - k; ++i) y[k + i] -= w * v[i];
  }
}

}  // namespace detail

/// A P = Q R of a rows x cols matrix (Eigen::Dynamic sizes: set by compute).
template <class Scalar, int rows, int cols>
class PivotedQr {
 public:
  using Matrix = Eigen::Matrix<Scalar, rows, cols>;
  static constexpr int steps = rows == Eigen::Dynamic || cols == Eigen::Dynamic ? Eigen::Dynamic
                               : rows < cols                                     ? rows
                                                                                 : cols;

  /// The size relative to the largest |R_kk| below which a diagonal entry of R counts as zero
  /// (by default epsilon times the number of diagonal entries, Eigen's default).
  void set_threshold(const Scalar& threshold) { threshold_ = threshold; }

  template <class Derived>
  void compute(const Eigen::MatrixBase<Derived>& A) {
    qr_ = A;
    tau_.resize(std::min(qr_.rows(), qr_.cols()));
    permutation_.resize(qr_.cols());
    detail::pivoted_qr_factorize(qr_.data(), qr_.rows(), qr_.cols(), tau_.data(), permutation_.data());
  }

  /// The number of diagonal entries of R above threshold times the largest.
  Eigen::Index rank() const {
    using std::abs;
    Scalar largest = 0;
    for (Eigen::Index k = 0; k < tau_.size(); ++k) largest = std::max(largest, Scalar(abs(qr_(k, k))));
    const Scalar threshold =
        threshold_ >= Scalar(0) ? threshold_ : Eigen::NumTraits<Scalar>::epsilon() * Scalar(tau_.size());
    Eigen::Index r = 0;
    for (Eigen::Index k = 0; k < tau_.size(); ++k) r += abs(qr_(k, k)) > threshold * largest ? 1 : 0;
    return r;
  }

  /// The column of A that is column k of R.
  int column(Eigen::Index k) const { return permutation_(k); }

  /// R on and above the diagonal (the reflectors' parts below it).
  const Matrix& packed() const { return qr_; }

  /// y <- Q y (y of rows entries, contiguous).
  void apply_q(Scalar* y) const { detail::pivoted_qr_apply_q(qr_.data(), qr_.rows(), qr_.cols(), tau_.data(), y); }

 private:
  Matrix qr_;
  Eigen::Matrix<Scalar, steps, 1> tau_;
  Eigen::Matrix<int, cols, 1> permutation_;
  Scalar threshold_ = -1;  // the default
};

}  // namespace eomrt
