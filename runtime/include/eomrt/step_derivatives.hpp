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
namespace detail {

// out += a x, column by column: each column of the result a combination of a's columns, which
// are contiguous where a is rows of a column-major matrix (A's bottom rows). For the small
// fixed sizes of a step's stages this is faster than Eigen's product, which takes its blocked
// kernel there: in a micro-benchmark on g++ -O2 (Eigen 3.4) the products of an RK4 step's
// three later stages took 1.5 us against 2.3 with 6 coordinates and inputs, 2.0 against 3.1
// with 7, 14.6 against 18.0 with 16 (minima of 31 rounds).
template <class Scalar, int rows, class A, class X, class Out>
void add_product_by_columns(const Eigen::MatrixBase<A>& a, const Eigen::MatrixBase<X>& x,
                            Eigen::MatrixBase<Out>& out) noexcept {
  for (Eigen::Index c = 0; c < x.cols(); ++c) {
    Eigen::Matrix<Scalar, rows, 1> column = out.col(c);
    for (Eigen::Index k = 0; k < x.rows(); ++k) column += a.col(k) * x(k, c);
    out.col(c) = column;
  }
}

}  // namespace detail

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
    auto dk_dx_bottom = ws.dk_dx[i].template bottomRows<nq>();
    dk_dx_bottom.setZero();
    detail::add_product_by_columns<Scalar, nq>(A_bottom, ws.dX_dx, dk_dx_bottom);
    if constexpr (nu > 0) {
      ws.dk_du[i].template topRows<nq>() = ws.dX_du.template bottomRows<nq>();
      auto dk_du_bottom = ws.dk_du[i].template bottomRows<nq>();
      dk_du_bottom = ws.stage.B.template bottomRows<nq>();
      detail::add_product_by_columns<Scalar, nq>(A_bottom, ws.dX_du, dk_du_bottom);
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
