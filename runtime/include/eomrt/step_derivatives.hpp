#pragma once
/// \file
/// Exact derivatives of one fixed step of an explicit Runge-Kutta method (the runtime's `euler`
/// and `rk4` tableaus, or any other explicit one) on the state the runtime integrates,
/// x = [q; qd]: the discrete-time model x_next = Step(t, x, u) that iLQR/DDP and multiple
/// shooting consume, with
///   Phi = dx_next/dx (2 nq x 2 nq),   Gamma = dx_next/du (2 nq x nu).
///
/// The input is held over the step (zero-order hold). The right-hand side is the model's forward
/// dynamics f(t, x, u) = [qd; qdd] (for a constrained model the KKT accelerations, without
/// Baumgarte terms or projection: the step of rk_step with that f). The chain rule through the
/// stages, with A_i, B_i = df/dx, df/du at stage i (eomrt::linearization, from the generated
/// linearization_terms):
///   X_i = x + h sum_{j<i} a_ij k_j,       k_i = f(t + c_i h, X_i, u),
///   dX_i/dx = I + h sum_{j<i} a_ij dk_j/dx,   dk_i/dx = A_i dX_i/dx,
///   dX_i/du =     h sum_{j<i} a_ij dk_j/du,   dk_i/du = A_i dX_i/du + B_i,
///   x_next = x + h sum_i b_i k_i,   Phi = I + h sum_i b_i dk_i/dx,   Gamma = h sum_i b_i dk_i/du.
/// A_i = [[0, I], [A_q, A_qd]] is used by its blocks: its top half only copies rows.
/// Everything is fixed-size: nothing allocates.
#include <array>
#include <cstddef>

#include "eomrt/linearization.hpp"
#include "eomrt/tableau.hpp"

namespace eomrt {

/// Scratch and results of step_derivatives for one model and an S-stage tableau.
template <class Model, std::size_t S, class Scalar = double>
struct StepDerivativesWorkspace {
  static constexpr int nq = Model::nq;
  static constexpr int nu = Model::nu;
  using State = Eigen::Matrix<Scalar, 2 * nq, 1>;

  LinearizationWorkspace<Model, Scalar> stage;      ///< the linearization at the current stage
  std::array<State, S> k;                           ///< stage derivatives k_i
  std::array<StateMatrix<Scalar, nq>, S> dk_dx;     ///< dk_i/dx
  std::array<StateInputMatrix<Scalar, nq, nu>, S> dk_du;  ///< dk_i/du
  State x_stage;                                    ///< X_i
  StateMatrix<Scalar, nq> dX_dx;                    ///< dX_i/dx
  StateInputMatrix<Scalar, nq, nu> dX_du;           ///< dX_i/du
  State x_next;                                     ///< result: the state after the step
  StateMatrix<Scalar, nq> Phi;                      ///< result: dx_next/dx
  StateInputMatrix<Scalar, nq, nu> Gamma;           ///< result: dx_next/du
};

/// One explicit Runge-Kutta step from (t, x) with u held, and its derivatives (file comment).
/// \param[in]  tableau  an explicit method (eomrt::euler, eomrt::rk4); only the strictly lower
///                      triangle of a is read
/// \param[in]  p        parameters, or their Constants (model_traits.hpp)
/// \param[out] ws       ws.x_next, ws.Phi and ws.Gamma receive the result
/// \param[in]  t        time at the start of the step
/// \param[in]  h        step size
/// \param[in]  x        state [q; qd] (dim 2 nq)
/// \param[in]  u        inputs (dim nu), held over the step
/// \return ok, or the status of the first stage whose dynamics or linearization failed
///         (singular M or KKT matrix, non_finite); the results are then not meaningful
template <class Model, std::size_t S, class Scalar,
          class ParametersOrConstants = typename ModelTypes<Model, Scalar>::Parameters>
DynamicsStatus step_derivatives(const ButcherTableau<S>& tableau, const ParametersOrConstants& p,
                                StepDerivativesWorkspace<Model, S, Scalar>& ws, const Scalar& t, const Scalar& h,
                                const typename ModelTypes<Model, Scalar>::State& x,
                                const typename ModelTypes<Model, Scalar>::Inputs& u) noexcept {
  constexpr int nq = Model::nq;
  constexpr int nu = Model::nu;
  for (std::size_t i = 0; i < S; ++i) {
    ws.x_stage = x;
    // a stage at x itself (the first) has dX/dx = I and dX/du = 0: its dk is A and B as they are
    bool moved = false;
    for (std::size_t j = 0; j < i; ++j) {
      if (tableau.a[i][j] == 0) continue;
      if (!moved) {
        ws.dX_dx.setIdentity();
        ws.dX_du.setZero();
        moved = true;
      }
      const Scalar w = h * static_cast<Scalar>(tableau.a[i][j]);
      ws.x_stage += w * ws.k[j];
      ws.dX_dx += w * ws.dk_dx[j];
      if constexpr (nu > 0) ws.dX_du += w * ws.dk_du[j];
    }
    const typename ModelTypes<Model, Scalar>::Coordinates q = ws.x_stage.template head<nq>(),
                                                          qd = ws.x_stage.template tail<nq>();
    const DynamicsStatus status =
        linearization<Model>(p, ws.stage, t + static_cast<Scalar>(tableau.c[i]) * h, q, qd, u);
    if (status != DynamicsStatus::ok) return status;
    ws.k[i] << qd, ws.stage.dynamics.qdd;
    if (!moved) {
      ws.dk_dx[i] = ws.stage.A;
      if constexpr (nu > 0) ws.dk_du[i] = ws.stage.B;
      continue;
    }
    // dk_i = A_i dX_i: the top rows of A_i pick the rates' rows, the bottom ones are products
    const auto A_bottom = ws.stage.A.template bottomRows<nq>();
    ws.dk_dx[i].template topRows<nq>() = ws.dX_dx.template bottomRows<nq>();
    ws.dk_dx[i].template bottomRows<nq>().noalias() = A_bottom * ws.dX_dx;
    if constexpr (nu > 0) {
      ws.dk_du[i].template topRows<nq>() = ws.dX_du.template bottomRows<nq>();
      ws.dk_du[i].template bottomRows<nq>() = ws.stage.B.template bottomRows<nq>();
      ws.dk_du[i].template bottomRows<nq>().noalias() += A_bottom * ws.dX_du;
    }
  }
  ws.x_next = x;
  ws.Phi.setIdentity();
  ws.Gamma.setZero();
  for (std::size_t i = 0; i < S; ++i) {
    if (tableau.b[i] == 0) continue;
    const Scalar w = h * static_cast<Scalar>(tableau.b[i]);
    ws.x_next += w * ws.k[i];
    ws.Phi += w * ws.dk_dx[i];
    if constexpr (nu > 0) ws.Gamma += w * ws.dk_du[i];
  }
  return ws.x_next.allFinite() && ws.Phi.allFinite() && ws.Gamma.allFinite() ? DynamicsStatus::ok
                                                                              : DynamicsStatus::non_finite;
}

}  // namespace eomrt
