#include "linearization_source.hpp"

namespace eomgen {

namespace {

// The derivatives of the KKT accelerations and multipliers of a constrained model, composed of
// the header's own functions: M, F, Xi and b, the KKT system's solution by an LU factorization
// with partial pivoting (written out: Eigen's LU would cost every program that includes the
// header seconds of compilation per size), linearization_terms at it, and the same factors
// applied to the derivatives' right sides (the implicit function theorem on R = 0, S = 0).
constexpr const char* constrained_derivatives = R"cpp(
  // A and B about an operating point: eomrt::linearization<Model> (eomrt/linearization.hpp)
  // solves the KKT system there for qdd0 and lambda0 with the runtime's regularity tests (and
  // its treatment of redundant rows), evaluates linearization_terms at them and solves the KKT
  // system again for the derivatives of qdd.

  /// d[qdd; lambda]/d[q, qd, u] ((nq + nc) x (2 nq + nu), the accelerations' rows first) of the
  /// KKT system [[M, -Xi^T], [-Xi, 0]] [qdd; lambda] = [F; b] at (t, q, qd, u): by the implicit
  /// function theorem, [[M, -Xi^T], [-Xi, 0]] d[qdd; lambda] = [-K dq - D dqd + B_u du;
  /// S_q dq + S_qd dqd] with linearization_terms at the solution. False where the KKT matrix is
  /// singular (a pivot not above its column's size times the round-off) or an entry is not finite.
  template <class DerivedQ, class DerivedQd, class DerivedU, class ParametersOrConstants, class Out0>
  static bool kkt_derivatives(const typename DerivedQ::Scalar& t, const Eigen::MatrixBase<DerivedQ>& q,
                              const Eigen::MatrixBase<DerivedQd>& qd, const Eigen::MatrixBase<DerivedU>& u,
                              const ParametersOrConstants& p, Out0&& kkt_x) noexcept {
    using Scalar = typename DerivedQ::Scalar;
    using std::abs;
    using std::isfinite;
    MassMatrix<Scalar> M;
    Vector<Scalar> F;
    ConstraintJacobian<Scalar> Xi;
    ConstraintVector<Scalar> b;
    mass_matrix_and_forcing(t, q, qd, u, p, M, F);
    constraint_jacobian(t, q, p, Xi);
    constraint_acceleration_term(t, q, qd, p, b);
    Eigen::Matrix<Scalar, nq + nc, nq + nc> kkt;
    kkt << M, -Xi.transpose(), -Xi, Eigen::Matrix<Scalar, nc, nc>::Zero();
    // P kkt = L U in place, the largest entry of each column below the diagonal the pivot
    std::array<int, nq + nc> kkt_pivot{};
    for (int k = 0; k < nq + nc; ++k) {
      int kkt_row = k;
      Scalar kkt_below = Scalar(0), kkt_column = Scalar(0);
      for (int i = 0; i < nq + nc; ++i) {
        kkt_column = abs(kkt(i, k)) > kkt_column ? abs(kkt(i, k)) : kkt_column;
        if (i < k) continue;
        kkt_below = abs(kkt(i, k)) > kkt_below ? abs(kkt(i, k)) : kkt_below;
        if (abs(kkt(i, k)) > abs(kkt(kkt_row, k))) kkt_row = i;
      }
      if (!isfinite(kkt_below) || !(kkt_below > Scalar(nq + nc) * Eigen::NumTraits<Scalar>::epsilon() * kkt_column))
        return false;
      kkt_pivot[k] = kkt_row;
      if (kkt_row != k) kkt.row(k).swap(kkt.row(kkt_row));
      for (int i = k + 1; i < nq + nc; ++i) {
        kkt(i, k) /= kkt(k, k);
        for (int j = k + 1; j < nq + nc; ++j) kkt(i, j) -= kkt(i, k) * kkt(k, j);
      }
    }
    const auto kkt_solve = [&](auto& kkt_rhs) {
      for (int k = 0; k < nq + nc; ++k)
        if (kkt_pivot[k] != k) kkt_rhs.row(k).swap(kkt_rhs.row(kkt_pivot[k]));
      for (int j = 0; j < kkt_rhs.cols(); ++j) {
        for (int i = 1; i < nq + nc; ++i)
          for (int k = 0; k < i; ++k) kkt_rhs(i, j) -= kkt(i, k) * kkt_rhs(k, j);
        for (int i = nq + nc - 1; i >= 0; --i) {
          for (int k = i + 1; k < nq + nc; ++k) kkt_rhs(i, j) -= kkt(i, k) * kkt_rhs(k, j);
          kkt_rhs(i, j) /= kkt(i, i);
        }
      }
    };
    Eigen::Matrix<Scalar, nq + nc, 1> total;
    total << F, b;
    kkt_solve(total);
    const Vector<Scalar> qdd = total.head(nq);
    const ConstraintVector<Scalar> lambda = total.tail(nc);
    MassMatrix<Scalar> K, D;
    InputMatrix<Scalar> B_u;
    ConstraintJacobian<Scalar> S_q, S_qd;
    linearization_terms(t, q, qd, u, p, qdd, lambda, K, D, B_u, S_q, S_qd);
    kkt_x << -K, -D, B_u, S_q, S_qd, Eigen::Matrix<Scalar, nc, nu>::Zero();
    kkt_solve(kkt_x);
    bool regular = true;
    for (int j = 0; j < kkt_x.cols(); ++j)
      for (int i = 0; i < kkt_x.rows(); ++i) regular = regular && isfinite(kkt_x(i, j));
    return regular;
  }

  /// dqdd/dq, dqdd/dqd and dqdd/du of the KKT accelerations (kkt_derivatives' top rows); false
  /// where the KKT matrix is singular or an entry is not finite
  template <class DerivedQ, class DerivedQd, class DerivedU, class ParametersOrConstants, class Out0, class Out1,
            class Out2>
  static bool forward_dynamics_derivatives(const typename DerivedQ::Scalar& t, const Eigen::MatrixBase<DerivedQ>& q,
                                           const Eigen::MatrixBase<DerivedQd>& qd, const Eigen::MatrixBase<DerivedU>& u,
                                           const ParametersOrConstants& p, Out0&& dqdd_dq, Out1&& dqdd_dqd,
                                           Out2&& dqdd_du) noexcept {
    Eigen::Matrix<typename DerivedQ::Scalar, nq + nc, 2 * nq + nu> kkt_x;
    if (!kkt_derivatives(t, q, qd, u, p, kkt_x)) return false;
    dqdd_dq = kkt_x.topLeftCorner(nq, nq);
    dqdd_dqd = kkt_x.block(0, nq, nq, nq);
    dqdd_du = kkt_x.topRightCorner(nq, nu);
    return true;
  }

  /// dlambda/dq, dlambda/dqd and dlambda/du of the KKT multipliers (kkt_derivatives' bottom
  /// rows), the companion of forward_dynamics_derivatives; false as it
  template <class DerivedQ, class DerivedQd, class DerivedU, class ParametersOrConstants, class Out0, class Out1,
            class Out2>
  static bool multiplier_derivatives(const typename DerivedQ::Scalar& t, const Eigen::MatrixBase<DerivedQ>& q,
                                     const Eigen::MatrixBase<DerivedQd>& qd, const Eigen::MatrixBase<DerivedU>& u,
                                     const ParametersOrConstants& p, Out0&& dlambda_dq, Out1&& dlambda_dqd,
                                     Out2&& dlambda_du) noexcept {
    Eigen::Matrix<typename DerivedQ::Scalar, nq + nc, 2 * nq + nu> kkt_x;
    if (!kkt_derivatives(t, q, qd, u, p, kkt_x)) return false;
    dlambda_dq = kkt_x.bottomLeftCorner(nc, nq);
    dlambda_dqd = kkt_x.block(nq, nq, nc, nq);
    dlambda_du = kkt_x.bottomRightCorner(nc, nu);
    return true;
  }
)cpp";

}  // namespace

std::string linearization_source(bool is_constrained) {
  return is_constrained ? constrained_derivatives
                        : R"cpp(
  // A and B about an operating point: eomrt::linearization<Model> (eomrt/linearization.hpp)
  // writes forward_dynamics_derivatives into their bottom rows; the second-order form M, D, K,
  // B_u: eomrt::second_order_linearization<Model>, from linearization_terms at the point's own
  // accelerations qdd0 = M^-1 F.
)cpp";
}

}  // namespace eomgen
