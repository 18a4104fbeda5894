#pragma once
/// \file
/// DynamicsWorkspace: all per-evaluation data of a model's forward dynamics (M, F, Xi, the
/// factorizations, qdd, lambda), built once so that a solve never allocates.
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/LU>
#include <Eigen/QR>

#include "eomrt/kkt_system.hpp"
#include "eomrt/lu_factorization.hpp"
#include "eomrt/pivoted_qr.hpp"
#include "eomrt/model_traits.hpp"
#include "eomrt/regularity.hpp"
#include "eomrt/status.hpp"

namespace eomrt {

/// Constraint stabilization terms added at acceleration level (Baumgarte):
///   Xi qdd + b + 2 alpha (Xi qd + Xi_t) + beta^2 phi = 0,
/// phi entering only the holonomic rows. alpha = beta = 0 is the plain constraint.
template <class Scalar>
struct Baumgarte {
  Scalar alpha = 0;  ///< [1/s] damping of the velocity-level residual
  Scalar beta = 0;   ///< [1/s] natural frequency pulling phi back to zero
};

namespace detail {

/// Factorizations only a constrained model needs; empty for nc = 0, where Eigen's fixed-size
/// decompositions of zero-sized matrices do not compile.
template <class Scalar, int nq, int nc>
struct ConstraintSolvers {
  static constexpr int nk = nq + nc;
  static constexpr int nr = nq - nc;
  KktSystem<Scalar, nq, nc> kkt;                                 ///< [[M, -Xi^T], [-Xi, 0]], factorized
  Eigen::Matrix<Scalar, nk, 1> kkt_rhs;                          ///< [F; -r], then [qdd; lambda]
  Eigen::ColPivHouseholderQR<Eigen::Matrix<Scalar, nq, nc>> qr;  ///< of Xi^T = Q R P^T
  Eigen::Matrix<Scalar, nq, nq> q_full;                          ///< Q of the QR
  Eigen::Matrix<Scalar, nq, nr> upsilon;                         ///< Xi Upsilon = 0
  Eigen::Matrix<Scalar, nr, nr> reduced_mass;                    ///< Upsilon^T M Upsilon
  Eigen::LLT<Eigen::Matrix<Scalar, nr, nr>> reduced_llt;         ///< of reduced_mass
  Eigen::Matrix<Scalar, nc, nc> dependent_block;                 ///< Xi restricted to dependent speeds
  Eigen::PartialPivLU<Eigen::Matrix<Scalar, nc, nc>> dependent_lu;
  Eigen::Matrix<Scalar, nc, nc> gram;                            ///< Xi Xi^T (projection)
  LuFactorization<Scalar, nc> gram_lu;                           ///< of gram
  PivotedQr<Scalar, nq, nc> rows_qr;  ///< of Xi^T, for the rows the projection leaves out
  Eigen::Matrix<Scalar, nq, 1> particular;                       ///< qdd_p with Xi qdd_p = r
  Eigen::Matrix<Scalar, nr, 1> reduced_rhs;                      ///< Upsilon^T (F - M qdd_p)
  Eigen::Matrix<Scalar, nc, 1> small;                            ///< scratch of dim nc
  /// rows of Xi the projection left out as dependent at the state (redundant constraints)
  Eigen::Array<bool, nc, 1> dependent_rows = Eigen::Array<bool, nc, 1>::Constant(false);
};

template <class Scalar, int nq>
struct ConstraintSolvers<Scalar, nq, 0> {};

}  // namespace detail

/// Scratch and results of the forward dynamics of one model, for one scalar type. All members
/// are fixed-size: constructing it is the only allocation-free "allocation" there is, and every
/// algorithm taking it runs without touching the heap.
template <class Model, class Scalar = double>
struct DynamicsWorkspace {
  static_assert(check_model<Model, Scalar>());
  using Types = ModelTypes<Model, Scalar>;
  static constexpr int nq = Model::nq;
  static constexpr int nc = Model::nc;
  static constexpr int nh = Model::nh;

  typename Types::MassMatrix M;                     ///< M(q, t) (nq x nq)
  typename Types::Coordinates F;                    ///< F(q, qd, t, u) (dim nq)
  typename Types::ConstraintJacobian Xi;            ///< Xi(q, t) (nc x nq)
  typename Types::ConstraintVector Xi_t;            ///< Xi_t(q, t) (dim nc)
  typename Types::ConstraintVector b;               ///< dXi/dt qd + dXi_t/dt (dim nc)
  typename Types::ConstraintVector velocity_residual;  ///< Xi qd + Xi_t (dim nc)
  typename Types::HolonomicVector phi;              ///< phi(q, t) (dim nh)
  /// right side r of the acceleration-level constraints Xi qdd = r (dim nc); with Baumgarte
  /// r = -(b + 2 alpha (Xi qd + Xi_t) + beta^2 phi)
  typename Types::ConstraintVector constraint_rhs;
  typename Types::Coordinates qdd;                  ///< result: accelerations (dim nq)
  typename Types::ConstraintVector lambda;          ///< result: multipliers (dim nc)
  /// whether the last null-space solve used the declared independent speeds (else QR)
  bool declared_basis_used = false;
  Eigen::LLT<typename Types::MassMatrix> mass_llt;  ///< Cholesky of M (unconstrained models)
  detail::ConstraintSolvers<Scalar, nq, nc> solvers;

  /// Reciprocal condition number below which a factorization counts as singular (see
  /// default_singular_rcond). Cholesky factorizations of mass matrices compare it with their
  /// pivot ratio (cholesky_is_regular), the KKT matrix and the Gram matrix Xi Xi^T with
  /// the estimated reciprocal condition number of their LU (LuFactorization::is_regular), the QR of Xi^T with the ratio of its diagonal.
  Scalar singular_rcond = default_singular_rcond<Scalar>();

  DynamicsWorkspace() {
    M.setZero();
    F.setZero();
    Xi.setZero();
    Xi_t.setZero();
    b.setZero();
    velocity_residual.setZero();
    phi.setZero();
    constraint_rhs.setZero();
    qdd.setZero();
    lambda.setZero();
  }
};

/// Evaluates the model's terms at (t, q, qd, u): M, F, and for a constrained model Xi, Xi_t, b,
/// phi, the residual Xi qd + Xi_t and the stabilized right side r of Xi qdd = r.
/// \param[in]  p      parameters, or their Constants (model_traits.hpp) to evaluate repeatedly
/// \param[out] ws     ws.M, ws.F, ws.Xi, ws.Xi_t, ws.b, ws.phi, ws.velocity_residual,
///                    ws.constraint_rhs
/// \param[in]  t      time
/// \param[in]  q, qd  coordinates and rates (dim nq)
/// \param[in]  u      inputs (dim nu)
/// \param[in]  stab   Baumgarte terms (zero: none)
/// \return ok, or non_finite if any evaluated entry is NaN or infinite
template <class Model, class Scalar,
          class ParametersOrConstants = typename ModelTypes<Model, Scalar>::Parameters>
DynamicsStatus evaluate_dynamics_terms(const ParametersOrConstants& p,
                                       DynamicsWorkspace<Model, Scalar>& ws, const Scalar& t,
                                       const typename ModelTypes<Model, Scalar>::Coordinates& q,
                                       const typename ModelTypes<Model, Scalar>::Coordinates& qd,
                                       const typename ModelTypes<Model, Scalar>::Inputs& u,
                                       const Baumgarte<Scalar>& stab) {
  static_assert(is_parameter_argument_v<Model, Scalar, ParametersOrConstants>,
                "eomrt: p must be the model's Parameters or its Constants");
  Model::mass_matrix_and_forcing(t, q, qd, u, p, ws.M, ws.F);
  if (!ws.M.allFinite() || !ws.F.allFinite()) return DynamicsStatus::non_finite;
  if constexpr (Model::nc > 0) {
    Model::constraint_jacobian(t, q, p, ws.Xi);
    Model::constraint_rate_term(t, q, p, ws.Xi_t);
    Model::constraint_acceleration_term(t, q, qd, p, ws.b);
    ws.velocity_residual.noalias() = ws.Xi * qd;
    ws.velocity_residual += ws.Xi_t;
    ws.constraint_rhs = -ws.b;
    if (stab.alpha != 0) ws.constraint_rhs -= (2 * stab.alpha) * ws.velocity_residual;
    if constexpr (Model::nh > 0) {
      Model::holonomic_residuals(t, q, p, ws.phi);
      if (stab.beta != 0)
        for (int i = 0; i < Model::nh; ++i)
          ws.constraint_rhs(Model::holonomic_rows[i]) -= stab.beta * stab.beta * ws.phi(i);
    }
    if (!ws.Xi.allFinite() || !ws.constraint_rhs.allFinite()) return DynamicsStatus::non_finite;
  }
  return DynamicsStatus::ok;
}

}  // namespace eomrt
