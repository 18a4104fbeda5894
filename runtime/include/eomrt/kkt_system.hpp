#pragma once
/// \file
/// The KKT system of docs/conventions.md,
///   [[M, -Xi^T], [-Xi, 0]] [x; y] = [f; g],
/// assembled, tested for regularity and solved in this one place. The forward dynamics solve it
/// for [qdd; lambda] from [F; b], the linearization for the derivatives of qdd and lambda, and
/// the generator's numeric evaluation (with dynamic sizes) for both. M alone may be singular,
/// e.g. for a quaternion attitude with omega = 2 S(q) qd, where M has rank nq - 1; the KKT
/// matrix is still regular as long as M is positive definite on the null space of Xi.
#include <Eigen/Core>

#include "eomrt/lu_factorization.hpp"
#include "eomrt/pivoted_qr.hpp"
#include "eomrt/regularity.hpp"
#include "eomrt/status.hpp"

namespace eomrt {

namespace detail {

/// a + b for Eigen's compile-time sizes, Dynamic if either is
constexpr int size_sum(int a, int b) { return a == Eigen::Dynamic || b == Eigen::Dynamic ? Eigen::Dynamic : a + b; }

/// k a for Eigen's compile-time sizes, Dynamic if a is
constexpr int size_times(int k, int a) { return a == Eigen::Dynamic ? Eigen::Dynamic : k * a; }

}  // namespace detail

/// The KKT matrix [[M, -Xi^T], [-Xi, 0]] of one state, factorized once and solved for any
/// number of right sides (the Eigen decomposition pattern: compute, then solve). With fixed
/// sizes nq, nc nothing touches the heap; Eigen::Dynamic (the default) serves the generator.
/// The matrix is symmetric but indefinite, so the factorization is LU with partial pivoting.
template <class Scalar, int nq = Eigen::Dynamic, int nc = Eigen::Dynamic>
class KktSystem {
 public:
  static constexpr int nk = detail::size_sum(nq, nc);
  using Matrix = Eigen::Matrix<Scalar, nk, nk>;

  /// Assembles the KKT matrix and factorizes it.
  /// \param[in] M               mass matrix (n x n; nq if fixed), possibly singular
  /// \param[in] Xi              constraint Jacobian (m x n; nc x nq if fixed)
  /// \param[in] singular_rcond  the regularity threshold (see default_singular_rcond)
  /// \return ok, or singular_kkt_matrix where the (scaled) matrix is not regular (LuFactorization::is_regular):
  ///         dependent constraints, or M singular on the directions the constraints allow
  template <class MassMatrix, class Jacobian>
  DynamicsStatus compute(const Eigen::MatrixBase<MassMatrix>& M, const Eigen::MatrixBase<Jacobian>& Xi,
                         const Scalar& singular_rcond = default_singular_rcond<Scalar>()) {
    const Eigen::Index n = M.rows();
    constraints_ = Xi.rows();
    // the constraint block is scaled by sigma to the size of M: in SI units M can be 1e-6 (a
    // coin) while Xi is O(1), and the unscaled matrix would lose digits for no reason. The
    // unknowns become x and y / sigma; solve_in_place undoes the scaling.
    const Scalar xi_size = constraints_ > 0 ? Scalar(Xi.cwiseAbs().maxCoeff()) : Scalar(0);
    const Scalar m_size = n > 0 ? Scalar(M.cwiseAbs().maxCoeff()) : Scalar(0);
    sigma_ = xi_size > 0 && m_size > 0 ? Scalar(m_size / xi_size) : Scalar(1);
    matrix_.resize(n + constraints_, n + constraints_);
    matrix_.topLeftCorner(n, n) = M;
    matrix_.topRightCorner(n, constraints_) = -sigma_ * Xi.transpose();
    matrix_.bottomLeftCorner(constraints_, n) = -sigma_ * Xi;
    matrix_.bottomRightCorner(constraints_, constraints_).setZero();
    left_out_.setConstant(constraints_, false);
    lu_.compute(matrix_);
    if (lu_.is_regular(singular_rcond)) return DynamicsStatus::ok;
    if (constraints_ == 0) return DynamicsStatus::singular_kkt_matrix;
    // Redundant constraints (two wheels on one axle forbid the same sideways slip): rows of Xi
    // dependent at this state. A column-pivoted QR of Xi^T takes an independent set; each row
    // left out gets the equation lambda_k = 0 in place of its own, which the others imply at
    // this state (docs/conventions.md, Redundant constraints). Which rows are dependent may
    // change with the state (with the heading), so the choice is made per state.
    rows_qr_.set_threshold(singular_rcond);
    rows_qr_.compute(Xi.transpose());
    const Eigen::Index rank = rows_qr_.rank();
    // full rank: M is what is singular; rank 0: no constraint has a direction here (a Cartesian
    // pendulum's bob on its pivot), a singular configuration rather than a redundant row
    if (rank == constraints_ || rank == 0) return DynamicsStatus::singular_kkt_matrix;
    for (Eigen::Index k = rank; k < constraints_; ++k) {
      const Eigen::Index row = rows_qr_.column(k);
      left_out_(row) = true;
      matrix_.row(n + row).setZero();
      matrix_.col(n + row).setZero();
      matrix_(n + row, n + row) = m_size > 0 ? m_size : Scalar(1);
    }
    lu_.compute(matrix_);
    return lu_.is_regular(singular_rcond) ? DynamicsStatus::ok : DynamicsStatus::singular_kkt_matrix;
  }

  /// Whether the last compute() left redundant rows out (see compute), and which.
  bool left_rows_out() const { return left_out_.any(); }
  const Eigen::Array<bool, nc, 1>& left_out() const { return left_out_; }

  /// Solves the system compute() factorized, in place.
  /// \param[in,out] rhs  [f; g] on entry, [x; y] on return (n + m rows, any number of columns)
  template <class Rhs>
  void solve_in_place(Eigen::MatrixBase<Rhs>& rhs) const {
    // [[M, -sigma Xi^T], [-sigma Xi, 0]] [x; y / sigma] = [f; sigma g]
    rhs.bottomRows(constraints_) *= sigma_;
    if (left_out_.any())
      for (Eigen::Index k = 0; k < constraints_; ++k)
        if (left_out_(k)) rhs.row(rhs.rows() - constraints_ + k).setZero();
    lu_.solve_in_place(rhs);
    rhs.bottomRows(constraints_) *= sigma_;
  }

  /// The assembled matrix, with its constraint block scaled (for diagnostics: its rank).
  const Matrix& matrix() const { return matrix_; }

 private:
  Matrix matrix_;
  LuFactorization<Scalar, nk> lu_;
  PivotedQr<Scalar, nq, nc> rows_qr_;
  Eigen::Array<bool, nc, 1> left_out_ = Eigen::Array<bool, nc, 1>::Constant(nc == Eigen::Dynamic ? 0 : nc, false);
  Scalar sigma_ = Scalar(1);
  Eigen::Index constraints_ = nc == Eigen::Dynamic ? 0 : nc;
};

}  // namespace eomrt
