#pragma once
/// \file
/// Linear models about an operating point (t, q, qd, u), x = [q; qd]. The model-specific part
/// is the generated linearization_terms (eomgen generate --linearization): the exact
/// derivatives of the residuals
///   R = M qdd - F - Xi^T lambda,   S = Xi qdd + b,
/// K = dR/dq, D = dR/dqd, B_u = -dR/du (= dF/du), S_q = dS/dq, S_qd = dS/dqd, at given qdd and
/// lambda. They are taken here at the point's own accelerations qdd0 and multipliers lambda0,
/// from the forward dynamics, so a steady motion (a spinning top, a rolling coin), where qdd0
/// is not zero and dM/dq qdd0 belongs to K, linearizes correctly.
///
/// Unconstrained: M dqdd + D dqd + K dq = B_u du, the second-order form, gives
///   A = [[0, 1], [-M^-1 K, -M^-1 D]],   B = [[0], [M^-1 B_u]].
/// Those bottom rows are dqdd/dq, dqdd/dqd and dqdd/du, which a header generated with
/// --linearization for a model without constraints computes in one function,
/// forward_dynamics_derivatives (in the form of fewer operations: the chain rule through the
/// recursive forward dynamics, or M's LDL^T factors applied to K, D, B_u); linearization uses
/// it where the model has it.
/// Constrained: dR = 0 and dS = 0 are the KKT system of docs/conventions.md for the derivatives,
///   [[M, -Xi^T], [-Xi, 0]] d[qdd; lambda] = [-K dq - D dqd + B_u du; S_q dq + S_qd dqd],
/// (the implicit function theorem), and A, B are those of the KKT accelerations on the full
/// state. At a point on the constraints the tangent space of the constraint manifold is
/// invariant under A; restricted to it (independent coordinates and speeds) it is the reduced
/// model `eomgen linearize` prints.
///
/// first_order_form works on any sizes (the generator uses it with dynamic ones);
/// linearization and second_order_linearization evaluate a model and allocate nothing.
#include <type_traits>
#include <utility>

#include "eomrt/dynamics_kkt.hpp"
#include "eomrt/dynamics_unconstrained.hpp"
#include "eomrt/kkt_system.hpp"

namespace eomrt {

/// The derivatives linearization_terms gives at one point (nc = 0: S_q and S_qd are empty).
template <class Scalar, int nq = Eigen::Dynamic, int nu = Eigen::Dynamic, int nc = Eigen::Dynamic>
struct LinearizationTerms {
  Eigen::Matrix<Scalar, nq, nq> K;     ///< dR/dq (nq x nq)
  Eigen::Matrix<Scalar, nq, nq> D;     ///< dR/dqd (nq x nq)
  Eigen::Matrix<Scalar, nq, nu> B_u;   ///< dF/du (nq x nu)
  Eigen::Matrix<Scalar, nc, nq> S_q;   ///< dS/dq (nc x nq)
  Eigen::Matrix<Scalar, nc, nq> S_qd;  ///< dS/dqd (nc x nq)
};

/// A (2 nq x 2 nq) of dx' = A dx + B du.
template <class Scalar, int nq = Eigen::Dynamic>
using StateMatrix = Eigen::Matrix<Scalar, detail::size_times(2, nq), detail::size_times(2, nq)>;
/// B (2 nq x nu) of dx' = A dx + B du.
template <class Scalar, int nq = Eigen::Dynamic, int nu = Eigen::Dynamic>
using StateInputMatrix = Eigen::Matrix<Scalar, detail::size_times(2, nq), nu>;
/// d[qdd; lambda]/d[q, qd, u] ((nq + nc) x (2 nq + nu)), the constrained solve's scratch.
template <class Scalar, int nq = Eigen::Dynamic, int nu = Eigen::Dynamic, int nc = Eigen::Dynamic>
using KktDerivatives = Eigen::Matrix<Scalar, detail::size_sum(nq, nc), detail::size_sum(detail::size_times(2, nq), nu)>;

namespace detail {

// Writes A and B of the unconstrained form into A, B of the right sizes (a caller's blocks or
// the workspace's): [0, I] written as it is, -M^-1 [K, D] and M^-1 B_u solved in place.
template <class Llt, class Scalar, int nq, int nu, int nc, class OutA, class OutB>
void write_first_order_form(const Llt& mass_llt, const LinearizationTerms<Scalar, nq, nu, nc>& terms,
                            Eigen::MatrixBase<OutA>& A, Eigen::MatrixBase<OutB>& B) {
  const Eigen::Index n = terms.K.rows();
  A.topLeftCorner(n, n).setZero();
  A.topRightCorner(n, n).setIdentity();
  A.bottomLeftCorner(n, n) = -terms.K;
  A.bottomRightCorner(n, n) = -terms.D;
  auto bottom = A.bottomRows(n);
  mass_llt.solveInPlace(bottom);
  B.topRows(n).setZero();
  if constexpr (nu != 0) {
    auto inputs = B.bottomRows(n);
    inputs = terms.B_u;
    mass_llt.solveInPlace(inputs);
  }
}

// Writes A and B of the constrained form from the KKT solve of the derivatives' right sides.
template <class Scalar, int nq, int nu, int nc, class OutA, class OutB>
void write_first_order_form(const KktSystem<Scalar, nq, nc>& kkt, const LinearizationTerms<Scalar, nq, nu, nc>& terms,
                            KktDerivatives<Scalar, nq, nu, nc>& derivatives, Eigen::MatrixBase<OutA>& A,
                            Eigen::MatrixBase<OutB>& B) {
  const Eigen::Index n = terms.K.rows(), m = terms.S_q.rows(), k = terms.B_u.cols();
  derivatives.resize(n + m, 2 * n + k);
  derivatives.topLeftCorner(n, n) = -terms.K;
  derivatives.block(0, n, n, n) = -terms.D;
  derivatives.topRightCorner(n, k) = terms.B_u;
  derivatives.bottomLeftCorner(m, n) = terms.S_q;
  derivatives.block(n, n, m, n) = terms.S_qd;
  derivatives.bottomRightCorner(m, k).setZero();
  kkt.solve_in_place(derivatives);
  A.topLeftCorner(n, n).setZero();
  A.topRightCorner(n, n).setIdentity();
  A.bottomRows(n) = derivatives.topLeftCorner(n, 2 * n);
  B.topRows(n).setZero();
  B.bottomRows(n) = derivatives.topRightCorner(n, k);
}

}  // namespace detail

/// A and B of an unconstrained model from its second-order form.
/// \param[in]  mass_llt  Cholesky factorization of M at the point (regular)
/// \param[in]  terms     K, D, B_u at the point
/// \param[out] A, B      dx' = A dx + B du (resized if dynamic)
template <class Llt, class Scalar, int nq, int nu, int nc>
void first_order_form(const Llt& mass_llt, const LinearizationTerms<Scalar, nq, nu, nc>& terms,
                      StateMatrix<Scalar, nq>& A, StateInputMatrix<Scalar, nq, nu>& B) {
  const Eigen::Index n = terms.K.rows(), m = terms.B_u.cols();
  A.resize(2 * n, 2 * n);
  B.resize(2 * n, m);
  detail::write_first_order_form(mass_llt, terms, A, B);
}

/// A and B of a constrained model: the derivatives of its KKT accelerations.
/// \param[in]  kkt          the KKT system of M and Xi at the point, factorized (compute() ok)
/// \param[in]  terms        K, D, B_u, S_q, S_qd at the point
/// \param[out] derivatives  d[qdd; lambda]/d[q, qd, u] (scratch, resized if dynamic)
/// \param[out] A, B         dx' = A dx + B du (resized if dynamic)
template <class Scalar, int nq, int nu, int nc>
void first_order_form(const KktSystem<Scalar, nq, nc>& kkt, const LinearizationTerms<Scalar, nq, nu, nc>& terms,
                      KktDerivatives<Scalar, nq, nu, nc>& derivatives, StateMatrix<Scalar, nq>& A,
                      StateInputMatrix<Scalar, nq, nu>& B) {
  const Eigen::Index n = terms.K.rows(), k = terms.B_u.cols();
  A.resize(2 * n, 2 * n);
  B.resize(2 * n, k);
  detail::write_first_order_form(kkt, terms, derivatives, A, B);
}

namespace detail {

// linearization_terms taking P as its parameter argument (Parameters or Constants)
template <class Model, class Scalar, class P, class = void>
struct has_linearization_terms : std::false_type {};
template <class Model, class Scalar, class P>
struct has_linearization_terms<Model, Scalar, P, std::enable_if_t<Model::nc == 0, void_t<decltype(Model::linearization_terms(
    std::declval<const Scalar&>(), std::declval<const typename ModelTypes<Model, Scalar>::Coordinates&>(),
    std::declval<const typename ModelTypes<Model, Scalar>::Coordinates&>(),
    std::declval<const typename ModelTypes<Model, Scalar>::Inputs&>(),
    std::declval<const P&>(),
    std::declval<const typename ModelTypes<Model, Scalar>::Coordinates&>(),
    std::declval<Eigen::Matrix<Scalar, Model::nq, Model::nq>&>(), std::declval<Eigen::Matrix<Scalar, Model::nq, Model::nq>&>(),
    std::declval<Eigen::Matrix<Scalar, Model::nq, Model::nu>&>()))>>> : std::true_type {};
template <class Model, class Scalar, class P>
struct has_linearization_terms<Model, Scalar, P, std::enable_if_t<(Model::nc > 0), void_t<decltype(Model::linearization_terms(
    std::declval<const Scalar&>(), std::declval<const typename ModelTypes<Model, Scalar>::Coordinates&>(),
    std::declval<const typename ModelTypes<Model, Scalar>::Coordinates&>(),
    std::declval<const typename ModelTypes<Model, Scalar>::Inputs&>(),
    std::declval<const P&>(),
    std::declval<const typename ModelTypes<Model, Scalar>::Coordinates&>(),
    std::declval<const typename ModelTypes<Model, Scalar>::ConstraintVector&>(),
    std::declval<Eigen::Matrix<Scalar, Model::nq, Model::nq>&>(), std::declval<Eigen::Matrix<Scalar, Model::nq, Model::nq>&>(),
    std::declval<Eigen::Matrix<Scalar, Model::nq, Model::nu>&>(),
    std::declval<typename ModelTypes<Model, Scalar>::ConstraintJacobian&>(),
    std::declval<typename ModelTypes<Model, Scalar>::ConstraintJacobian&>()))>>> : std::true_type {};

// forward_dynamics_derivatives with qdd as its first output (generated with --linearization for
// models without constraints), taking P as its parameter argument
template <class Model, class Scalar, class P, class = void>
struct has_forward_dynamics_derivatives : std::false_type {};
template <class Model, class Scalar, class P>
struct has_forward_dynamics_derivatives<Model, Scalar, P, void_t<decltype(Model::forward_dynamics_derivatives(
    std::declval<const Scalar&>(), std::declval<const typename ModelTypes<Model, Scalar>::Coordinates&>(),
    std::declval<const typename ModelTypes<Model, Scalar>::Coordinates&>(),
    std::declval<const typename ModelTypes<Model, Scalar>::Inputs&>(),
    std::declval<const P&>(), std::declval<typename ModelTypes<Model, Scalar>::Coordinates&>(),
    std::declval<Eigen::Matrix<Scalar, Model::nq, Model::nq>&>(), std::declval<Eigen::Matrix<Scalar, Model::nq, Model::nq>&>(),
    std::declval<Eigen::Matrix<Scalar, Model::nq, Model::nu>&>()))>> : std::true_type {};

}  // namespace detail

/// Scratch and results of the linearization of one model, for one scalar type; fixed-size, so
/// the algorithms below allocate nothing.
template <class Model, class Scalar = double>
struct LinearizationWorkspace {
  static constexpr int nq = Model::nq;
  static constexpr int nu = Model::nu;
  static constexpr int nc = Model::nc;
  /// the operating point's forward dynamics: M, F, Xi, b, their factorizations, and qdd0 and
  /// lambda0 in dynamics.qdd and dynamics.lambda
  DynamicsWorkspace<Model, Scalar> dynamics;
  LinearizationTerms<Scalar, nq, nu, nc> terms;      ///< K, D, B_u (S_q, S_qd) at qdd0, lambda0
  KktDerivatives<Scalar, nq, nu, nc> derivatives;    ///< d[qdd; lambda]/d[q, qd, u] (nc > 0)
  StateMatrix<Scalar, nq> A;                         ///< result (2 nq x 2 nq)
  StateInputMatrix<Scalar, nq, nu> B;                ///< result (2 nq x nu)
};

/// The second-order form M dqdd + D dqd + K dq = B_u du of an unconstrained model about
/// (t, q, qd, u), K taken at the point's accelerations qdd0 = M^-1 F (zero at an equilibrium).
/// \param[in]  p      parameters, or their Constants (model_traits.hpp) to evaluate repeatedly
/// \param[out] ws     ws.dynamics.M, ws.terms.K, ws.terms.D, ws.terms.B_u; qdd0 in
///                    ws.dynamics.qdd and the Cholesky factor of M in ws.dynamics.mass_llt
/// \param[in]  t      time
/// \param[in]  q, qd  coordinates and rates (dim nq)
/// \param[in]  u      inputs (dim nu)
/// \return ok; singular_mass_matrix if M is not (numerically) positive definite; non_finite if
///         M, F, qdd0 or a term is not finite
template <class Model, class Scalar,
          class ParametersOrConstants = typename ModelTypes<Model, Scalar>::Parameters>
DynamicsStatus second_order_linearization(const ParametersOrConstants& p,
                                          LinearizationWorkspace<Model, Scalar>& ws, const Scalar& t,
                                          const typename ModelTypes<Model, Scalar>::Coordinates& q,
                                          const typename ModelTypes<Model, Scalar>::Coordinates& qd,
                                          const typename ModelTypes<Model, Scalar>::Inputs& u) noexcept {
  static_assert(is_parameter_argument_v<Model, Scalar, ParametersOrConstants>,
                "eomrt: p must be the model's Parameters or its Constants");
  static_assert(Model::nc == 0,
                "second_order_linearization: the model has constraints; use linearization (the KKT form)");
  static_assert(detail::has_linearization_terms<Model, Scalar, ParametersOrConstants>::value,
                "eomrt model: linearization needs linearization_terms; generate with --linearization");
  // the factor of M solves for A and B below, so M is factorized even where the model has its
  // own forward_dynamics()
  const DynamicsStatus status = detail::forward_dynamics_by_mass_matrix<Model>(p, ws.dynamics, t, q, qd, u);
  if (status != DynamicsStatus::ok) return status;
  Model::linearization_terms(t, q, qd, u, p, ws.dynamics.qdd, ws.terms.K, ws.terms.D, ws.terms.B_u);
  return ws.terms.K.allFinite() && ws.terms.D.allFinite() && ws.terms.B_u.allFinite() ? DynamicsStatus::ok
                                                                                        : DynamicsStatus::non_finite;
}

namespace detail {

// linearization() into A and B of the right sizes (the workspace's, or a caller's blocks)
template <class Model, class Scalar, class ParametersOrConstants, class OutA, class OutB>
DynamicsStatus linearization_into(const ParametersOrConstants& p, LinearizationWorkspace<Model, Scalar>& ws,
                                  const Scalar& t, const typename ModelTypes<Model, Scalar>::Coordinates& q,
                                  const typename ModelTypes<Model, Scalar>::Coordinates& qd,
                                  const typename ModelTypes<Model, Scalar>::Inputs& u, Eigen::MatrixBase<OutA>& A,
                                  Eigen::MatrixBase<OutB>& B) noexcept {
  static_assert(is_parameter_argument_v<Model, Scalar, ParametersOrConstants>,
                "eomrt: p must be the model's Parameters or its Constants");
  static_assert(has_linearization_terms<Model, Scalar, ParametersOrConstants>::value,
                "eomrt model: linearization needs linearization_terms; generate with --linearization");
  // a constrained header's forward_dynamics_derivatives solves the KKT system without the
  // runtime's regularity tests and redundant rows: the KKT path below keeps them
  if constexpr (Model::nc == 0 && has_forward_dynamics_derivatives<Model, Scalar, ParametersOrConstants>::value) {
    // the generated derivatives of qdd written straight into A's and B's bottom rows, and qdd0
    // (which they compute on the way) into ws.dynamics for the caller: a step's stages need it
    if (!q.allFinite() || !qd.allFinite() || !u.allFinite()) return DynamicsStatus::non_finite;
    constexpr int n = Model::nq;
    A.template topLeftCorner<n, n>().setZero();
    A.template topRightCorner<n, n>().setIdentity();
    B.template topRows<n>().setZero();
    // it tests its pivots and every entry it writes, and the top rows are constants
    if (Model::forward_dynamics_derivatives(t, q, qd, u, p, ws.dynamics.qdd, A.template bottomLeftCorner<n, n>(),
                                            A.template bottomRightCorner<n, n>(), B.template bottomRows<n>()))
      return DynamicsStatus::ok;
    // which of the two failed: the model's forward dynamics tells a singular M (a finite point
    // whose qdd is not finite included) from derivatives that are not finite
    const DynamicsStatus status = forward_dynamics_unconstrained<Model>(p, ws.dynamics, t, q, qd, u);
    return status != DynamicsStatus::ok ? status : DynamicsStatus::non_finite;
  } else if constexpr (Model::nc == 0) {
    const DynamicsStatus status = second_order_linearization<Model>(p, ws, t, q, qd, u);
    if (status != DynamicsStatus::ok) return status;
    write_first_order_form(ws.dynamics.mass_llt, ws.terms, A, B);
  } else {
    const DynamicsStatus status = forward_dynamics_kkt<Model>(p, ws.dynamics, t, q, qd, u);
    if (status != DynamicsStatus::ok) return status;
    Model::linearization_terms(t, q, qd, u, p, ws.dynamics.qdd, ws.dynamics.lambda, ws.terms.K, ws.terms.D,
                               ws.terms.B_u, ws.terms.S_q, ws.terms.S_qd);
    write_first_order_form(ws.dynamics.solvers.kkt, ws.terms, ws.derivatives, A, B);
  }
  return A.allFinite() && B.allFinite() ? DynamicsStatus::ok : DynamicsStatus::non_finite;
}

}  // namespace detail

/// A and B of dx' = A dx + B du, x = [q; qd], about (t, q, qd, u), from exact derivatives; for
/// a constrained model those of the KKT accelerations (without stabilization) on the full state.
/// \param[in]  p      parameters, or their Constants (model_traits.hpp) to evaluate repeatedly
/// \param[out] ws     ws.A (2 nq x 2 nq) and ws.B (2 nq x nu) receive the result; qdd0 (and with
///                    constraints lambda0) stay in ws.dynamics. The bottom rows of A and B come
///                    from the model's forward_dynamics_derivatives where it has them (generated
///                    with --linearization, no constraints), ws.terms left alone; otherwise from
///                    K, D, B_u (S_q, S_qd) of linearization_terms, kept in ws.terms
/// \param[in]  t      time
/// \param[in]  q, qd  coordinates and rates (dim nq)
/// \param[in]  u      inputs (dim nu)
/// \return ok; singular_mass_matrix (unconstrained) or singular_kkt_matrix (constrained) where
///         the point's dynamics are singular; non_finite if a term, A or B is not finite
template <class Model, class Scalar,
          class ParametersOrConstants = typename ModelTypes<Model, Scalar>::Parameters>
DynamicsStatus linearization(const ParametersOrConstants& p,
                             LinearizationWorkspace<Model, Scalar>& ws, const Scalar& t,
                             const typename ModelTypes<Model, Scalar>::Coordinates& q,
                             const typename ModelTypes<Model, Scalar>::Coordinates& qd,
                             const typename ModelTypes<Model, Scalar>::Inputs& u) noexcept {
  return detail::linearization_into<Model>(p, ws, t, q, qd, u, ws.A, ws.B);
}

/// linearization() written into a caller's matrices: A and B may be blocks of larger ones (an
/// MPC's stacked dynamics), of 2 nq x 2 nq and 2 nq x nu; ws.A and ws.B are left alone. The top
/// half [0, I] of A and [0] of B are written as they are, not solved for.
/// \param[out] A, B  dx' = A dx + B du, written through (blocks and maps bind as Eigen's
///                   in-place solves take them)
template <class Model, class Scalar, class ParametersOrConstants, class OutA, class OutB>
DynamicsStatus linearization(const ParametersOrConstants& p, LinearizationWorkspace<Model, Scalar>& ws,
                             const Scalar& t, const typename ModelTypes<Model, Scalar>::Coordinates& q,
                             const typename ModelTypes<Model, Scalar>::Coordinates& qd,
                             const typename ModelTypes<Model, Scalar>::Inputs& u, const Eigen::MatrixBase<OutA>& A,
                             const Eigen::MatrixBase<OutB>& B) noexcept {
  static_assert(int(OutA::RowsAtCompileTime) == Eigen::Dynamic || int(OutA::RowsAtCompileTime) == 2 * Model::nq,
                "eomrt::linearization: A has 2 nq rows");
  static_assert(int(OutB::ColsAtCompileTime) == Eigen::Dynamic || int(OutB::ColsAtCompileTime) == Model::nu,
                "eomrt::linearization: B has nu columns");
  eigen_assert(A.rows() == 2 * Model::nq && A.cols() == 2 * Model::nq && B.rows() == 2 * Model::nq &&
               B.cols() == Model::nu && "eomrt::linearization: A is 2 nq x 2 nq and B 2 nq x nu");
  auto& a = const_cast<Eigen::MatrixBase<OutA>&>(A);
  auto& b = const_cast<Eigen::MatrixBase<OutB>&>(B);
  return detail::linearization_into<Model>(p, ws, t, q, qd, u, a, b);
}

}  // namespace eomrt
