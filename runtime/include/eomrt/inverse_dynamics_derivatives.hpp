#pragma once
/// \file
/// Derivatives of the inverse dynamics tau = M(q) qdd - F(t, q, qd, u) of an unconstrained
/// model (the generated inverse_dynamics, docs/controller-functions.md) at given accelerations:
///   dtau/dq = K,   dtau/dqd = D,   dtau/du = -B_u,   dtau/dqdd = M,
/// where K, D, B_u are the generated linearization_terms taken at those accelerations (the
/// residual R = M qdd - F is tau itself). Solvers that write the dynamics as tau(q, qd, qdd)
/// (direct collocation, inverse-dynamics MPC) consume these. Nothing allocates.
#include "eomrt/linearization.hpp"

namespace eomrt {

/// dtau/dq and dtau/dqd (nq x nq each) of tau = M qdd - F about (t, q, qd, qdd, u).
/// \param[in]  p         parameters, or their Constants (model_traits.hpp)
/// \param[in]  t         time
/// \param[in]  q, qd     coordinates and rates (dim nq)
/// \param[in]  qdd       the accelerations tau produces (dim nq)
/// \param[in]  u         inputs (dim nu)
/// \param[out] dtau_dq   K at qdd, written through (a block of a caller's matrix binds)
/// \param[out] dtau_dqd  D at qdd, written through
/// \return ok, or non_finite if a derivative is not a finite number
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
  static_assert(Model::nc == 0,
                "inverse_dynamics_derivatives: the model has constraints, whose inverse dynamics also split lambda");
  static_assert(detail::has_linearization_terms<Model, Scalar, ParametersOrConstants>::value,
                "eomrt model: inverse_dynamics_derivatives needs linearization_terms; generate with --linearization");
  auto& K = const_cast<Eigen::MatrixBase<OutQ>&>(dtau_dq).derived();
  auto& D = const_cast<Eigen::MatrixBase<OutQd>&>(dtau_dqd).derived();
  Eigen::Matrix<Scalar, Model::nq, Model::nu> B_u;  // dtau/du = -B_u, not asked for
  Model::linearization_terms(t, q, qd, u, p, qdd, K, D, B_u);
  return K.allFinite() && D.allFinite() ? DynamicsStatus::ok : DynamicsStatus::non_finite;
}

}  // namespace eomrt
