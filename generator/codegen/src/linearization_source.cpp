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

  /// d[qdd; lambda]/d[q, qd, u] ((nq + nc) x (2 nq + nu)) of the KKT system
  /// [[M, -Xi^T], [-Xi, 0]] [qdd; lambda] = [F; b] at (t, q, qd, u): by the implicit function
  /// theorem, [[M, -Xi^T], [-Xi, 0]] d[qdd; lambda] = [-K dq - D dqd + B_u du; S_q dq + S_qd dqd]
  /// with linearization_terms at the solution. False where the KKT matrix is singular (a pivot
  /// not above its column's size times the round-off) or an entry is not finite.
  template <class DerivedQ, class DerivedQd, class DerivedU, class P, class Out>
  static bool kkt_derivatives(const typename DerivedQ::Scalar& t, const Eigen::MatrixBase<DerivedQ>& q,
                              const Eigen::MatrixBase<DerivedQd>& qd, const Eigen::MatrixBase<DerivedU>& u,
                              const P& p, Out&& X) noexcept {
    using Scalar = typename DerivedQ::Scalar;
    using std::abs;
    using std::isfinite;
    constexpr int n = nq + nc;
    MassMatrix<Scalar> M;
    Vector<Scalar> F;
    ConstraintJacobian<Scalar> Xi;
    ConstraintVector<Scalar> b;
    mass_matrix_and_forcing(t, q, qd, u, p, M, F);
    constraint_jacobian(t, q, p, Xi);
    constraint_acceleration_term(t, q, qd, p, b);
    Eigen::Matrix<Scalar, n, n> lu;
    lu << M, -Xi.transpose(), -Xi, Eigen::Matrix<Scalar, nc, nc>::Zero();
    // P lu = L U in place, the largest entry of each column below the diagonal the pivot
    std::array<int, n> pivot{};
    for (int k = 0; k < n; ++k) {
      int largest = k;
      Scalar size = Scalar(0);
      for (int i = k; i < n; ++i) {
        size = abs(lu(i, k)) > size ? abs(lu(i, k)) : size;
        if (abs(lu(i, k)) > abs(lu(largest, k))) largest = i;
      }
      Scalar column = Scalar(0);
      for (int i = 0; i < n; ++i) column = abs(lu(i, k)) > column ? abs(lu(i, k)) : column;
      if (!isfinite(size) || !(size > Scalar(n) * Eigen::NumTraits<Scalar>::epsilon() * column)) return false;
      pivot[k] = largest;
      if (largest != k) lu.row(k).swap(lu.row(largest));
      for (int i = k + 1; i < n; ++i) {
        lu(i, k) /= lu(k, k);
        for (int j = k + 1; j < n; ++j) lu(i, j) -= lu(i, k) * lu(k, j);
      }
    }
    const auto solve = [&](auto& rhs) {
      for (int k = 0; k < n; ++k)
        if (pivot[k] != k) rhs.row(k).swap(rhs.row(pivot[k]));
      for (int c = 0; c < rhs.cols(); ++c) {
        for (int i = 1; i < n; ++i)
          for (int j = 0; j < i; ++j) rhs(i, c) -= lu(i, j) * rhs(j, c);
        for (int i = n - 1; i >= 0; --i) {
          for (int j = i + 1; j < n; ++j) rhs(i, c) -= lu(i, j) * rhs(j, c);
          rhs(i, c) /= lu(i, i);
        }
      }
    };
    Eigen::Matrix<Scalar, n, 1> solution;
    solution << F, b;
    solve(solution);
    const Vector<Scalar> qdd = solution.template head<nq>();
    const ConstraintVector<Scalar> lambda = solution.template tail<nc>();
    MassMatrix<Scalar> K, D;
    InputMatrix<Scalar> B_u;
    ConstraintJacobian<Scalar> S_q, S_qd;
    linearization_terms(t, q, qd, u, p, qdd, lambda, K, D, B_u, S_q, S_qd);
    X.template topLeftCorner<nq, nq>() = -K;
    X.template block<nq, nq>(0, nq) = -D;
    X.template topRightCorner<nq, nu>() = B_u;
    X.template bottomLeftCorner<nc, nq>() = S_q;
    X.template block<nc, nq>(nq, nq) = S_qd;
    X.template bottomRightCorner<nc, nu>().setZero();
    solve(X);
    bool regular = true;
    for (int j = 0; j < X.cols(); ++j)
      for (int i = 0; i < X.rows(); ++i) regular = regular && isfinite(X(i, j));
    return regular;
  }

  /// dqdd/dq, dqdd/dqd and dqdd/du of the KKT accelerations (kkt_derivatives' top rows); false
  /// where the KKT matrix is singular or an entry is not finite
  template <class DerivedQ, class DerivedQd, class DerivedU, class P, class Out0, class Out1, class Out2>
  static bool forward_dynamics_derivatives(const typename DerivedQ::Scalar& t, const Eigen::MatrixBase<DerivedQ>& q,
                                           const Eigen::MatrixBase<DerivedQd>& qd, const Eigen::MatrixBase<DerivedU>& u,
                                           const P& p, Out0&& dqdd_dq, Out1&& dqdd_dqd, Out2&& dqdd_du) noexcept {
    Eigen::Matrix<typename DerivedQ::Scalar, nq + nc, 2 * nq + nu> X;
    if (!kkt_derivatives(t, q, qd, u, p, X)) return false;
    dqdd_dq = X.template topLeftCorner<nq, nq>();
    dqdd_dqd = X.template block<nq, nq>(0, nq);
    dqdd_du = X.template topRightCorner<nq, nu>();
    return true;
  }

  /// dlambda/dq, dlambda/dqd and dlambda/du of the KKT multipliers (kkt_derivatives' bottom
  /// rows), the companion of forward_dynamics_derivatives; false as it
  template <class DerivedQ, class DerivedQd, class DerivedU, class P, class Out0, class Out1, class Out2>
  static bool multiplier_derivatives(const typename DerivedQ::Scalar& t, const Eigen::MatrixBase<DerivedQ>& q,
                                     const Eigen::MatrixBase<DerivedQd>& qd, const Eigen::MatrixBase<DerivedU>& u,
                                     const P& p, Out0&& dlambda_dq, Out1&& dlambda_dqd, Out2&& dlambda_du) noexcept {
    Eigen::Matrix<typename DerivedQ::Scalar, nq + nc, 2 * nq + nu> X;
    if (!kkt_derivatives(t, q, qd, u, p, X)) return false;
    dlambda_dq = X.template bottomLeftCorner<nc, nq>();
    dlambda_dqd = X.template block<nc, nq>(nq, nq);
    dlambda_du = X.template bottomRightCorner<nc, nu>();
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
