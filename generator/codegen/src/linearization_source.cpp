#include "linearization_source.hpp"

namespace eomgen {
namespace {

// the same threshold as the runtime's DynamicsWorkspace::singular_rcond
constexpr const char* singular = "Scalar(1000) * Eigen::NumTraits<Scalar>::epsilon()";

std::string unconstrained() {
  return std::string(R"cpp(
  /// M at (t, q, qd, u), its Cholesky factor and the point's own accelerations qdd0 = M^-1 F.
  /// Returns false where M is not (numerically) positive definite: the runtime's test, the
  /// pivot ratio (min L_ii / max L_ii)^2, cheap and zero where M is singular.
  template <class Scalar>
  static bool operating_point_accelerations(const Scalar& t, const Vector<Scalar>& q, const Vector<Scalar>& qd, const Inputs<Scalar>& u, const Parameters<Scalar>& p, MassMatrix<Scalar>& M, Eigen::LLT<MassMatrix<Scalar>>& llt, Vector<Scalar>& qdd) noexcept {
    Vector<Scalar> F;
    mass_matrix_and_forcing(t, q, qd, u, p, M, F);
    llt.compute(M);
    if (llt.info() != Eigen::Success) return false;
    const Scalar smallest = llt.matrixLLT().diagonal().minCoeff(), largest = llt.matrixLLT().diagonal().maxCoeff();
    if (!(smallest * smallest > )cpp") + singular + R"cpp( * largest * largest)) return false;
    qdd = llt.solve(F);
    return true;
  }

  /// The second-order form M dqdd + D dqd + K dq = B_u du about (t, q, qd, u), with K taken at
  /// the point's own accelerations qdd0 = M^-1 F (zero at an equilibrium; not at a steady
  /// motion, where dM/dq qdd0 belongs to K). Returns false, the outputs unspecified, where M is
  /// not (numerically) positive definite.
  template <class Scalar>
  static bool second_order_linearization(const Scalar& t, const Vector<Scalar>& q, const Vector<Scalar>& qd, const Inputs<Scalar>& u, const Parameters<Scalar>& p, MassMatrix<Scalar>& M, MassMatrix<Scalar>& D, MassMatrix<Scalar>& K, InputMatrix<Scalar>& B_u) noexcept {
    Eigen::LLT<MassMatrix<Scalar>> llt;
    Vector<Scalar> qdd;
    if (!operating_point_accelerations(t, q, qd, u, p, M, llt, qdd)) return false;
    linearization_terms(t, q, qd, u, p, qdd, K, D, B_u);
    return true;
  }

  /// A and B of the first-order form dx' = A dx + B du, x = [q; qd], about (t, q, qd, u):
  /// A = [[0, 1], [-M^-1 K, -M^-1 D]], B = [[0], [M^-1 B_u]], from exact derivatives. Returns
  /// false, A and B unspecified, where M is not (numerically) positive definite.
  template <class Scalar>
  static bool linearization(const Scalar& t, const Vector<Scalar>& q, const Vector<Scalar>& qd, const Inputs<Scalar>& u, const Parameters<Scalar>& p, StateMatrix<Scalar>& A, StateInputMatrix<Scalar>& B) noexcept {
    MassMatrix<Scalar> M, D, K;
    InputMatrix<Scalar> B_u;
    Eigen::LLT<MassMatrix<Scalar>> llt;
    Vector<Scalar> qdd;
    if (!operating_point_accelerations(t, q, qd, u, p, M, llt, qdd)) return false;
    linearization_terms(t, q, qd, u, p, qdd, K, D, B_u);
    A.setZero();
    A.template topRightCorner<nq, nq>().setIdentity();
    A.template bottomLeftCorner<nq, nq>() = -llt.solve(K);
    A.template bottomRightCorner<nq, nq>() = -llt.solve(D);
    B.setZero();
    if constexpr (nu > 0) B.template bottomRows<nq>() = llt.solve(B_u);
    return A.allFinite() && B.allFinite();
  }
)cpp";
}

std::string constrained() {
  return std::string(R"cpp(
  /// A and B of dx' = A dx + B du, x = [q; qd], about (t, q, qd, u), for the accelerations the
  /// KKT system M qdd - Xi^T lambda = F, Xi qdd + b = 0 gives: exact derivatives by the implicit
  /// function theorem, d[qdd; lambda] = -[[M, -Xi^T], [Xi, 0]]^-1 d[R; S]. At a point on the
  /// constraints the tangent space of the constraint manifold is invariant under A; restrict A
  /// to it (independent coordinates and speeds) for a minimal model, as `eomgen linearize`
  /// does. Returns false, A and B unspecified, where the KKT matrix is singular.
  template <class Scalar>
  static bool linearization(const Scalar& t, const Vector<Scalar>& q, const Vector<Scalar>& qd, const Inputs<Scalar>& u, const Parameters<Scalar>& p, StateMatrix<Scalar>& A, StateInputMatrix<Scalar>& B) noexcept {
    using Square = Eigen::Matrix<Scalar, nq + nc, nq + nc>;
    MassMatrix<Scalar> M;
    Vector<Scalar> F;
    ConstraintJacobian<Scalar> Xi;
    ConstraintVector<Scalar> b;
    mass_matrix_and_forcing(t, q, qd, u, p, M, F);
    constraint_jacobian(t, q, p, Xi);
    constraint_acceleration_term(t, q, qd, p, b);
    // the constraint block scaled to the size of M, as in the runtime's KKT solve (a coin's M
    // is 1e-6 in SI units while Xi is 1); the unknowns are qdd and lambda / sigma
    const Scalar xi_size = Xi.cwiseAbs().maxCoeff(), m_size = M.cwiseAbs().maxCoeff();
    const Scalar sigma = xi_size > Scalar(0) && m_size > Scalar(0) ? Scalar(m_size / xi_size) : Scalar(1);
    Square J;
    J.template topLeftCorner<nq, nq>() = M;
    J.template topRightCorner<nq, nc>() = -sigma * Xi.transpose();
    J.template bottomLeftCorner<nc, nq>() = -sigma * Xi;
    J.template bottomRightCorner<nc, nc>().setZero();
    const Eigen::PartialPivLU<Square> lu(J);
    if (!(lu.rcond() > )cpp") + singular + R"cpp()) return false;
    Eigen::Matrix<Scalar, nq + nc, 1> rhs;
    rhs << F, sigma * b;
    const Eigen::Matrix<Scalar, nq + nc, 1> solution = lu.solve(rhs);
    const Vector<Scalar> qdd = solution.template head<nq>();
    const ConstraintVector<Scalar> lambda = sigma * solution.template tail<nc>();
    MassMatrix<Scalar> K, D;
    InputMatrix<Scalar> B_u;
    ConstraintJacobian<Scalar> S_q, S_qd;
    linearization_terms(t, q, qd, u, p, qdd, lambda, K, D, B_u, S_q, S_qd);
    // J d[qdd; lambda / sigma] = [-dR; sigma dS] with dR = K dq + D dqd - B_u du
    Eigen::Matrix<Scalar, nq + nc, 2 * nq + nu> derivative_rhs;
    derivative_rhs.template topLeftCorner<nq, nq>() = -K;
    derivative_rhs.template block<nq, nq>(0, nq) = -D;
    derivative_rhs.template topRightCorner<nq, nu>() = B_u;
    derivative_rhs.template bottomLeftCorner<nc, nq>() = sigma * S_q;
    derivative_rhs.template block<nc, nq>(nq, nq) = sigma * S_qd;
    derivative_rhs.template bottomRightCorner<nc, nu>().setZero();
    const Eigen::Matrix<Scalar, nq + nc, 2 * nq + nu> derivatives = lu.solve(derivative_rhs);
    A.setZero();
    A.template topRightCorner<nq, nq>().setIdentity();
    A.template bottomRows<nq>() = derivatives.template topLeftCorner<nq, 2 * nq>();
    B.setZero();
    if constexpr (nu > 0) B.template bottomRows<nq>() = derivatives.template topRightCorner<nq, nu>();
    return A.allFinite() && B.allFinite();
  }
)cpp";
}

}  // namespace

std::string linearization_source(bool is_constrained) { return is_constrained ? constrained() : unconstrained(); }

}  // namespace eomgen
