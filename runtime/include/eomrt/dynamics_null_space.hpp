#pragma once
/// \file
/// Forward dynamics by the null-space method (notes, section 5.6.2): with Upsilon a basis of
/// the null space of Xi (Xi Upsilon = 0) and qdd_p any solution of Xi qdd_p = r,
///   qdd = qdd_p + Upsilon w,   (Upsilon^T M Upsilon) w = Upsilon^T (F - M qdd_p),
/// which needs M positive definite only on the constraint (a quaternion's singular M is fine).
/// The multipliers follow afterwards from Xi^T lambda = M qdd - F.
///
/// Upsilon comes either from a QR decomposition of Xi^T (orthonormal, always available) or from
/// independent speeds the model declares: Xi = [Xi_d  Xi_i] over dependent and independent
/// rates gives Upsilon = [-Xi_d^{-1} Xi_i; 1], the textbook choice, singular where Xi_d is
/// (the knife edge's y_dot = tan(theta) x_dot at theta = pi/2). qdd and lambda do not depend on
/// the basis, so where the declared one degenerates (an entry of Upsilon beyond
/// max_declared_basis_gain) the QR basis is used for that evaluation instead of failing.
#include <array>
#include <sstream>
#include <stdexcept>

#include "eomrt/dynamics_unconstrained.hpp"

namespace eomrt {

/// Largest |entry| of the declared basis's dependent rows, -Xi_d^{-1} Xi_i, accepted before
/// the QR basis takes over: beyond it the reduced mass matrix would lose about twice as many
/// digits (its condition grows with the square of the gain).
template <class Scalar>
inline constexpr Scalar max_declared_basis_gain = Scalar(1000);

/// A split of the rates into nq - nc independent and nc dependent ones, checked once at setup.
template <class Model>
struct SpeedPartition {
  static constexpr int nq = Model::nq;
  static constexpr int nc = Model::nc;
  std::array<int, nq - nc> independent{};  ///< coordinate indices of the independent speeds
  std::array<int, nc> dependent{};         ///< the remaining indices, increasing

  /// \param[in] independent_indices  nq - nc distinct coordinate indices in [0, nq)
  /// @throws std::invalid_argument if an index is out of range or repeated
  explicit SpeedPartition(const std::array<int, nq - nc>& independent_indices)
      : independent(independent_indices) {
    std::array<bool, nq> is_independent{};
    for (int i : independent) {
      if (i < 0 || i >= nq || is_independent[i]) {
        std::ostringstream msg;
        msg << "SpeedPartition: independent speeds expected distinct indices in [0, " << nq
            << "), got " << i << (i >= 0 && i < nq ? " twice" : "");
        throw std::invalid_argument(msg.str());
      }
      is_independent[i] = true;
    }
    int k = 0;
    for (int i = 0; i < nq; ++i)
      if (!is_independent[i]) dependent[k++] = i;
  }
};

/// The partition a model declares (its independent_speeds), for models that have one.
template <class Model>
SpeedPartition<Model> declared_speed_partition() {
  static_assert(has_independent_speeds_v<Model>, "the model declares no independent speeds");
  static_assert(Model::ni == Model::nq - Model::nc, "ni must equal nq - nc");
  std::array<int, Model::nq - Model::nc> indices{};
  for (int i = 0; i < Model::ni; ++i) indices[i] = Model::independent_speeds[i];
  return SpeedPartition<Model>(indices);
}

/// Accelerations and multipliers by the null-space method; same results as forward_dynamics_kkt
/// wherever both are regular.
/// \param[in]  p          parameters, or their Constants (model_traits.hpp) to evaluate repeatedly
/// \param[out] ws         workspace; ws.qdd (dim nq) and ws.lambda (dim nc) receive the result,
///                        ws.solvers.upsilon the basis used (nq x (nq - nc)), and
///                        ws.declared_basis_used whether it was the partition's
/// \param[in]  t          time
/// \param[in]  q, qd      coordinates and rates (dim nq)
/// \param[in]  u          inputs (dim nu)
/// \param[in]  stab       Baumgarte stabilization (default: none)
/// \param[in]  partition  independent speeds defining Upsilon; nullptr: QR of Xi^T
/// \return ok; non_finite if a term or the result is not finite; singular_constraint_jacobian
///         if Xi lost rank; singular_mass_matrix if Upsilon^T M Upsilon (or, for an
///         unconstrained model, M) is not positive definite
template <class Model, class Scalar,
          class ParametersOrConstants = typename ModelTypes<Model, Scalar>::Parameters>
DynamicsStatus forward_dynamics_null_space(
    const ParametersOrConstants& p, DynamicsWorkspace<Model, Scalar>& ws,
    const Scalar& t, const typename ModelTypes<Model, Scalar>::Coordinates& q,
    const typename ModelTypes<Model, Scalar>::Coordinates& qd,
    const typename ModelTypes<Model, Scalar>::Inputs& u, const Baumgarte<Scalar>& stab = {},
    const SpeedPartition<Model>* partition = nullptr) {
  static_assert(is_parameter_argument_v<Model, Scalar, ParametersOrConstants>,
                "eomrt: p must be the model's Parameters or its Constants");
  const DynamicsStatus status = evaluate_dynamics_terms(p, ws, t, q, qd, u, stab);
  if (status != DynamicsStatus::ok) return status;
  if constexpr (Model::nc == 0) {
    return detail::solve_mass_matrix(ws);
  } else {
    constexpr int nq = Model::nq;
    constexpr int nc = Model::nc;
    auto& s = ws.solvers;
    bool declared = partition != nullptr;
    if (declared) {
      for (int i = 0; i < nc; ++i) s.dependent_block.col(i) = ws.Xi.col(partition->dependent[i]);
      s.dependent_lu.compute(s.dependent_block);
      s.upsilon.setZero();
      for (int j = 0; j < nq - nc && declared; ++j) {
        s.upsilon(partition->independent[j], j) = 1;
        s.small = -s.dependent_lu.solve(ws.Xi.col(partition->independent[j]));
        // a 1x1 block has rcond 1 however small it is: the gain into the dependent speeds is
        // the measure that sees it (and NaN from an exactly singular block fails it too)
        declared = s.small.cwiseAbs().maxCoeff() <= max_declared_basis_gain<Scalar>;
        for (int i = 0; i < nc; ++i) s.upsilon(partition->dependent[i], j) = s.small(i);
      }
    }
    if (declared) {
      s.particular.setZero();
      s.small = s.dependent_lu.solve(ws.constraint_rhs);
      for (int i = 0; i < nc; ++i) s.particular(partition->dependent[i]) = s.small(i);
    } else {
      // Xi^T P = Q R with Q = [Q1 Q2]: Q2 spans the null space of Xi, and Xi = P R^T Q1^T
      s.qr.compute(ws.Xi.transpose());
      const auto R = s.qr.matrixR().template topLeftCorner<nc, nc>();
      const Scalar r_max = R.diagonal().cwiseAbs().maxCoeff();
      if (!(r_max > 0) || !(R.diagonal().cwiseAbs().minCoeff() > ws.singular_rcond * r_max))
        return DynamicsStatus::singular_constraint_jacobian;
      s.q_full = s.qr.householderQ();
      s.upsilon = s.q_full.template rightCols<nq - nc>();
      // particular solution qdd_p = Q1 y with R^T y = P^T r
      s.small = s.qr.colsPermutation().transpose() * ws.constraint_rhs;
      R.template triangularView<Eigen::Upper>().transpose().solveInPlace(s.small);
      s.particular.noalias() = s.q_full.template leftCols<nc>() * s.small;
    }
    ws.declared_basis_used = declared;
    s.reduced_mass.noalias() = s.upsilon.transpose() * ws.M * s.upsilon;
    s.reduced_llt.compute(s.reduced_mass);
    if (!cholesky_is_regular(s.reduced_llt, ws.singular_rcond))
      return DynamicsStatus::singular_mass_matrix;
    ws.qdd = ws.F;
    ws.qdd.noalias() -= ws.M * s.particular;
    s.reduced_rhs.noalias() = s.upsilon.transpose() * ws.qdd;
    s.reduced_llt.solveInPlace(s.reduced_rhs);
    ws.qdd = s.particular;
    ws.qdd.noalias() += s.upsilon * s.reduced_rhs;

    // Xi^T lambda = M qdd - F, solved on the rows that determine lambda
    s.particular = ws.F;
    s.particular.noalias() -= ws.M * ws.qdd;
    s.particular = -s.particular;  // now M qdd - F
    if (!declared) {
      // lambda = P R^{-1} Q1^T (M qdd - F)
      s.small.noalias() = s.q_full.template leftCols<nc>().transpose() * s.particular;
      s.qr.matrixR().template topLeftCorner<nc, nc>().template triangularView<Eigen::Upper>().solveInPlace(
          s.small);
      ws.lambda = s.qr.colsPermutation() * s.small;
    } else {
      // Xi_d^T lambda = (M qdd - F)_d
      for (int i = 0; i < nc; ++i) s.small(i) = s.particular(partition->dependent[i]);
      ws.lambda = s.dependent_lu.transpose().solve(s.small);
    }
    return ws.qdd.allFinite() && ws.lambda.allFinite() ? DynamicsStatus::ok
                                                      : DynamicsStatus::non_finite;
  }
}

}  // namespace eomrt
