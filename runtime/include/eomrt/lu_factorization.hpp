#pragma once
/// \file
/// LuFactorization: P A = L U of a square matrix with partial (row) pivoting, its solves with A
/// and with A^T, and the estimate of its reciprocal condition number that decides whether it
/// counts as regular (regularity.hpp).
///
/// The arithmetic is written here, unblocked, over runtime sizes and compiled once per scalar
/// type. Eigen's PartialPivLU instantiates its blocked algorithm (with a general matrix-matrix
/// product) and its condition estimate once per fixed size it meets: 2 to 3 s of g++ for each
/// size, on every simulation program a constrained model compiles (the KKT matrix, the Gram
/// matrices of projection and assembly). At these sizes, a few tens, Eigen runs the unblocked
/// loop too. With a fixed size the storage is inline and nothing touches the heap.
#include <Eigen/Core>
#include <cmath>
#include <utility>

namespace eomrt {

namespace detail {

// The kernels work on column-major storage of an n x n matrix, a(i, j) = a[i + j n].

/// Factorizes a in place into L (unit lower, below the diagonal) and U; pivots[k] is the row
/// swapped with row k at step k. A zero pivot leaves its column as it is (the matrix is
/// singular; the caller's regularity test says so).
template <class Scalar>
void lu_factorize(Scalar* a, Eigen::Index n, int* pivots) {
  using std::abs;
  for (Eigen::Index k = 0; k < n; ++k) {
    Eigen::Index p = k;
    Scalar largest = abs(a[k + k * n]);
    for (Eigen::Index i = k + 1; i < n; ++i)
      if (abs(a[i + k * n]) > largest) largest = abs(a[i + k * n]), p = i;
    pivots[k] = static_cast<int>(p);
    if (p != k)
      for (Eigen::Index j = 0; j < n; ++j) std::swap(a[k + j * n], a[p + j * n]);
    const Scalar pivot = a[k + k * n];
    if (pivot == Scalar(0)) continue;
    for (Eigen::Index i = k + 1; i < n; ++i) a[i + k * n] /= pivot;
    for (Eigen::Index j = k + 1; j < n; ++j) {
      const Scalar u = a[k + j * n];
      if (u == Scalar(0)) continue;
      for (Eigen::Index i = k + 1; i < n; ++i) a[i + j * n] -= a[i + k * n] * u;
    }
  }
}

/// x <- A^-1 x, from lu_factorize's factors.
template <class Scalar>
void lu_solve(const Scalar* a, Eigen::Index n, const int* pivots, Scalar* x) {
  for (Eigen::Index k = 0; k < n; ++k)
    if (pivots[k] != k) std::swap(x[k], x[pivots[k]]);
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::Index i = j + 1; i < n; ++i) x[i] -= a[i + j * n] * x[j];
  for (Eigen::Index j = n - 1; j >= 0; --j) {
    x[j] /= a[j + j * n];
    for (Eigen::Index i = 0; i < j; ++i) x[i] -= a[i + j * n] * x[j];
  }
}

/// x <- A^-T x: A^T = U^T L^T P, solved in that order.
template <class Scalar>
void lu_solve_transposed(const Scalar* a, Eigen::Index n, const int* pivots, Scalar* x) {
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index k = 0; k < i; ++k) x[i] -= a[k + i * n] * x[k];
    x[i] /= a[i + i * n];
  }
  for (Eigen::Index i = n - 1; i >= 0; --i)
    for (Eigen::Index k = i + 1; k < n; ++k) x[i] -= a[k + i * n] * x[k];
  for (Eigen::Index k = n - 1; k >= 0; --k)
    if (pivots[k] != k) std::swap(x[k], x[pivots[k]]);
}

template <class Scalar>
Scalar norm1(const Scalar* x, Eigen::Index n) {
  using std::abs;
  Scalar s = 0;
  for (Eigen::Index i = 0; i < n; ++i) s += abs(x[i]);
  return s;
}

/// Higham's estimate of |A^-1|_1 (N. J. Higham, "FORTRAN codes for estimating the one-norm of a
/// real or complex matrix", ACM TOMS 14, 1988, Algorithm 4.1, the method of LAPACK's xLACON):
/// a few solves with A and A^T climbing to the column of A^-1 of largest norm, checked against
/// one solve with an alternating vector. v and sign: scratch of n entries. A lower bound,
/// within a factor of 3 of the truth in practice.
template <class Scalar>
Scalar lu_inverse_norm1_estimate(const Scalar* a, Eigen::Index n, const int* pivots, Scalar* v, Scalar* sign) {
  using std::abs;
  const auto signs_of = [&](bool& changed) {
    changed = false;
    for (Eigen::Index i = 0; i < n; ++i) {
      const Scalar s = v[i] < Scalar(0) ? Scalar(-1) : Scalar(1);
      changed = changed || s != sign[i];
      sign[i] = s;
    }
  };
  const auto largest_entry = [&]() {
    Eigen::Index j = 0;
    for (Eigen::Index i = 1; i < n; ++i)
      if (abs(v[i]) > abs(v[j])) j = i;
    return j;
  };
  for (Eigen::Index i = 0; i < n; ++i) v[i] = Scalar(1) / Scalar(n);
  lu_solve(a, n, pivots, v);
  Scalar estimate = norm1(v, n);
  if (n == 1) return estimate;
  bool changed = true;
  for (Eigen::Index i = 0; i < n; ++i) sign[i] = Scalar(0);
  signs_of(changed);
  for (Eigen::Index i = 0; i < n; ++i) v[i] = sign[i];
  lu_solve_transposed(a, n, pivots, v);
  Eigen::Index j = largest_entry(), previous_j = n;
  for (int iteration = 0; iteration < 4; ++iteration) {
    for (Eigen::Index i = 0; i < n; ++i) v[i] = Scalar(i == j ? 1 : 0);
    lu_solve(a, n, pivots, v);
    const Scalar previous = estimate;
    estimate = norm1(v, n);
    if (!(estimate > previous)) {
      estimate = previous;
      break;
    }
    signs_of(changed);
    if (!changed) break;
    for (Eigen::Index i = 0; i < n; ++i) v[i] = sign[i];
    lu_solve_transposed(a, n, pivots, v);
    previous_j = j;
    j = largest_entry();
    if (j == previous_j) break;
  }
  // the alternating vector catches matrices the climb underestimates
  for (Eigen::Index i = 0; i < n; ++i)
    v[i] = (i % 2 == 0 ? Scalar(1) : Scalar(-1)) * (Scalar(1) + Scalar(i) / Scalar(n - 1));
  lu_solve(a, n, pivots, v);
  const Scalar alternating = Scalar(2) * norm1(v, n) / (Scalar(3) * Scalar(n));
  return alternating > estimate ? alternating : estimate;
}

}  // namespace detail

/// P A = L U of an n x n matrix (Eigen::Dynamic: sized by compute), the Eigen decomposition
/// pattern: compute once, then solve any number of right sides.
template <class Scalar, int n = Eigen::Dynamic>
class LuFactorization {
 public:
  using Matrix = Eigen::Matrix<Scalar, n, n>;
  using Vector = Eigen::Matrix<Scalar, n, 1>;

  /// Factorizes A (square).
  template <class Derived>
  void compute(const Eigen::MatrixBase<Derived>& A) {
    lu_ = A;
    pivots_.resize(lu_.rows());
    norm1_ = lu_.size() > 0 ? Scalar(lu_.cwiseAbs().colwise().sum().maxCoeff()) : Scalar(0);
    detail::lu_factorize(lu_.data(), lu_.rows(), pivots_.data());
  }

  Eigen::Index size() const { return lu_.rows(); }

  /// Whether the factorization is numerically regular: every pivot finite and nonzero, and the
  /// estimated reciprocal condition number above threshold (the test of regularity.hpp).
  bool is_regular(const Scalar& threshold) const {
    if (size() == 0) return true;
    for (Eigen::Index k = 0; k < size(); ++k) {
      using std::isfinite;
      const Scalar pivot = lu_(k, k);
      if (!isfinite(pivot) || pivot == Scalar(0)) return false;
    }
    return rcond() > threshold;
  }

  /// 1 / (|A|_1 |A^-1|_1), |A^-1|_1 estimated (detail::lu_inverse_norm1_estimate); 0 for a
  /// zero matrix, 1 for a 1 x 1 one.
  Scalar rcond() const {
    if (norm1_ == Scalar(0)) return Scalar(0);
    if (size() == 1) return Scalar(1);
    Vector v(size()), sign(size());
    const Scalar inverse =
        detail::lu_inverse_norm1_estimate(lu_.data(), size(), pivots_.data(), v.data(), sign.data());
    return inverse == Scalar(0) ? Scalar(0) : (Scalar(1) / inverse) / norm1_;
  }

  /// rhs <- A^-1 rhs, column by column (any number of columns).
  template <class Rhs>
  void solve_in_place(const Eigen::MatrixBase<Rhs>& rhs) const {
    solve_columns(rhs, false);
  }

  /// rhs <- A^-T rhs, column by column.
  template <class Rhs>
  void solve_transposed_in_place(const Eigen::MatrixBase<Rhs>& rhs) const {
    solve_columns(rhs, true);
  }

 private:
  // rhs is const& so that blocks and other expressions bind; they write through, as Eigen's own
  // in-place solves do
  template <class Rhs>
  void solve_columns(const Eigen::MatrixBase<Rhs>& rhs, bool transposed) const {
    auto& out = const_cast<Eigen::MatrixBase<Rhs>&>(rhs);
    Vector column(size());
    for (Eigen::Index j = 0; j < out.cols(); ++j) {
      for (Eigen::Index i = 0; i < size(); ++i) column(i) = out(i, j);
      if (transposed)
        detail::lu_solve_transposed(lu_.data(), size(), pivots_.data(), column.data());
      else
        detail::lu_solve(lu_.data(), size(), pivots_.data(), column.data());
      for (Eigen::Index i = 0; i < size(); ++i) out(i, j) = column(i);
    }
  }

  Matrix lu_;
  Eigen::Matrix<int, n, 1> pivots_;
  Scalar norm1_ = 0;
};

}  // namespace eomrt
