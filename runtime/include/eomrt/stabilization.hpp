#pragma once
/// \file
/// Projection of q and qd back onto the constraint manifold, the alternative to Baumgarte
/// stabilization (see Baumgarte in workspace.hpp) against the drift of an integrated DAE.
///
/// Positions: Gauss-Newton on phi(q, t) = 0 with minimum-norm corrections
///   dq = Xi^T (Xi Xi^T)^{-1} e,   e = phi on the holonomic rows, 0 on the others,
/// so a correction never violates a nonholonomic constraint to first order. Rates: the
/// minimum-norm correction onto Xi qd + Xi_t = 0 (one step, the condition is linear in qd).
/// The norm is Euclidean rather than M-weighted because M may be singular (quaternions).
#include <cmath>
#include <limits>

#include "eomrt/workspace.hpp"

namespace eomrt {

/// Residuals of the constraints at a state.
template <class Scalar>
struct ConstraintResiduals {
  Scalar position = 0;  ///< max |phi_i(q, t)| over the holonomic constraints
  Scalar velocity = 0;  ///< max |(Xi qd + Xi_t)_i| over all constraints
};

/// Evaluates the constraint residuals at (t, q, qd).
/// \param[in]  p      parameters, or their Constants (model_traits.hpp) to evaluate repeatedly
/// \param[out] ws     workspace; ws.phi, ws.Xi, ws.Xi_t, ws.velocity_residual are overwritten
/// \param[in]  t      time
/// \param[in]  q, qd  coordinates and rates (dim nq)
/// \return the largest residuals (zero for an unconstrained model)
template <class Model, class Scalar,
          class ParametersOrConstants = typename ModelTypes<Model, Scalar>::Parameters>
ConstraintResiduals<Scalar> constraint_residuals(
    const ParametersOrConstants& p, DynamicsWorkspace<Model, Scalar>& ws,
    const Scalar& t, const typename ModelTypes<Model, Scalar>::Coordinates& q,
    const typename ModelTypes<Model, Scalar>::Coordinates& qd) {
  static_assert(is_parameter_argument_v<Model, Scalar, ParametersOrConstants>,
                "eomrt: p must be the model's Parameters or its Constants");
  ConstraintResiduals<Scalar> r;
  if constexpr (Model::nc > 0) {
    Model::constraint_jacobian(t, q, p, ws.Xi);
    Model::constraint_rate_term(t, q, p, ws.Xi_t);
    ws.velocity_residual.noalias() = ws.Xi * qd;
    ws.velocity_residual += ws.Xi_t;
    r.velocity = ws.velocity_residual.cwiseAbs().maxCoeff();
    if constexpr (Model::nh > 0) {
      Model::holonomic_residuals(t, q, p, ws.phi);
      r.position = ws.phi.cwiseAbs().maxCoeff();
    }
  }
  return r;
}

/// Projects q onto phi(q, t) = 0 (holonomic constraints only), then qd onto Xi qd + Xi_t = 0.
/// \param[in]     p               parameters, or their Constants (model_traits.hpp)
/// \param[out]    ws              workspace (scratch; ws.Xi etc. hold the final evaluation)
/// \param[in]     t               time
/// \param[in,out] q, qd           coordinates and rates (dim nq), corrected in place
/// \param[in]     max_iterations  Newton iterations allowed for the positions
/// \return ok; singular_constraint_jacobian if Xi Xi^T is singular; non_finite if a term is
///         not finite; projection_failed if the positions did not converge
template <class Model, class Scalar,
          class ParametersOrConstants = typename ModelTypes<Model, Scalar>::Parameters>
DynamicsStatus project_onto_constraints(const ParametersOrConstants& p,
                                        DynamicsWorkspace<Model, Scalar>& ws, const Scalar& t,
                                        typename ModelTypes<Model, Scalar>::Coordinates& q,
                                        typename ModelTypes<Model, Scalar>::Coordinates& qd,
                                        int max_iterations = 8) {
  static_assert(is_parameter_argument_v<Model, Scalar, ParametersOrConstants>,
                "eomrt: p must be the model's Parameters or its Constants");
  if constexpr (Model::nc == 0) {
    return DynamicsStatus::ok;
  } else {
    using std::abs;
    auto& s = ws.solvers;
    const Scalar eps = std::numeric_limits<Scalar>::epsilon();
    const auto factor_gram = [&]() {
      Model::constraint_jacobian(t, q, p, ws.Xi);
      if (!ws.Xi.allFinite()) return DynamicsStatus::non_finite;
      s.dependent_rows.setConstant(false);
      s.gram.noalias() = ws.Xi * ws.Xi.transpose();
      s.gram_lu.compute(s.gram);
      if (s.gram_lu.is_regular(ws.singular_rcond)) return DynamicsStatus::ok;
      // redundant constraints: the rows dependent at this state are left out of the correction
      // (the others imply them here), as the KKT system leaves them out (kkt_system.hpp)
      s.rows_qr.set_threshold(ws.singular_rcond);
      s.rows_qr.compute(ws.Xi.transpose());
      const Eigen::Index rank = s.rows_qr.rank();
      if (rank == Model::nc) return DynamicsStatus::singular_constraint_jacobian;
      for (Eigen::Index k = rank; k < Model::nc; ++k) {
        const Eigen::Index row = s.rows_qr.column(k);
        s.dependent_rows(row) = true;
        ws.Xi.row(row).setZero();
      }
      s.gram.noalias() = ws.Xi * ws.Xi.transpose();
      s.gram.diagonal() += s.dependent_rows.template cast<Scalar>().matrix();
      s.gram_lu.compute(s.gram);
      if (!s.gram_lu.is_regular(ws.singular_rcond))
        return DynamicsStatus::singular_constraint_jacobian;
      return DynamicsStatus::ok;
    };
    if constexpr (Model::nh > 0) {
      bool converged = false;
      Scalar last_step = std::numeric_limits<Scalar>::infinity();
      for (int k = 0; k < max_iterations && !converged; ++k) {
        Model::holonomic_residuals(t, q, p, ws.phi);
        if (!ws.phi.allFinite()) return DynamicsStatus::non_finite;
        if (ws.phi.isZero(0)) break;
        const DynamicsStatus status = factor_gram();
        if (status != DynamicsStatus::ok) return status;
        s.small.setZero();
        for (int i = 0; i < Model::nh; ++i)
          if (!s.dependent_rows(Model::holonomic_rows[i])) s.small(Model::holonomic_rows[i]) = ws.phi(i);
        s.gram_lu.solve_in_place(s.small);
        s.particular.noalias() = ws.Xi.transpose() * s.small;
        q -= s.particular;
        // Newton converges quadratically: once the step is at rounding level of q, phi is too
        last_step = s.particular.cwiseAbs().maxCoeff();
        converged = last_step <= 4 * eps * (1 + q.cwiseAbs().maxCoeff());
      }
      if (!converged) {
        // Newton may stall a few ulps above the strict test, in rounding noise: accept a last
        // step that small; a step still of the size of the error means it did not converge
        Model::holonomic_residuals(t, q, p, ws.phi);
        if (!ws.phi.isZero(0) && !(last_step <= 1000 * eps * (1 + q.cwiseAbs().maxCoeff())))
          return DynamicsStatus::projection_failed;
      }
    }
    const DynamicsStatus status = factor_gram();
    if (status != DynamicsStatus::ok) return status;
    Model::constraint_rate_term(t, q, p, ws.Xi_t);
    ws.velocity_residual.noalias() = ws.Xi * qd;
    ws.velocity_residual += ws.Xi_t;
    for (Eigen::Index k = 0; k < Model::nc; ++k)
      if (s.dependent_rows(k)) ws.velocity_residual(k) = 0;
    s.small = ws.velocity_residual;
    s.gram_lu.solve_in_place(s.small);
    qd.noalias() -= ws.Xi.transpose() * s.small;
    return q.allFinite() && qd.allFinite() ? DynamicsStatus::ok : DynamicsStatus::non_finite;
  }
}

}  // namespace eomrt
