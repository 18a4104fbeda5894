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

/// qdd by the Cholesky factorization of M, whatever else the model offers: ws.M, ws.F and
/// ws.mass_llt are filled (the linearization solves with the factor). Arguments as below.
template <class Model, class Scalar,
          class ParametersOrConstants = typename ModelTypes<Model, Scalar>::Parameters>
DynamicsStatus forward_dynamics_by_mass_matrix(
    const ParametersOrConstants& p, DynamicsWorkspace<Model, Scalar>& ws,
    const Scalar& t, const typename ModelTypes<Model, Scalar>::Coordinates& q,
    const typename ModelTypes<Model, Scalar>::Coordinates& qd,
    const typename ModelTypes<Model, Scalar>::Inputs& u) {
  const DynamicsStatus status = evaluate_dynamics_terms(p, ws, t, q, qd, u, Baumgarte<Scalar>{});
  if (status != DynamicsStatus::ok) return status;
  return solve_mass_matrix(ws);
}

}  // namespace detail

/// Accelerations of a model without constraints, M(q, t) qdd = F(q, qd, t, u): by the model's
/// own forward_dynamics() when it has one and prefers it (uses_forward_dynamics_v: linear in the
/// number of bodies for a generated tree, and preferred where that takes fewer operations),
/// otherwise by the Cholesky factorization of M.
/// \param[in]  p      parameters, or their Constants (model_traits.hpp) to evaluate repeatedly
/// \param[out] ws     workspace; ws.qdd receives the result. ws.M and ws.F receive the evaluated
///                    terms on the Cholesky path only: with the model's forward_dynamics() they
///                    are left as they were
/// \param[in]  t      time
/// \param[in]  q, qd  coordinates and rates (dim nq)
/// \param[in]  u      inputs (dim nu)
/// \return ok; non_finite if M, F or qdd is not finite; singular_mass_matrix if M is not
///         (numerically) positive definite. With the model's forward_dynamics(), a non-positive
///         pivot or a qdd that is not finite is singular_mass_matrix, and a tiny positive pivot
///         passes (there is no pivot-ratio test on that path)
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
  if constexpr (uses_forward_dynamics_v<Model, Scalar>) {
    return Model::forward_dynamics(t, q, qd, u, p, ws.qdd) ? DynamicsStatus::ok
                                                            : DynamicsStatus::singular_mass_matrix;
  } else {
    return detail::forward_dynamics_by_mass_matrix<Model>(p, ws, t, q, qd, u);
  }
}

}  // namespace eomrt
