#pragma once
/// \file
/// Derivatives of the inverse dynamics (the generated inverse_dynamics,
/// docs/controller-functions.md) at given accelerations. Solvers that write the dynamics as
/// tau(q, qd, qdd) (direct collocation, inverse-dynamics MPC) consume these. Nothing allocates.
///
/// Without constraints tau = M(q) qdd - F(t, q, qd, u) is the residual R itself:
///   dtau/dq = K,   dtau/dqd = D,   dtau/du = -B_u,   dtau/dqdd = M,
/// K, D, B_u the generated linearization_terms taken at those accelerations.
///
/// With constraints the header splits R = tau + Xi^T lambda, lambda = (Xi Xi^T)^-1 Xi R, tau
/// orthogonal to the rows of Xi. Then, with K and D the linearization_terms at (qdd, lambda)
/// (the derivatives of R - Xi^T lambda at fixed lambda) and G = Xi Xi^T, differentiating
/// Xi tau = 0 gives
///   dlambda/dq_k = G^-1 (Xi K e_k + (dXi/dq_k) tau),   dtau/dq = K - Xi^T dlambda/dq,
///   dlambda/dqd  = G^-1 Xi D,                          dtau/dqd = D - Xi^T dlambda/dqd,
/// where (dXi/dq_k) tau is column k of S_q taken at qdd = tau less S_q at qdd = 0 (S_q =
/// d(Xi qdd + b)/dq is affine in qdd).
#include "eomrt/linearization.hpp"
#include "eomrt/lu_factorization.hpp"
#include "eomrt/regularity.hpp"

namespace eomrt {

namespace detail {

// the constrained split's derivatives; dlambda_dq and dlambda_dqd are nc x nq
template <class Model, class Scalar, class P, class OutQ, class OutQd, class OutLq, class OutLqd>
DynamicsStatus constrained_inverse_dynamics_derivatives(const P& p, const Scalar& t,
                                                        const typename ModelTypes<Model, Scalar>::Coordinates& q,
                                                        const typename ModelTypes<Model, Scalar>::Coordinates& qd,
                                                        const typename ModelTypes<Model, Scalar>::Coordinates& qdd,
                                                        const typename ModelTypes<Model, Scalar>::Inputs& u,
                                                        OutQ& dtau_dq, OutQd& dtau_dqd, OutLq& dlambda_dq,
                                                        OutLqd& dlambda_dqd) noexcept {
  using Types = ModelTypes<Model, Scalar>;
  constexpr int nq = Model::nq, nc = Model::nc, nu = Model::nu;
  typename Types::Coordinates tau;
  typename Types::ConstraintVector lambda;
  Model::inverse_dynamics(t, q, qd, qdd, u, p, tau, lambda);
  Eigen::Matrix<Scalar, nq, nq> K, D, unused_K, unused_D;
  Eigen::Matrix<Scalar, nq, nu> B_u;
  typename Types::ConstraintJacobian Xi, S_q, S_qd, S_q_at_tau, S_q_at_zero;
  Model::linearization_terms(t, q, qd, u, p, qdd, lambda, K, D, B_u, S_q, S_qd);
  Model::linearization_terms(t, q, qd, u, p, tau, lambda, unused_K, unused_D, B_u, S_q_at_tau, S_qd);
  Model::linearization_terms(t, q, qd, u, p, Types::Coordinates::Zero().eval(), lambda, unused_K, unused_D, B_u,
                             S_q_at_zero, S_qd);
  Model::constraint_jacobian(t, q, p, Xi);
  LuFactorization<Scalar, nc> gram;
  gram.compute(Xi * Xi.transpose());
  if (!gram.is_regular(default_singular_rcond<Scalar>())) return DynamicsStatus::singular_constraint_jacobian;
  dlambda_dq = Xi * K + (S_q_at_tau - S_q_at_zero);
  gram.solve_in_place(dlambda_dq);
  dlambda_dqd = Xi * D;
  gram.solve_in_place(dlambda_dqd);
  dtau_dq = K - Xi.transpose() * dlambda_dq;
  dtau_dqd = D - Xi.transpose() * dlambda_dqd;
  return dtau_dq.allFinite() && dtau_dqd.allFinite() && dlambda_dq.allFinite() && dlambda_dqd.allFinite()
             ? DynamicsStatus::ok
             : DynamicsStatus::non_finite;
}

}  // namespace detail

/// dtau/dq and dtau/dqd (nq x nq each) of the inverse dynamics about (t, q, qd, qdd, u): of
/// tau = M qdd - F, or with constraints of the least tau of the split (file comment).
/// \param[in]  p         parameters, or their Constants (model_traits.hpp)
/// \param[in]  t         time
/// \param[in]  q, qd     coordinates and rates (dim nq)
/// \param[in]  qdd       the accelerations tau produces (dim nq)
/// \param[in]  u         inputs (dim nu)
/// \param[out] dtau_dq   written through (a block of a caller's matrix binds)
/// \param[out] dtau_dqd  written through
/// \return ok; non_finite if a derivative is not a finite number; with constraints
///         singular_constraint_jacobian where Xi Xi^T is singular (redundant rows)
template <class Model, class Scalar, class ParametersOrConstants, class OutQ, class OutQd>
DynamicsStatus inverse_dynamics_derivatives(const ParametersOrConstants& p, const Scalar& t,
                                            const typename ModelTypes<Model, Scalar>::Coordinates& q,
                                            const typename ModelTypes<Model, Scalar>::Coordinates& qd,
                                            const typename ModelTypes<Model, Scalar>::Coordinates& qdd,
                                            const typename ModelTypes<Model, Scalar>::Inputs& u,
                                            const Eigen::MatrixBase<OutQ>& dtau_dq,
                                            const Eigen::MatrixBase<OutQd>& dtau_dqd) noexcept {
  static_assert(is_parameter_argument_v<Model, Scalar, ParametersOrConstants>,
                "eomrt: p must be the model's Parameters or its Constants");
  static_assert(detail::has_linearization_terms<Model, Scalar, ParametersOrConstants>::value,
                "eomrt model: inverse_dynamics_derivatives needs linearization_terms; generate with --linearization");
  auto& K = const_cast<Eigen::MatrixBase<OutQ>&>(dtau_dq).derived();
  auto& D = const_cast<Eigen::MatrixBase<OutQd>&>(dtau_dqd).derived();
  if constexpr (Model::nc == 0) {
    Eigen::Matrix<Scalar, Model::nq, Model::nu> B_u;  // dtau/du = -B_u, not asked for
    Model::linearization_terms(t, q, qd, u, p, qdd, K, D, B_u);
    return K.allFinite() && D.allFinite() ? DynamicsStatus::ok : DynamicsStatus::non_finite;
  } else {
    typename ModelTypes<Model, Scalar>::ConstraintJacobian dlambda_dq, dlambda_dqd;
    return detail::constrained_inverse_dynamics_derivatives<Model>(p, t, q, qd, qdd, u, K, D, dlambda_dq, dlambda_dqd);
  }
}

/// The same with the multipliers' derivatives besides, for a model with constraints:
/// dlambda/dq and dlambda/dqd (nc x nq each) of the lambda the generated inverse_dynamics returns.
template <class Model, class Scalar, class ParametersOrConstants, class OutQ, class OutQd, class OutLq, class OutLqd>
DynamicsStatus inverse_dynamics_derivatives(const ParametersOrConstants& p, const Scalar& t,
                                            const typename ModelTypes<Model, Scalar>::Coordinates& q,
                                            const typename ModelTypes<Model, Scalar>::Coordinates& qd,
                                            const typename ModelTypes<Model, Scalar>::Coordinates& qdd,
                                            const typename ModelTypes<Model, Scalar>::Inputs& u,
                                            const Eigen::MatrixBase<OutQ>& dtau_dq,
                                            const Eigen::MatrixBase<OutQd>& dtau_dqd,
                                            const Eigen::MatrixBase<OutLq>& dlambda_dq,
                                            const Eigen::MatrixBase<OutLqd>& dlambda_dqd) noexcept {
  static_assert(is_parameter_argument_v<Model, Scalar, ParametersOrConstants>,
                "eomrt: p must be the model's Parameters or its Constants");
  static_assert(Model::nc > 0, "inverse_dynamics_derivatives: the model has no constraints, hence no lambda");
  static_assert(detail::has_linearization_terms<Model, Scalar, ParametersOrConstants>::value,
                "eomrt model: inverse_dynamics_derivatives needs linearization_terms; generate with --linearization");
  return detail::constrained_inverse_dynamics_derivatives<Model>(
      p, t, q, qd, qdd, u, const_cast<Eigen::MatrixBase<OutQ>&>(dtau_dq).derived(),
      const_cast<Eigen::MatrixBase<OutQd>&>(dtau_dqd).derived(), const_cast<Eigen::MatrixBase<OutLq>&>(dlambda_dq).derived(),
      const_cast<Eigen::MatrixBase<OutLqd>&>(dlambda_dqd).derived());
}

}  // namespace eomrt
