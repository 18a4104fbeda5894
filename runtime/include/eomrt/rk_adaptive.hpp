#pragma once
/// \file
/// Adaptive explicit Runge-Kutta integration with an embedded pair (tableau.hpp): error
/// control, step rejection and dense output, after E. Hairer, S. P. Norsett, G. Wanner, Solving
/// Ordinary Differential Equations I, 2nd ed., sec. II.4 (error norm, step-size control,
/// starting step) and II.6 (continuous extension), and their code dopri5. The pair is a
/// parameter, so another FSAL pair is a tableau, not a copy of this file; dormand_prince54 is
/// the one simulate() registers (integrators.hpp).
///
/// Notation as in rk_fixed.hpp: n is the state dimension, S the number of stages of the pair,
/// f(t, x, dxdt) the right-hand side, returning void or bool (rhs.hpp). Integration runs
/// forward only (t_end >= t0). The algorithm is split so that a caller can act between steps
/// (project x onto a constraint manifold, sample the dense output, stop on an event):
///
///   AdaptiveWorkspace<Vector, S> ws(n);                             // the only allocation
///   AdaptiveStatus s = adaptive_start(pair, f, t0, x0, t_end, options, ws);
///   while (s == AdaptiveStatus::ok && ws.t < t_end) {
///     s = adaptive_step(pair, f, t_end, options, ws);               // [ws.t_previous, ws.t]
///     ...                                                           // dense_output(ws, t, x)
///   }
///
/// integrate_adaptive is that loop with output on a time grid.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "eomrt/rhs.hpp"
#include "eomrt/rk_fixed.hpp"
#include "eomrt/tableau.hpp"

namespace eomrt {

/// Tolerances and limits of an adaptive integration. Validated by adaptive_start and
/// integrate_adaptive; adaptive_step expects the options adaptive_start accepted.
template <typename Scalar>
struct AdaptiveOptions {
  /// relative tolerance, > 0
  Scalar rtol = Scalar(1e-8);
  /// absolute tolerance, >= 0; with 0, a component that is exactly 0 at both ends of a step
  /// must have a zero error estimate or the step is rejected
  Scalar atol = Scalar(1e-10);
  /// first step to try, >= 0; 0: chosen automatically (Hairer's starting-step heuristic)
  Scalar h_initial = 0;
  /// largest step, >= 0; 0: unlimited (in effect |t_end - t0|)
  Scalar h_max = 0;
  /// limit on step attempts, accepted plus rejected, since adaptive_start; > 0
  long long max_steps = 10000000;
};

/// Outcome of an adaptive step or integration (ComputationInfo style: reported, not thrown).
enum class AdaptiveStatus {
  ok,                   ///< step accepted (or nothing left to do)
  non_finite,           ///< the state or f is NaN/Inf and shrinking the step did not help
  step_size_underflow,  ///< the error test kept failing down to a step of ~10 ulp of |t|
  too_many_steps,       ///< options.max_steps attempts used up
  rhs_failed,           ///< the right-hand side reported that it could not evaluate
};

/// \return the enumerator's name, for messages and logs
inline const char* to_string(AdaptiveStatus status) {
  switch (status) {
    case AdaptiveStatus::ok:
      return "ok";
    case AdaptiveStatus::non_finite:
      return "non_finite";
    case AdaptiveStatus::step_size_underflow:
      return "step_size_underflow";
    case AdaptiveStatus::too_many_steps:
      return "too_many_steps";
    case AdaptiveStatus::rhs_failed:
      return "rhs_failed";
  }
  return "unknown";
}

/// State of an adaptive integration and the scratch of its steps. All memory is taken in the
/// constructor; adaptive_start, adaptive_step, adaptive_restart and dense_output never allocate
/// (given an x_out of dim n).
/// \tparam Vector  Eigen column vector type of the state, fixed or dynamic size
/// \tparam S       number of stages of the embedded pair it serves
template <typename Vector, std::size_t S>
struct AdaptiveWorkspace {
  static_assert(Vector::ColsAtCompileTime == 1,
                "AdaptiveWorkspace: the state must be a column vector");
  static_assert(S >= 2, "AdaptiveWorkspace: an embedded pair has at least two stages");
  using Scalar = typename Vector::Scalar;

  /// \param[in] n  state dimension; must equal the compile-time size of a fixed-size Vector
  /// @throws std::invalid_argument if n is negative or differs from a fixed size
  explicit AdaptiveWorkspace(Eigen::Index n) {
    constexpr Eigen::Index fixed = Vector::RowsAtCompileTime;
    if (n < 0 || (fixed != Eigen::Dynamic && n != fixed)) {
      std::ostringstream msg;
      msg << "AdaptiveWorkspace: state dimension expected "
          << (fixed == Eigen::Dynamic ? std::string(">= 0") : std::to_string(fixed)) << ", got "
          << n;
      throw std::invalid_argument(msg.str());
    }
    // setZero rather than a size constructor, which a 1x1 fixed vector reads as a coefficient
    x.setZero(n);
    x_previous.setZero(n);
    for (Vector& ki : k) ki.setZero(n);
    for (Vector& di : dense) di.setZero(n);
    x_stage.setZero(n);
    x_error.setZero(n);
  }

  /// time of x: the end of the last accepted step (t0 after adaptive_start)
  Scalar t = 0;
  /// start of the last accepted step (equal to t before the first step)
  Scalar t_previous = 0;
  /// next step size to try; adaptive_step may take less to land on t_end
  Scalar h = 0;
  /// state at t (dim n); the caller may change it between steps if it then calls
  /// adaptive_restart
  Vector x;
  /// state at t_previous (dim n)
  Vector x_previous;
  /// stage derivatives (S vectors of dim n). k[0] = f(t, x), the first stage of the next
  /// step (FSAL); k[1..S-1] are stages 2..S of the last attempt
  std::array<Vector, S> k;
  /// dense output of the last accepted step (5 vectors of dim n), as computed, unaffected by
  /// later changes of x: the end state x1, then D = x1 - x0, B = h k_1 - D, D - h k_S - B and
  /// h sum d_i k_i (see EmbeddedTableau::dense)
  std::array<Vector, 5> dense;
  /// state of the current stage; the trial state x1 after the last one (dim n)
  Vector x_stage;
  /// local error estimate h sum (b_i - b_hat_i) k_i of the last attempt (dim n)
  Vector x_error;
  /// step attempts since adaptive_start that passed (accepted) or failed (rejected) the error
  /// test
  long long accepted = 0, rejected = 0;
  /// calls of f since adaptive_start, including failed ones
  long long evaluations = 0;
};

namespace detail {

// controller constants of dopri5 (Hairer II.4, eq. (4.13) with fac = 0.9, facmin = 0.2,
// facmax = 10); a non-finite attempt says nothing about how much too large h was, so it is
// cut harder than any error-based rejection
inline constexpr Coefficient step_safety = 0.9L;
inline constexpr Coefficient step_factor_min = 0.2L;
inline constexpr Coefficient step_factor_max = 10;
inline constexpr Coefficient non_finite_step_factor = 0.1L;
// a step within 1% of the end is stretched to it rather than followed by a sliver (dopri5)
inline constexpr Coefficient landing_stretch = 1.01L;
// below ~10 ulp of |t| a step no longer moves t by more than rounding
inline constexpr Coefficient underflow_ulps = 10;

/// 1 / (q + 1) for an error estimator of order q: the local error it estimates scales like
/// h^(q + 1), so err^(-1/(q + 1)) is the step factor that would give err = 1 (1/5 for DOPRI5)
template <std::size_t S>
constexpr Coefficient error_exponent(const EmbeddedTableau<S>& pair) {
  return 1.0L / (pair.embedded_order + 1);
}

/// Hairer's error norm (eq. (4.11)): sqrt(1/n sum (e_i / (atol + rtol max(|x_i|, |y_i|)))^2).
/// A zero scale counts e_i = 0 as exact and any other e_i as infinitely large, not as NaN.
template <typename E, typename X, typename Y, typename Scalar>
Scalar error_norm(const Eigen::MatrixBase<E>& e, const Eigen::MatrixBase<X>& x,
                  const Eigen::MatrixBase<Y>& y, Scalar atol, Scalar rtol) {
  using std::abs;
  using std::sqrt;
  const Eigen::Index n = e.size();
  if (n == 0) return 0;
  Scalar sum = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (e(i) == 0) continue;
    const Scalar scale = atol + rtol * (abs(x(i)) > abs(y(i)) ? abs(x(i)) : abs(y(i)));
    const Scalar ratio = scale > 0 ? e(i) / scale : std::numeric_limits<Scalar>::infinity();
    sum += ratio * ratio;
  }
  return sqrt(sum / static_cast<Scalar>(n));
}

/// Misuse checks shared by adaptive_start and integrate_adaptive; \p operation starts the
/// message.
template <std::size_t S, typename Scalar>
void check_adaptive_arguments(const char* operation, const EmbeddedTableau<S>& pair, Scalar t0,
                              Scalar t_end, const AdaptiveOptions<Scalar>& options) {
  using std::isfinite;
  const auto fail = [operation](const char* what, const char* expected, auto got) {
    std::ostringstream msg;
    msg << operation << ": " << what << " expected " << expected << ", got " << got;
    throw std::invalid_argument(msg.str());
  };
  // the step reuses the last stage as the next first one and builds the dense output from it
  if (!is_consistent(pair) || !is_fsal(pair))
    throw std::invalid_argument(
        std::string(operation) +
        ": embedded pair expected consistent and FSAL (last row of a = b, c = 1)");
  if (!isfinite(options.rtol) || !(options.rtol > 0))
    fail("rtol", "positive and finite", options.rtol);
  if (!isfinite(options.atol) || !(options.atol >= 0))
    fail("atol", "non-negative and finite", options.atol);
  if (!isfinite(options.h_initial) || !(options.h_initial >= 0))
    fail("h_initial", "non-negative and finite", options.h_initial);
  if (!isfinite(options.h_max) || !(options.h_max >= 0))
    fail("h_max", "non-negative and finite", options.h_max);
  if (options.max_steps <= 0) fail("max_steps", "positive", options.max_steps);
  if (!isfinite(t0) || !isfinite(t_end) || t_end < t0) {
    std::ostringstream msg;
    msg << operation << ": time span expected finite with t_end >= t0, got [" << t0 << ", " << t_end
        << "]";
    throw std::invalid_argument(msg.str());
  }
}

/// Starting step of Hairer II.4 ("Starting Step Size"), with the RMS norm of error_norm:
/// h0 = 0.01 |x0| / |f0|, then an Euler step of h0 estimates the second derivative, and
/// h = min(100 h0, (0.01 / max(|f0|, |f1 - f0| / h0))^(1/(q+1))). Expects ws.k[0] = f(t0, x0);
/// costs one evaluation, which uses ws.k[1] and ws.x_stage as scratch.
/// \param[out] h  the step, limited by \p limit
/// \return ok, or rhs_failed if f failed at the Euler state
template <std::size_t S, typename Rhs, typename Vector>
AdaptiveStatus starting_step(const EmbeddedTableau<S>& pair, Rhs& f, typename Vector::Scalar limit,
                             const AdaptiveOptions<typename Vector::Scalar>& options,
                             AdaptiveWorkspace<Vector, S>& ws, typename Vector::Scalar& h) {
  using Scalar = typename Vector::Scalar;
  using std::pow;
  const Scalar atol = options.atol, rtol = options.rtol;
  const Scalar d0 = error_norm(ws.x, ws.x, ws.x, atol, rtol);
  const Scalar d1 = error_norm(ws.k[0], ws.x, ws.x, atol, rtol);
  // tiny norms give no usable ratio; Hairer's fallback
  Scalar h0 = (d0 < Scalar(1e-5L) || d1 < Scalar(1e-5L)) ? Scalar(1e-6L) : Scalar(0.01L) * d0 / d1;
  if (h0 > limit) h0 = limit;

  ws.x_stage = ws.x + h0 * ws.k[0];
  h = h0;
  // no curvature estimate past a non-finite Euler state; the controller shrinks h0 if needed
  if (!ws.x_stage.allFinite()) return AdaptiveStatus::ok;
  ++ws.evaluations;
  const Vector& x_euler = ws.x_stage;
  if (!evaluate_rhs(f, ws.t + h0, x_euler, ws.k[1])) return AdaptiveStatus::rhs_failed;
  if (!ws.k[1].allFinite()) return AdaptiveStatus::ok;

  const Scalar d2 = error_norm(ws.k[1] - ws.k[0], ws.x, ws.x, atol, rtol) / h0;
  const Scalar d_max = d1 > d2 ? d1 : d2;
  const Scalar h1 = d_max <= Scalar(1e-15L)
                        ? (h0 * Scalar(1e-3L) > Scalar(1e-6L) ? h0 * Scalar(1e-3L) : Scalar(1e-6L))
                        : pow(Scalar(0.01L) / d_max, static_cast<Scalar>(error_exponent(pair)));
  h = 100 * h0 < h1 ? 100 * h0 : h1;
  if (h > limit) h = limit;
  return AdaptiveStatus::ok;
}

/// Outcome of one attempt at a step: its stages ran (finite or not), or f failed.
enum class Attempt { finite, non_finite, rhs_failed };

/// Stages 2..S of a step of size h from (ws.t, ws.x) to t_new, and the error estimate into
/// ws.x_error; the last stage state is the trial state x1 (FSAL). f is never called at a
/// non-finite stage state: a state past overflow means h is far too large.
template <std::size_t S, typename Rhs, typename Vector>
Attempt attempt_step(const EmbeddedTableau<S>& pair, Rhs& f, typename Vector::Scalar t_new,
                     typename Vector::Scalar h, AdaptiveWorkspace<Vector, S>& ws) {
  using Scalar = typename Vector::Scalar;
  const auto scalar = [](Coefficient c) { return static_cast<Scalar>(c); };
  const Vector& x_stage = ws.x_stage;
  for (std::size_t i = 1; i < S; ++i) {
    ws.x_stage = ws.x;
    for (std::size_t j = 0; j < i; ++j)
      if (pair.a[i][j] != 0) ws.x_stage += (h * scalar(pair.a[i][j])) * ws.k[j];
    if (!ws.x_stage.allFinite()) return Attempt::non_finite;
    const Scalar t_stage = pair.c[i] == 1 ? t_new : ws.t + scalar(pair.c[i]) * h;
    ++ws.evaluations;
    if (!evaluate_rhs(f, t_stage, x_stage, ws.k[i])) return Attempt::rhs_failed;
  }
  // a non-finite k_i reaches a later stage state or this estimate, so one check covers all
  ws.x_error.setZero();
  for (std::size_t i = 0; i < S; ++i) {
    const Coefficient e = pair.b[i] - pair.b_hat[i];
    if (e != 0) ws.x_error += (h * scalar(e)) * ws.k[i];
  }
  return ws.x_error.allFinite() ? Attempt::finite : Attempt::non_finite;
}

/// Hairer's step factor min(10, max(0.2, 0.9 err^(-1/(q+1)))).
template <typename Scalar, std::size_t S>
Scalar step_factor(const EmbeddedTableau<S>& pair, Scalar err) {
  using std::pow;
  const auto scalar = [](Coefficient c) { return static_cast<Scalar>(c); };
  Scalar factor = err == 0 ? scalar(step_factor_max)
                           : scalar(step_safety) * pow(err, scalar(-error_exponent(pair)));
  if (factor < scalar(step_factor_min)) factor = scalar(step_factor_min);
  if (factor > scalar(step_factor_max)) factor = scalar(step_factor_max);
  return factor;
}

/// Accepts the attempt from (ws.t, ws.x) to (t_new, ws.x_stage): the dense output first, as
/// it needs the old state and the stages (dopri5's CONT), then the new state, whose
/// derivative k_S is the next first stage.
template <std::size_t S, typename Vector>
void accept_step(const EmbeddedTableau<S>& pair, typename Vector::Scalar t_new,
                 typename Vector::Scalar h, AdaptiveWorkspace<Vector, S>& ws) {
  using Scalar = typename Vector::Scalar;
  ws.dense[0] = ws.x_stage;
  ws.dense[1] = ws.x_stage - ws.x;
  ws.dense[2] = h * ws.k[0] - ws.dense[1];
  ws.dense[3] = ws.dense[1] - h * ws.k[S - 1] - ws.dense[2];
  ws.dense[4].setZero();
  for (std::size_t i = 0; i < S; ++i)
    if (pair.dense[i] != 0) ws.dense[4] += (h * static_cast<Scalar>(pair.dense[i])) * ws.k[i];

  ws.x_previous = ws.x;
  ws.x = ws.x_stage;
  ws.t_previous = ws.t;
  ws.t = t_new;
  ws.k[0] = ws.k[S - 1];
  ++ws.accepted;
}

// keeps a parameter out of template deduction, so adaptive_start takes x0 as any expression
// that converts to the workspace's Vector (std::type_identity is C++20)
template <typename T>
struct type_identity {
  using type = T;
};

}  // namespace detail

/// Starts an integration at (t0, x0): resets ws, evaluates the first stage f(t0, x0) and
/// chooses the first step (options.h_initial, or Hairer's heuristic when it is 0, at the cost
/// of one more evaluation). The dense output then returns x0 for every t.
/// \param[in]     pair     embedded pair, consistent and FSAL
/// \param[in]     f        right-hand side f(t, x, dxdt)
/// \param[in]     t0       initial time
/// \param[in]     x0       initial state (dim n)
/// \param[in]     t_end    final time, t_end >= t0; bounds the first step
/// \param[in]     options  tolerances and limits
/// \param[in,out] ws       workspace built for n; on return ws.t = t0, ws.x = x0, ws.h > 0
/// \return ok; non_finite if x0 or f(t0, x0) is not finite; rhs_failed if f failed
/// @throws std::invalid_argument if the pair is not consistent and FSAL, options are out of
///         range (see AdaptiveOptions), t0 or t_end is not finite, t_end < t0, or x0 is not
///         of dim n
template <std::size_t S, typename Rhs, typename Vector>
AdaptiveStatus adaptive_start(const EmbeddedTableau<S>& pair, Rhs&& f, typename Vector::Scalar t0,
                              const typename detail::type_identity<Vector>::type& x0,
                              typename Vector::Scalar t_end,
                              const AdaptiveOptions<typename Vector::Scalar>& options,
                              AdaptiveWorkspace<Vector, S>& ws) {
  using Scalar = typename Vector::Scalar;
  detail::check_adaptive_arguments("adaptive_start", pair, t0, t_end, options);
  if (x0.size() != ws.x.size()) {
    std::ostringstream msg;
    msg << "adaptive_start: initial state x0 of dim " << ws.x.size() << " expected, got "
        << x0.size();
    throw std::invalid_argument(msg.str());
  }

  ws.t = ws.t_previous = t0;
  ws.x = x0;
  ws.x_previous = x0;
  // a step of length zero whose dense output is the constant x0
  ws.dense[0] = x0;
  for (std::size_t i = 1; i < ws.dense.size(); ++i) ws.dense[i].setZero();
  ws.h = 0;
  ws.accepted = ws.rejected = ws.evaluations = 0;

  if (!ws.x.allFinite()) return AdaptiveStatus::non_finite;
  ++ws.evaluations;
  const Vector& x = ws.x;
  if (!evaluate_rhs(f, t0, x, ws.k[0])) return AdaptiveStatus::rhs_failed;
  if (!ws.k[0].allFinite()) return AdaptiveStatus::non_finite;

  // the first step never exceeds h_max or the span (unless the span is empty)
  Scalar limit = options.h_max > 0 ? options.h_max : t_end - t0;
  if (!(limit > 0)) limit = std::numeric_limits<Scalar>::max();
  if (options.h_initial > 0) {
    ws.h = options.h_initial < limit ? options.h_initial : limit;
    return AdaptiveStatus::ok;
  }
  return detail::starting_step(pair, f, limit, options, ws, ws.h);
}

/// Takes one accepted step from (ws.t, ws.x) towards t_end, retrying rejected attempts:
/// h_new = h min(10, max(0.2, 0.9 err^(-1/(q+1)))) with err the error_norm of the embedded
/// estimate and q the order of the estimator (the embedded order), no growth right after a
/// rejection, and h never beyond options.h_max. A step within 1% of t_end is taken to t_end
/// exactly; such a shortened last step keeps the controller's proposal in ws.h, so successive
/// end times do not shrink the step. A non-finite stage state, stage derivative or error
/// estimate counts as a rejection and cuts h by 10; f is never called at a non-finite state.
/// \param[in]     pair     the embedded pair adaptive_start was given
/// \param[in]     f        right-hand side f(t, x, dxdt)
/// \param[in]     t_end    time not to step past; if ws.t >= t_end nothing is done
/// \param[in]     options  the options adaptive_start accepted
/// \param[in,out] ws       started by adaptive_start; on ok, [ws.t_previous, ws.t] is the step
///                         just accepted, ws.x its end state, ws.k[0] = f(ws.t, ws.x), ws.h
///                         the next step to try and ws.dense its dense output
/// \return ok on an accepted step (or nothing to do). On any other status ws.t, ws.x, ws.k[0]
///         and the dense output still describe the last accepted state, and ws.h is the step
///         that failed. step_size_underflow: the error test failed down to a step of ~10 ulp
///         of |ws.t|. non_finite: the same, but the last attempts were non-finite, so f itself
///         is not finite near ws.t. too_many_steps: options.max_steps attempts since
///         adaptive_start. rhs_failed: f reported failure at a stage.
template <std::size_t S, typename Rhs, typename Vector>
AdaptiveStatus adaptive_step(const EmbeddedTableau<S>& pair, Rhs&& f, typename Vector::Scalar t_end,
                             const AdaptiveOptions<typename Vector::Scalar>& options,
                             AdaptiveWorkspace<Vector, S>& ws) {
  using Scalar = typename Vector::Scalar;
  using std::abs;
  if (!(ws.t < t_end)) return AdaptiveStatus::ok;
  // |t| is fixed during the call, so is the smallest step that still moves t
  const Scalar h_min = std::max(static_cast<Scalar>(detail::underflow_ulps) *
                                    std::numeric_limits<Scalar>::epsilon() * abs(ws.t),
                                std::numeric_limits<Scalar>::min());
  bool after_rejection = false, after_non_finite = false;

  for (;;) {
    if (ws.accepted + ws.rejected >= options.max_steps) return AdaptiveStatus::too_many_steps;
    const Scalar h_proposal = options.h_max > 0 && ws.h > options.h_max ? options.h_max : ws.h;
    if (!(h_proposal >= h_min))
      return after_non_finite ? AdaptiveStatus::non_finite : AdaptiveStatus::step_size_underflow;

    // the step is the difference of representable times, so t_new - t is exactly h
    const bool landing =
        ws.t + static_cast<Scalar>(detail::landing_stretch) * h_proposal >= t_end &&
        !(options.h_max > 0 && t_end - ws.t > options.h_max);
    const Scalar t_new = landing ? t_end : ws.t + h_proposal;
    const Scalar h = t_new - ws.t;

    const detail::Attempt attempt = detail::attempt_step(pair, f, t_new, h, ws);
    if (attempt == detail::Attempt::rhs_failed) return AdaptiveStatus::rhs_failed;
    if (attempt == detail::Attempt::non_finite) {
      ++ws.rejected;
      ws.h = h * static_cast<Scalar>(detail::non_finite_step_factor);
      after_rejection = after_non_finite = true;
      continue;
    }

    const Scalar err = detail::error_norm(ws.x_error, ws.x, ws.x_stage, options.atol, options.rtol);
    Scalar factor = detail::step_factor(pair, err);
    if (!(err <= 1)) {
      ++ws.rejected;
      ws.h = h * factor;
      after_rejection = true;
      after_non_finite = false;
      continue;
    }
    detail::accept_step(pair, t_new, h, ws);

    // a step that just succeeded after a failure is not trusted to grow (Hairer II.4)
    if (after_rejection && factor > 1) factor = 1;
    Scalar h_next = h * factor;
    if (landing && h_next < h_proposal) h_next = h_proposal;
    if (options.h_max > 0 && h_next > options.h_max) h_next = options.h_max;
    ws.h = h_next;
    return AdaptiveStatus::ok;
  }
}

/// Restarts after the caller changed ws.x in place (e.g. projected it onto the constraint
/// manifold): re-evaluates the first stage f(ws.t, ws.x) that the next step reuses. ws.t,
/// ws.h and the dense output of the last step (the trajectory before the change) are kept.
/// \param[in]     f   right-hand side f(t, x, dxdt)
/// \param[in,out] ws  workspace after adaptive_start or adaptive_step; on return
///                    ws.k[0] = f(ws.t, ws.x)
/// \return ok; non_finite if ws.x or f(ws.t, ws.x) is not finite; rhs_failed if f failed
template <typename Rhs, typename Vector, std::size_t S>
AdaptiveStatus adaptive_restart(Rhs&& f, AdaptiveWorkspace<Vector, S>& ws) {
  if (!ws.x.allFinite()) return AdaptiveStatus::non_finite;
  ++ws.evaluations;
  const Vector& x = ws.x;
  if (!evaluate_rhs(f, ws.t, x, ws.k[0])) return AdaptiveStatus::rhs_failed;
  return ws.k[0].allFinite() ? AdaptiveStatus::ok : AdaptiveStatus::non_finite;
}

/// Dense output on the last accepted step: the pair's continuous extension (see
/// EmbeddedTableau::dense; for dormand_prince54 Hairer's, of 4th order, whose error is O(h^5)
/// like the step's own local error). It is evaluated from the nearer end of the step, so
/// t = ws.t_previous gives ws.x_previous and t = ws.t the step's end state exactly. Before the
/// first step it returns x0.
/// \param[in]  ws     workspace after adaptive_step (or adaptive_start)
/// \param[in]  t      time in [ws.t_previous, ws.t]; outside it the polynomial extrapolates
///                    (not checked: this runs in the output loop)
/// \param[out] x_out  state at t (dim n; sized by the caller so nothing is allocated); must
///                    not be a member of ws
template <typename Vector, std::size_t S>
void dense_output(const AdaptiveWorkspace<Vector, S>& ws, typename Vector::Scalar t,
                  Vector& x_out) {
  using Scalar = typename Vector::Scalar;
  const Scalar h = ws.t - ws.t_previous;
  if (!(h > 0)) {
    x_out = ws.dense[0];
    return;
  }
  const Scalar theta = (t - ws.t_previous) / h, theta1 = (ws.t - t) / h;
  const auto& d = ws.dense;
  // x0 + theta (D + theta1 Q) = x1 - theta1 (D - theta Q) with Q = B + theta (C + theta1 E)
  if (theta <= theta1)
    x_out = ws.x_previous + theta * (d[1] + theta1 * (d[2] + theta * (d[3] + theta1 * d[4])));
  else
    x_out = d[0] - theta1 * (d[1] - theta * (d[2] + theta * (d[3] + theta1 * d[4])));
}

/// Where an adaptive integration ended, and what it cost.
template <typename Vector>
struct AdaptiveResult {
  /// ok, or why the integration stopped early
  AdaptiveStatus status;
  /// ok: exactly the last grid time. Otherwise the time of the last accepted state
  typename Vector::Scalar t;
  /// state at t (dim n); always the last accepted state, so finite unless x0 was not
  Vector x;
  /// accepted and rejected step attempts, and calls of f
  long long accepted, rejected, evaluations;
};

namespace detail {

/// Misuse checks of an output grid: non-empty, finite, strictly increasing, from t0 on.
template <typename Scalar, typename Grid>
void check_grid(Scalar t0, const Grid& grid) {
  using std::isfinite;
  const std::size_t count = static_cast<std::size_t>(std::size(grid));
  if (count == 0)
    throw std::invalid_argument("integrate_adaptive: grid expected non-empty, got 0 times");
  const auto at = [&grid](std::size_t i) { return static_cast<Scalar>(grid[i]); };
  for (std::size_t i = 0; i < count; ++i) {
    if (isfinite(at(i)) && (i == 0 ? at(i) >= t0 : at(i) > at(i - 1))) continue;
    std::ostringstream msg;
    msg << "integrate_adaptive: grid expected finite, strictly increasing and >= t0 = " << t0
        << ", got grid[" << i << "] = " << at(i);
    if (i > 0) msg << " after grid[" << i - 1 << "] = " << at(i - 1);
    throw std::invalid_argument(msg.str());
  }
}

}  // namespace detail

/// Integrates x' = f(t, x) from (t0, x0) to the last time of an increasing grid, calling
/// observer(t_g, x(t_g)) at every grid time t_g reached, from the dense output (so the grid
/// does not constrain the steps; the last grid time is the end of the last step).
/// \param[in] pair      embedded pair, consistent and FSAL (e.g. dormand_prince54)
/// \param[in] f         right-hand side f(t, x, dxdt), returning void or bool (see rhs.hpp)
/// \param[in] t0        initial time
/// \param[in] x0        initial state (dim n)
/// \param[in] grid      output times, strictly increasing, finite, grid[0] >= t0 (a grid time
///                      equal to t0 is observed with x0); any range with std::size and []
/// \param[in] options   tolerances and limits
/// \param[in] observer  called as observer(t, x) at each grid time, in order
/// \return status, time and state reached, step statistics; see AdaptiveResult
/// @throws std::invalid_argument if the grid is empty, not finite, not strictly increasing
///         or starts before t0, or on any misuse that adaptive_start rejects
template <std::size_t S, typename Rhs, typename Vector, typename Grid,
          typename Observer = NoObserver>
AdaptiveResult<Vector> integrate_adaptive(const EmbeddedTableau<S>& pair, Rhs&& f,
                                          typename Vector::Scalar t0, const Vector& x0,
                                          const Grid& grid,
                                          const AdaptiveOptions<typename Vector::Scalar>& options =
                                              AdaptiveOptions<typename Vector::Scalar>(),
                                          Observer&& observer = Observer{}) {
  using Scalar = typename Vector::Scalar;
  // misuse is reported before the loop; inside it only statuses are returned
  detail::check_grid(t0, grid);
  const std::size_t count = static_cast<std::size_t>(std::size(grid));
  const auto at = [&grid](std::size_t i) { return static_cast<Scalar>(grid[i]); };
  const Scalar t_end = at(count - 1);
  detail::check_adaptive_arguments("integrate_adaptive", pair, t0, t_end, options);

  AdaptiveWorkspace<Vector, S> ws(x0.size());
  Vector x_grid = x0;
  const Vector& x_observed = x_grid;
  std::size_t next = 0;
  // the grid times covered by the last accepted step, or t0 itself before the first step
  const auto observe = [&]() {
    for (; next < count && at(next) <= ws.t; ++next) {
      dense_output(ws, at(next), x_grid);
      observer(at(next), x_observed);
    }
  };

  AdaptiveStatus status = adaptive_start(pair, f, t0, x0, t_end, options, ws);
  if (status == AdaptiveStatus::ok) observe();
  while (status == AdaptiveStatus::ok && ws.t < t_end) {
    status = adaptive_step(pair, f, t_end, options, ws);
    if (status == AdaptiveStatus::ok) observe();
  }
  return AdaptiveResult<Vector>{status, ws.t, ws.x, ws.accepted, ws.rejected, ws.evaluations};
}

}  // namespace eomrt
