#pragma once
/// \file
/// Forward dynamics with Lagrange multipliers: the KKT system of docs/conventions.md,
///   [[M, -Xi^T], [-Xi, 0]] [qdd; lambda] = [F; b],   b = dXi/dt qd + dXi_t/dt,
/// (with Baumgarte terms b becomes -r, see Baumgarte). M alone may be singular, e.g. for a
/// quaternion attitude with omega = 2 S(q) qd, where M has rank nq - 1; the KKT matrix is
/// still regular as long as M is positive definite on the null space of Xi.
#include "eomrt/dynamics_unconstrained.hpp"

namespace eomrt {

/// Accelerations and multipliers from the KKT system (LU with partial pivoting: the matrix is
/// symmetric but indefinite, so Cholesky does not apply).
/// \param[in]  p      parameters
/// \param[out] ws     workspace; ws.qdd (dim nq) and ws.lambda (dim nc) receive the result,
///                    and the evaluated terms stay in ws (M, F, Xi, b, residuals)
/// \param[in]  t      time
/// \param[in]  q, qd  coordinates and rates (dim nq)
/// \param[in]  u      inputs (dim nu)
/// \param[in]  stab   Baumgarte stabilization (default: none)
/// \return ok; non_finite if a term or the result is not finite; singular_kkt_matrix if the
///         KKT matrix is singular (dependent constraints, or M singular on the constraint);
///         singular_mass_matrix for an unconstrained model whose M is singular
template <class Model, class Scalar>
DynamicsStatus forward_dynamics_kkt(const typename ModelTypes<Model, Scalar>::Parameters& p,
                                    DynamicsWorkspace<Model, Scalar>& ws, const Scalar& t,
                                    const typename ModelTypes<Model, Scalar>::Coordinates& q,
                                    const typename ModelTypes<Model, Scalar>::Coordinates& qd,
                                    const typename ModelTypes<Model, Scalar>::Inputs& u,
                                    const Baumgarte<Scalar>& stab = {}) {
  const DynamicsStatus status = evaluate_dynamics_terms(p, ws, t, q, qd, u, stab);
  if (status != DynamicsStatus::ok) return status;
  if constexpr (Model::nc == 0) {
    return detail::solve_mass_matrix(ws);
  } else {
    constexpr int nq = Model::nq;
    constexpr int nc = Model::nc;
    auto& s = ws.solvers;
    // the constraint block is scaled by sigma to the size of M: in SI units M can be 1e-6
    // (a coin) while Xi is O(1), and the unscaled matrix would lose digits for no reason.
    // Solving for mu = lambda / sigma keeps the system equivalent.
    const Scalar xi_size = ws.Xi.cwiseAbs().maxCoeff();
    const Scalar m_size = ws.M.cwiseAbs().maxCoeff();
    const Scalar sigma = xi_size > 0 && m_size > 0 ? m_size / xi_size : Scalar(1);
    s.kkt.template topLeftCorner<nq, nq>() = ws.M;
    s.kkt.template topRightCorner<nq, nc>() = -sigma * ws.Xi.transpose();
    s.kkt.template bottomLeftCorner<nc, nq>() = -sigma * ws.Xi;
    s.kkt.template bottomRightCorner<nc, nc>().setZero();
    s.kkt_rhs.template head<nq>() = ws.F;
    s.kkt_rhs.template tail<nc>() = -sigma * ws.constraint_rhs;  // = sigma b without stabilization
    s.kkt_lu.compute(s.kkt);
    if (!(s.kkt_lu.rcond() > ws.singular_rcond)) return DynamicsStatus::singular_kkt_matrix;
    s.kkt_rhs = s.kkt_lu.solve(s.kkt_rhs);
    ws.qdd = s.kkt_rhs.template head<nq>();
    ws.lambda = sigma * s.kkt_rhs.template tail<nc>();
    return ws.qdd.allFinite() && ws.lambda.allFinite() ? DynamicsStatus::ok
                                                      : DynamicsStatus::non_finite;
  }
}

}  // namespace eomrt
