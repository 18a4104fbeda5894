#pragma once
/// \file
/// Fixed-step explicit Runge-Kutta integration driven by a Butcher tableau.
///
/// Notation: n is the state dimension (x = [q; qd] gives n = nq + nv), S the number of
/// stages of the tableau. The right-hand side is any callable
///   f(Scalar t, const Vector& x, Vector& dxdt)
/// that writes all n entries of dxdt (pre-sized; it must not resize it) and returns void, or
/// bool with false for "could not evaluate" (see rhs.hpp).
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "eomrt/rhs.hpp"
#include "eomrt/tableau.hpp"

namespace eomrt {

/// Scratch of one explicit RK step, built once per integration so the step itself never
/// allocates (fixed-size vectors live inline; dynamic ones are sized here, never in the step).
/// \tparam Vector  Eigen column vector type of the state, fixed or dynamic size
/// \tparam S       number of stages of the tableau it serves
template <typename Vector, std::size_t S>
struct RkWorkspace {
  static_assert(Vector::ColsAtCompileTime == 1, "RkWorkspace: the state must be a column vector");

  /// \param[in] n  state dimension; must equal the compile-time size of a fixed-size Vector
  /// @throws std::invalid_argument if n is negative or differs from a fixed size
  explicit RkWorkspace(Eigen::Index n) {
    constexpr Eigen::Index fixed = Vector::RowsAtCompileTime;
    if (n < 0 || (fixed != Eigen::Dynamic && n != fixed)) {
      std::ostringstream msg;
      msg << "RkWorkspace: state dimension expected "
          << (fixed == Eigen::Dynamic ? std::string(">= 0") : std::to_string(fixed)) << ", got "
          << n;
      throw std::invalid_argument(msg.str());
    }
    // setZero instead of a size constructor: for 1x1 fixed vectors an integer argument
    // would be taken as the coefficient, not the size
    for (Vector& ki : k) ki.setZero(n);
    x_stage.setZero(n);
  }

  /// stage derivatives k_i (S vectors of dim n); after rk_step they hold the stages of the
  /// step just taken, which is what an embedded error estimate h sum (b_i - b_hat_i) k_i needs
  std::array<Vector, S> k;
  /// state at which the current stage is evaluated, x + h sum_{j<i} a_ij k_j (dim n)
  Vector x_stage;
};

/// One explicit Runge-Kutta step of size h from (t, x), in place.
/// \param[in]     tableau  method; only the strictly lower triangle of a is read
/// \param[in]     f        right-hand side f(t, x, dxdt), evaluated S times
/// \param[in]     t        time at the start of the step
/// \param[in,out] x        state (dim n); on return, the state at t + h, or unchanged if a
///                         stage failed
/// \param[in]     h        step size (may be negative to integrate backwards)
/// \param[in,out] ws       scratch sized for n; on return ws.k holds the S stage derivatives
///                         (up to the failed stage, if one failed)
/// \return false if f reported that it could not evaluate a stage; later stages are skipped
template <std::size_t S, typename Vector, typename Rhs>
bool rk_step(const ButcherTableau<S>& tableau, Rhs&& f, typename Vector::Scalar t, Vector& x,
             typename Vector::Scalar h, RkWorkspace<Vector, S>& ws) {
  using Scalar = typename Vector::Scalar;
  const Vector& x_stage = ws.x_stage;

  for (std::size_t i = 0; i < S; ++i) {
    // stage state; zero couplings are skipped, they are common (RK4 has 3 of 6)
    ws.x_stage = x;
    for (std::size_t j = 0; j < i; ++j)
      if (tableau.a[i][j] != 0) ws.x_stage += (h * static_cast<Scalar>(tableau.a[i][j])) * ws.k[j];
    if (!evaluate_rhs(f, t + static_cast<Scalar>(tableau.c[i]) * h, x_stage, ws.k[i])) return false;
  }

  // x_next = x + h sum b_i k_i, accumulated into x so that no temporary vector is needed
  for (std::size_t i = 0; i < S; ++i)
    if (tableau.b[i] != 0) x += (h * static_cast<Scalar>(tableau.b[i])) * ws.k[i];
  return true;
}

/// Outcome of an integration (ComputationInfo style: reported, never thrown from the loop).
enum class IntegrateStatus {
  ok,          ///< reached t_end
  non_finite,  ///< a step produced a NaN or infinite state entry; integration stopped
  rhs_failed,  ///< the right-hand side reported that it could not evaluate; integration stopped
};

/// \return the enumerator's name, for messages and logs
inline const char* to_string(IntegrateStatus status) {
  switch (status) {
    case IntegrateStatus::ok:
      return "ok";
    case IntegrateStatus::non_finite:
      return "non_finite";
    case IntegrateStatus::rhs_failed:
      return "rhs_failed";
  }
  return "unknown";
}

/// Where an integration ended.
template <typename Vector>
struct IntegrateResult {
  /// ok, or why the integration stopped early
  IntegrateStatus status;
  /// ok: exactly t_end. non_finite: the end time of the first step whose result is not
  /// finite (or t0 if x0 itself is not finite). rhs_failed: the start time of the step in
  /// which f failed
  typename Vector::Scalar t;
  /// state at t (dim n); for non_finite it is kept as computed, so its NaN/Inf entries
  /// show which coordinates diverged (the observer has already seen the last finite state);
  /// for rhs_failed it is the last state the observer saw (or x0)
  Vector x;
};

/// Observer that ignores every state: the default of integrate_fixed.
struct NoObserver {
  template <typename Scalar, typename Vector>
  void operator()(const Scalar& /*t*/, const Vector& /*x*/) const noexcept {}
};

/// Integrates x' = f(t, x) from (t0, x0) to t_end with steps of size h; the last step is
/// shortened so that the integration ends exactly on t_end (a step count within rounding of
/// an integer takes whole steps only, leaving no sliver step). Step k ends at t0 + (k+1) h,
/// computed directly rather than accumulated, so the times do not drift.
/// \param[in] tableau   method
/// \param[in] f         right-hand side f(t, x, dxdt), returning void or bool (see rhs.hpp)
/// \param[in] t0        initial time
/// \param[in] x0        initial state (dim n)
/// \param[in] t_end     final time, t_end >= t0
/// \param[in] h         nominal step size, h > 0
/// \param[in] observer  called as observer(t, x) after each step with a finite state
/// \return status, final time and final state; see IntegrateResult
/// @throws std::invalid_argument if h is not positive and finite
/// @throws std::invalid_argument if t0 or t_end is not finite, or t_end < t0
/// @throws std::invalid_argument if (t_end - t0) / h steps would overflow the step counter
template <std::size_t S, typename Vector, typename Rhs, typename Observer = NoObserver>
IntegrateResult<Vector> integrate_fixed(const ButcherTableau<S>& tableau, Rhs&& f,
                                        typename Vector::Scalar t0, const Vector& x0,
                                        typename Vector::Scalar t_end, typename Vector::Scalar h,
                                        Observer&& observer = Observer{}) {
  using Scalar = typename Vector::Scalar;
  using std::abs;
  using std::ceil;
  using std::isfinite;
  using std::round;

  // misuse is reported before the loop; inside it only statuses are returned
  if (!isfinite(h) || !(h > 0)) {
    std::ostringstream msg;
    msg << "integrate_fixed: step h expected positive and finite, got " << h;
    throw std::invalid_argument(msg.str());
  }
  if (!isfinite(t0) || !isfinite(t_end) || t_end < t0) {
    std::ostringstream msg;
    msg << "integrate_fixed: time span expected finite with t_end >= t0, got [" << t0 << ", "
        << t_end << "]";
    throw std::invalid_argument(msg.str());
  }

  // a ratio such as 2 / 0.1 = 19.999... counts as 20 steps, not 20 plus a sliver of 1e-16 h
  const Scalar ratio = (t_end - t0) / h;
  const Scalar nearest = round(ratio);
  const Scalar slack = 8 * std::numeric_limits<Scalar>::epsilon() * (ratio > 1 ? ratio : Scalar(1));
  const Scalar steps_real = abs(ratio - nearest) <= slack ? nearest : ceil(ratio);
  if (!(steps_real < static_cast<Scalar>(std::numeric_limits<long long>::max() / 2))) {
    std::ostringstream msg;
    msg << "integrate_fixed: step count (t_end - t0) / h too large, got " << ratio;
    throw std::invalid_argument(msg.str());
  }
  const long long steps = static_cast<long long>(steps_real);

  IntegrateResult<Vector> result{IntegrateStatus::ok, t0, x0};
  if (!result.x.allFinite()) {
    result.status = IntegrateStatus::non_finite;
    return result;
  }

  RkWorkspace<Vector, S> ws(x0.size());
  const Vector& x = result.x;
  for (long long k = 0; k < steps; ++k) {
    // the last step ends on t_end exactly, whatever rounding t0 + steps h would give
    const Scalar t_next = (k + 1 == steps) ? t_end : t0 + static_cast<Scalar>(k + 1) * h;
    // a failed stage leaves result.x at the start of the step, where the caller can inspect it
    if (!rk_step(tableau, f, result.t, result.x, t_next - result.t, ws)) {
      result.status = IntegrateStatus::rhs_failed;
      return result;
    }
    result.t = t_next;
    if (!result.x.allFinite()) {
      result.status = IntegrateStatus::non_finite;
      return result;
    }
    observer(result.t, x);
  }
  return result;
}

}  // namespace eomrt
