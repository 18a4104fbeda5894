#pragma once
/// \file
/// Forward dynamics with Lagrange multipliers: the KKT system of docs/conventions.md,
///   [[M, -Xi^T], [-Xi, 0]] [qdd; lambda] = [F; b],   b = dXi/dt qd + dXi_t/dt,
/// (with Baumgarte terms b becomes -r, see Baumgarte), solved by KktSystem (kkt_system.hpp).
#include "eomrt/dynamics_unconstrained.hpp"
#include "eomrt/kkt_system.hpp"

namespace eomrt {

/// Accelerations and multipliers from the KKT system; M may be singular where the KKT matrix
/// is not (a quaternion attitude).
/// \param[in]  p      parameters, or their Constants (model_traits.hpp) to evaluate repeatedly
/// \param[out] ws     workspace; ws.qdd (dim nq) and ws.lambda (dim nc) receive the result,
///                    and the evaluated terms stay in ws (M, F, Xi, b, residuals)
/// \param[in]  t      time
/// \param[in]  q, qd  coordinates and rates (dim nq)
/// \param[in]  u      inputs (dim nu)
/// \param[in]  stab   Baumgarte stabilization (default: none)
/// \return ok; non_finite if a term or the result is not finite; singular_kkt_matrix if the
///         KKT matrix is singular (dependent constraints, or M singular on the constraint);
///         singular_mass_matrix for an unconstrained model whose M is singular
template <class Model, class Scalar,
          class ParametersOrConstants = typename ModelTypes<Model, Scalar>::Parameters>
DynamicsStatus forward_dynamics_kkt(const ParametersOrConstants& p,
                                    DynamicsWorkspace<Model, Scalar>& ws, const Scalar& t,
                                    const typename ModelTypes<Model, Scalar>::Coordinates& q,
                                    const typename ModelTypes<Model, Scalar>::Coordinates& qd,
                                    const typename ModelTypes<Model, Scalar>::Inputs& u,
                                    const Baumgarte<Scalar>& stab = {}) {
  static_assert(is_parameter_argument_v<Model, Scalar, ParametersOrConstants>,
                "eomrt: p must be the model's Parameters or its Constants");
  const DynamicsStatus status = evaluate_dynamics_terms(p, ws, t, q, qd, u, stab);
  if (status != DynamicsStatus::ok) return status;
  if constexpr (Model::nc == 0) {
    return detail::solve_mass_matrix(ws);
  } else {
    auto& s = ws.solvers;
    if (s.kkt.compute(ws.M, ws.Xi, ws.singular_rcond) != DynamicsStatus::ok)
      return DynamicsStatus::singular_kkt_matrix;
    s.kkt_rhs << ws.F, -ws.constraint_rhs;  // [F; b] without stabilization
    s.kkt.solve_in_place(s.kkt_rhs);
    ws.qdd = s.kkt_rhs.template head<Model::nq>();
    ws.lambda = s.kkt_rhs.template tail<Model::nc>();
    return ws.qdd.allFinite() && ws.lambda.allFinite() ? DynamicsStatus::ok
                                                      : DynamicsStatus::non_finite;
  }
}

}  // namespace eomrt
