#pragma once
/// \file
/// Forward dynamics of an unconstrained model: M qdd = F solved by Cholesky.
#include "eomrt/workspace.hpp"

namespace eomrt {

namespace detail {

/// qdd from the M and F already in ws (Cholesky; M must be positive definite).
template <class Model, class Scalar>
DynamicsStatus solve_mass_matrix(DynamicsWorkspace<Model, Scalar>& ws) {
  ws.mass_llt.compute(ws.M);
  // LLT reports only a non-positive pivot; a tiny positive one (a configuration next to a
  // singularity, e.g. a gimbal lock) is caught by the pivot ratio
  if (!cholesky_is_regular(ws.mass_llt, ws.singular_rcond))
    return DynamicsStatus::singular_mass_matrix;
  ws.qdd = ws.mass_llt.solve(ws.F);
  return ws.qdd.allFinite() ? DynamicsStatus::ok : DynamicsStatus::non_finite;
}

}  // namespace detail

/// Accelerations of a model without constraints, M(q, t) qdd = F(q, qd, t, u).
/// \param[in]  p      parameters, or their Constants (model_traits.hpp) to evaluate repeatedly
/// \param[out] ws     workspace; ws.qdd receives the result, ws.M and ws.F the evaluated terms
/// \param[in]  t      time
/// \param[in]  q, qd  coordinates and rates (dim nq)
/// \param[in]  u      inputs (dim nu)
/// \return ok; non_finite if M, F or qdd is not finite; singular_mass_matrix if M is not
///         (numerically) positive definite
template <class Model, class Scalar,
          class ParametersOrConstants = typename ModelTypes<Model, Scalar>::Parameters>
DynamicsStatus forward_dynamics_unconstrained(
    const ParametersOrConstants& p, DynamicsWorkspace<Model, Scalar>& ws,
    const Scalar& t, const typename ModelTypes<Model, Scalar>::Coordinates& q,
    const typename ModelTypes<Model, Scalar>::Coordinates& qd,
    const typename ModelTypes<Model, Scalar>::Inputs& u) {
  static_assert(is_parameter_argument_v<Model, Scalar, ParametersOrConstants>,
                "eomrt: p must be the model's Parameters or its Constants");
  static_assert(Model::nc == 0,
                "forward_dynamics_unconstrained: the model has constraints; use "
                "forward_dynamics_kkt or forward_dynamics_null_space");
  const DynamicsStatus status = evaluate_dynamics_terms(p, ws, t, q, qd, u, Baumgarte<Scalar>{});
  if (status != DynamicsStatus::ok) return status;
  return detail::solve_mass_matrix(ws);
}

}  // namespace eomrt
