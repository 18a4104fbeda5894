#pragma once
/// \file
/// simulate(): integrates a model's first-order form x = [q; qd], x' = [qd; qdd(t, q, qd, u)],
/// with a fixed-step (Euler, RK4) or adaptive (Dormand-Prince 5(4)) method, the constraints
/// handled by Lagrange multipliers (KKT) or the null-space method, drift corrected by Baumgarte
/// terms or by projection, inputs from a callback u(t, x), and samples on a uniform time grid.
///
/// Nothing inside the loop allocates or throws: a failure (non-finite state, singular M or KKT
/// matrix, step-size underflow) ends the run with a status, the time and the last good state,
/// and describe() turns that into a message. Misuse is reported before the loop.
#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "eomrt/dormand_prince.hpp"
#include "eomrt/dynamics_kkt.hpp"
#include "eomrt/dynamics_null_space.hpp"
#include "eomrt/rk_fixed.hpp"
#include "eomrt/stabilization.hpp"
#include "eomrt/tableau.hpp"

namespace eomrt {

enum class Integrator { euler, rk4, dormand_prince };
enum class ConstraintSolver { kkt, null_space };
enum class Stabilization { none, baumgarte, projection };

/// \return the enumerator's name (as the eomgen command spells it)
inline const char* to_string(Integrator m) {
  switch (m) {
    case Integrator::euler:
      return "euler";
    case Integrator::rk4:
      return "rk4";
    case Integrator::dormand_prince:
      return "dp5";
  }
  return "unknown";
}

/// How a simulation is run. Defaults suit a first look at most models.
template <class Scalar>
struct SimulationOptions {
  Integrator integrator = Integrator::dormand_prince;
  Scalar t0 = 0;                    ///< [s] start time
  Scalar t_end = 1;                 ///< [s] end time, t_end >= t0
  Scalar step = Scalar(1e-3);       ///< [s] step of the fixed-step methods
  AdaptiveOptions<Scalar> adaptive;  ///< tolerances of dormand_prince
  /// [s] observer called at t0 + k sample_interval and at t_end; 0: after every step
  Scalar sample_interval = 0;
  ConstraintSolver solver = ConstraintSolver::kkt;
  /// null space from the model's declared independent speeds when it has them (else QR)
  bool use_declared_speeds = true;
  Stabilization stabilization = Stabilization::projection;
  /// used with Stabilization::baumgarte; alpha = beta = 1/(a few steps) is the usual choice
  Baumgarte<Scalar> baumgarte{Scalar(10), Scalar(10)};
};

/// Why a simulation ended.
enum class SimulationStatus {
  ok,                            ///< reached t_end
  non_finite_state,              ///< the state became NaN or infinite
  singular_mass_matrix,          ///< M (or Upsilon^T M Upsilon) not positive definite
  singular_kkt_matrix,           ///< the KKT matrix is singular
  singular_constraint_jacobian,  ///< Xi lost rank
  projection_failed,             ///< the projection onto phi = 0 did not converge
  step_size_underflow,           ///< the adaptive step fell below the resolution of t
  too_many_steps,                ///< the adaptive method exceeded its step budget
};

/// \return the enumerator's name
inline const char* to_string(SimulationStatus status) {
  switch (status) {
    case SimulationStatus::ok:
      return "ok";
    case SimulationStatus::non_finite_state:
      return "non_finite_state";
    case SimulationStatus::singular_mass_matrix:
      return "singular_mass_matrix";
    case SimulationStatus::singular_kkt_matrix:
      return "singular_kkt_matrix";
    case SimulationStatus::singular_constraint_jacobian:
      return "singular_constraint_jacobian";
    case SimulationStatus::projection_failed:
      return "projection_failed";
    case SimulationStatus::step_size_underflow:
      return "step_size_underflow";
    case SimulationStatus::too_many_steps:
      return "too_many_steps";
  }
  return "unknown";
}

/// \return what the status means, as a sentence fragment for error messages
inline const char* describe(SimulationStatus status) {
  switch (status) {
    case SimulationStatus::ok:
      return "reached the end time";
    case SimulationStatus::non_finite_state:
      return "the state became NaN or infinite (the motion blew up)";
    case SimulationStatus::singular_mass_matrix:
      return "the mass matrix is singular (a singular configuration of the coordinates)";
    case SimulationStatus::singular_kkt_matrix:
      return "the KKT matrix is singular (dependent constraints, or M singular on the constraints)";
    case SimulationStatus::singular_constraint_jacobian:
      return "the constraint Jacobian Xi lost rank (dependent constraints)";
    case SimulationStatus::projection_failed:
      return "the projection onto the position constraints did not converge";
    case SimulationStatus::step_size_underflow:
      return "the step size fell below the resolution of t (the solution blows up or is too stiff)";
    case SimulationStatus::too_many_steps:
      return "the adaptive method exceeded its step budget";
  }
  return "unknown status";
}

/// What the observer sees at a sample: the state and the dynamics evaluated there.
template <class Model, class Scalar>
struct Sample {
  using Types = ModelTypes<Model, Scalar>;
  Scalar t;                                    ///< [s] time
  const typename Types::Coordinates& q;        ///< coordinates (dim nq)
  const typename Types::Coordinates& qd;       ///< rates (dim nq)
  const typename Types::Inputs& u;             ///< inputs (dim nu)
  const DynamicsWorkspace<Model, Scalar>& ws;  ///< ws.qdd, ws.lambda, ws.M, ... at this state
  ConstraintResiduals<Scalar> residuals;       ///< after stabilization
  Scalar kinetic_energy;                       ///< T
  Scalar potential_energy;                     ///< V
};

/// Where a simulation ended.
template <class Model, class Scalar>
struct SimulationResult {
  using Types = ModelTypes<Model, Scalar>;
  SimulationStatus status = SimulationStatus::ok;
  Scalar t = 0;                  ///< end time: t_end, or the time of the last good state
  typename Types::State x;       ///< state at t (the last good one when status != ok)
  Scalar failure_time = 0;       ///< time at which the failure was detected (status != ok)
  long long steps = 0;           ///< accepted steps
  long long rejected_steps = 0;  ///< rejected steps (adaptive method)
  long long evaluations = 0;     ///< right-hand side evaluations
};

/// Inputs that are always zero: the default input callback.
struct ZeroInputs {
  template <class Scalar, class State, class Inputs>
  void operator()(const Scalar& /*t*/, const State& /*x*/, Inputs& u) const noexcept {
    u.setZero();
  }
};

/// Observer that ignores every sample: the default of simulate().
struct IgnoreSamples {
  template <class S>
  void operator()(const S& /*sample*/) const noexcept {}
};

namespace detail {

inline SimulationStatus simulation_status(DynamicsStatus s) {
  switch (s) {
    case DynamicsStatus::ok:
      return SimulationStatus::ok;
    case DynamicsStatus::non_finite:
      return SimulationStatus::non_finite_state;
    case DynamicsStatus::singular_mass_matrix:
      return SimulationStatus::singular_mass_matrix;
    case DynamicsStatus::singular_kkt_matrix:
      return SimulationStatus::singular_kkt_matrix;
    case DynamicsStatus::singular_constraint_jacobian:
      return SimulationStatus::singular_constraint_jacobian;
    case DynamicsStatus::projection_failed:
      return SimulationStatus::projection_failed;
  }
  return SimulationStatus::non_finite_state;
}

/// Everything one simulation needs besides the integrator's own scratch; built once.
template <class Model, class Scalar, class InputFn>
struct SimulationContext {
  using Types = ModelTypes<Model, Scalar>;
  static constexpr int nq = Model::nq;

  const typename Types::Parameters& p;
  const SimulationOptions<Scalar>& options;
  InputFn& input;
  DynamicsWorkspace<Model, Scalar> ws;
  typename Types::Coordinates q, qd;
  typename Types::Inputs u;
  DynamicsStatus failure = DynamicsStatus::ok;
  const SpeedPartition<Model>* partition = nullptr;

  SimulationContext(const typename Types::Parameters& p_, const SimulationOptions<Scalar>& o,
                    InputFn& in, const SpeedPartition<Model>* part)
      : p(p_), options(o), input(in), partition(part) {
    q.setZero();
    qd.setZero();
    u.setZero();
  }

  /// qdd (and lambda) at (t, x) into ws, with the configured solver and Baumgarte terms
  DynamicsStatus dynamics(const Scalar& t, const typename Types::State& x) {
    q = x.template head<nq>();
    qd = x.template tail<nq>();
    input(t, x, u);
    const Baumgarte<Scalar> stab = options.stabilization == Stabilization::baumgarte
                                       ? options.baumgarte
                                       : Baumgarte<Scalar>{};
    if (options.solver == ConstraintSolver::null_space)
      return forward_dynamics_null_space<Model, Scalar>(p, ws, t, q, qd, u, stab, partition);
    return forward_dynamics_kkt<Model, Scalar>(p, ws, t, q, qd, u, stab);
  }

  /// the right-hand side for the integrators; false stops them (the reason stays in failure)
  bool rhs(const Scalar& t, const typename Types::State& x, typename Types::State& dxdt) {
    const DynamicsStatus s = dynamics(t, x);
    if (s != DynamicsStatus::ok) {
      failure = s;
      return false;
    }
    dxdt.template head<nq>() = x.template tail<nq>();
    dxdt.template tail<nq>() = ws.qdd;
    return true;
  }

  /// projects x in place when projection is on
  DynamicsStatus stabilize(const Scalar& t, typename Types::State& x) {
    if (options.stabilization != Stabilization::projection || Model::nc == 0)
      return DynamicsStatus::ok;
    q = x.template head<nq>();
    qd = x.template tail<nq>();
    const DynamicsStatus s = project_onto_constraints<Model, Scalar>(p, ws, t, q, qd);
    x.template head<nq>() = q;
    x.template tail<nq>() = qd;
    return s;
  }

  /// evaluates everything a sample reports at (t, x) and hands it to the observer
  template <class Observer>
  DynamicsStatus emit(const Scalar& t, typename Types::State& x, Observer& observer) {
    DynamicsStatus s = stabilize(t, x);
    if (s != DynamicsStatus::ok) return s;
    s = dynamics(t, x);
    if (s != DynamicsStatus::ok) return s;
    const Scalar T = Model::kinetic_energy(t, q, qd, p);
    const Scalar V = Model::potential_energy(t, q, p);
    using std::isfinite;
    if (!isfinite(T) || !isfinite(V)) return DynamicsStatus::non_finite;
    const ConstraintResiduals<Scalar> r = constraint_residuals<Model, Scalar>(p, ws, t, q, qd);
    observer(Sample<Model, Scalar>{t, q, qd, u, ws, r, T, V});
    return DynamicsStatus::ok;
  }
};

template <class Scalar>
void check_options(const SimulationOptions<Scalar>& o) {
  using std::isfinite;
  std::ostringstream msg;
  if (!isfinite(o.t0) || !isfinite(o.t_end) || o.t_end < o.t0)
    msg << "simulate: time span expected finite with t_end >= t0, got [" << o.t0 << ", " << o.t_end
        << "]";
  else if (o.integrator != Integrator::dormand_prince && !(isfinite(o.step) && o.step > 0))
    msg << "simulate: step expected positive and finite, got " << o.step;
  else if (o.integrator != Integrator::dormand_prince && !((o.t_end - o.t0) / o.step <= Scalar(1e15)))
    msg << "simulate: (t_end - t0) / step expected at most 1e15 steps, got " << (o.t_end - o.t0) / o.step;
  else if (!(isfinite(o.sample_interval) && o.sample_interval >= 0))
    msg << "simulate: sample interval expected >= 0 and finite, got " << o.sample_interval;
  else if (o.sample_interval > 0 && !((o.t_end - o.t0) / o.sample_interval <= Scalar(1e15)))
    msg << "simulate: (t_end - t0) / sample_interval expected at most 1e15 samples";
  else if (o.integrator == Integrator::dormand_prince &&
           !(o.adaptive.rtol > 0 && o.adaptive.atol >= 0 && isfinite(o.adaptive.rtol) &&
             isfinite(o.adaptive.atol)))
    msg << "simulate: tolerances expected rtol > 0 and atol >= 0, got rtol " << o.adaptive.rtol
        << ", atol " << o.adaptive.atol;
  else if (o.stabilization == Stabilization::baumgarte &&
           !(o.baumgarte.alpha >= 0 && o.baumgarte.beta >= 0 && isfinite(o.baumgarte.alpha) &&
             isfinite(o.baumgarte.beta)))
    msg << "simulate: Baumgarte alpha and beta expected >= 0 and finite";
  else
    return;
  throw std::invalid_argument(msg.str());
}

/// Interval of the sample grid: the fixed step when every step is sampled.
template <class Scalar>
Scalar sample_interval(const SimulationOptions<Scalar>& o) {
  if (o.sample_interval > 0) return o.sample_interval;
  return o.integrator == Integrator::dormand_prince ? Scalar(0) : o.step;
}

/// Sample time number k, computed rather than accumulated so that the grid does not drift; a
/// time within rounding of t_end is t_end, so the grid never ends on a sliver interval.
template <class Scalar>
Scalar sample_time(const SimulationOptions<Scalar>& o, long long k) {
  const Scalar interval = sample_interval(o);
  const Scalar t = o.t0 + static_cast<Scalar>(k) * interval;
  return o.t_end - t <= Scalar(1e-9) * interval ? o.t_end : t;
}

}  // namespace detail

/// Simulates a model from (t0, x0) to t_end.
/// \param[in] p         parameters
/// \param[in] x0        initial state [q0; qd0] (dim 2 nq); with projection on, it is first
///                      projected onto the constraints
/// \param[in] options   integrator, span, solver, stabilization, sampling
/// \param[in] input     u(t, x, u): writes the inputs (dim nu); called at every evaluation
/// \param[in] observer  observer(const Sample&): called at t0, at every sample and at t_end
/// \return status, time and state reached, step statistics
/// @throws std::invalid_argument if the options are inconsistent (see check_options)
/// @throws std::invalid_argument if options.use_declared_speeds is set, the null-space solver
///         chosen, and the model's declared independent speeds are not a valid partition
template <class Model, class Scalar = double, class InputFn = ZeroInputs,
          class Observer = IgnoreSamples>
SimulationResult<Model, Scalar> simulate(const typename ModelTypes<Model, Scalar>::Parameters& p,
                                         const typename ModelTypes<Model, Scalar>::State& x0,
                                         const SimulationOptions<Scalar>& options,
                                         InputFn&& input = InputFn{},
                                         Observer&& observer = Observer{}) {
  static_assert(check_model<Model, Scalar>());
  using State = typename ModelTypes<Model, Scalar>::State;
  using std::abs;
  detail::check_options(options);

  // the declared partition is built (and validated) here, before the loop
  std::optional<SpeedPartition<Model>> declared;
  if constexpr (has_independent_speeds_v<Model>) {
    if (options.use_declared_speeds && options.solver == ConstraintSolver::null_space)
      declared = declared_speed_partition<Model>();
  }
  const SpeedPartition<Model>* partition = declared ? &*declared : nullptr;

  using Input = std::remove_reference_t<InputFn>;
  detail::SimulationContext<Model, Scalar, Input> ctx(p, options, input, partition);
  SimulationResult<Model, Scalar> result;
  result.t = options.t0;
  result.x = x0;

  const auto fail = [&](SimulationStatus status, const Scalar& when) {
    result.status = status;
    result.failure_time = when;
    return result;
  };
  if (!result.x.allFinite()) return fail(SimulationStatus::non_finite_state, options.t0);

  // the first sample stabilizes x0 (projection) and proves the dynamics regular there
  DynamicsStatus ds = ctx.emit(options.t0, result.x, observer);
  if (ds != DynamicsStatus::ok) return fail(detail::simulation_status(ds), options.t0);
  if (options.t_end == options.t0) return result;

  auto rhs = [&ctx](const Scalar& t, const State& x, State& dxdt) { return ctx.rhs(t, x, dxdt); };
  const bool every_step = detail::sample_interval(options) == 0;  // adaptive, no grid
  long long next_sample = 1;  // index of the next sample time on the grid
  State x_sample = result.x;

  if (options.integrator != Integrator::dormand_prince) {
    // fixed steps: march from sample time to sample time, each interval cut into equal steps
    // no longer than options.step, so that every sample lands on a step
    RkWorkspace<State, 4> ws4(2 * Model::nq);
    RkWorkspace<State, 1> ws1(2 * Model::nq);
    while (result.t < options.t_end) {
      using std::ceil;
      using std::round;
      const Scalar t_target = detail::sample_time(options, next_sample);
      const Scalar ratio = (t_target - result.t) / options.step;
      // a ratio within rounding of an integer takes that many steps, not one more sliver
      const Scalar whole = abs(ratio - round(ratio)) <= Scalar(1e-9) * (1 + ratio) ? round(ratio)
                                                                                     : ceil(ratio);
      const long long n_steps = whole < 1 ? 1 : static_cast<long long>(whole);
      const Scalar t_start = result.t;
      for (long long k = 0; k < n_steps; ++k) {
        const Scalar t_next =
            k + 1 == n_steps ? t_target
                             : t_start + (t_target - t_start) * static_cast<Scalar>(k + 1) /
                                             static_cast<Scalar>(n_steps);
        const State x_before = result.x;
        const bool ok = options.integrator == Integrator::rk4
                            ? rk_step(rk4, rhs, result.t, result.x, t_next - result.t, ws4)
                            : rk_step(euler, rhs, result.t, result.x, t_next - result.t, ws1);
        result.evaluations += options.integrator == Integrator::rk4 ? 4 : 1;
        if (!ok) {
          result.x = x_before;
          return fail(detail::simulation_status(ctx.failure), result.t);
        }
        if (!result.x.allFinite()) {
          result.x = x_before;
          return fail(SimulationStatus::non_finite_state, t_next);
        }
        ds = ctx.stabilize(t_next, result.x);
        if (ds != DynamicsStatus::ok) {
          result.x = x_before;
          return fail(detail::simulation_status(ds), t_next);
        }
        result.t = t_next;
        ++result.steps;
      }
      ds = ctx.emit(result.t, result.x, observer);
      if (ds != DynamicsStatus::ok) return fail(detail::simulation_status(ds), result.t);
      ++next_sample;
    }
    return result;
  }

  DormandPrinceWorkspace<State> dp(2 * Model::nq);
  const auto adaptive_failure = [&](AdaptiveStatus s) {
    switch (s) {
      case AdaptiveStatus::ok:
        return SimulationStatus::ok;
      case AdaptiveStatus::non_finite:
        return SimulationStatus::non_finite_state;
      case AdaptiveStatus::step_size_underflow:
        return SimulationStatus::step_size_underflow;
      case AdaptiveStatus::too_many_steps:
        return SimulationStatus::too_many_steps;
      case AdaptiveStatus::rhs_failed:
        return detail::simulation_status(ctx.failure);
    }
    return SimulationStatus::non_finite_state;
  };
  const auto record_statistics = [&]() {
    result.steps = dp.accepted;
    result.rejected_steps = dp.rejected;
    result.evaluations = dp.evaluations;
  };
  AdaptiveStatus as = dp_start(rhs, options.t0, result.x, options.t_end, options.adaptive, dp);
  if (as != AdaptiveStatus::ok) return fail(adaptive_failure(as), options.t0);
  while (dp.t < options.t_end) {
    as = dp_step(rhs, options.t_end, options.adaptive, dp);
    record_statistics();
    if (as != AdaptiveStatus::ok) {
      result.t = dp.t;
      result.x = dp.x;
      return fail(adaptive_failure(as), dp.t);
    }
    // samples inside the step come from the dense output, before the end state is projected
    if (!every_step) {
      for (Scalar ts = detail::sample_time(options, next_sample); ts < dp.t;
           ts = detail::sample_time(options, ++next_sample)) {
        dp_dense_output(dp, ts, x_sample);
        ds = ctx.emit(ts, x_sample, observer);
        if (ds != DynamicsStatus::ok) return fail(detail::simulation_status(ds), ts);
      }
    }
    ds = ctx.stabilize(dp.t, dp.x);
    if (ds != DynamicsStatus::ok) return fail(detail::simulation_status(ds), dp.t);
    if (options.stabilization == Stabilization::projection && Model::nc > 0) {
      as = dp_restart(rhs, dp);
      if (as != AdaptiveStatus::ok) return fail(adaptive_failure(as), dp.t);
    }
    result.t = dp.t;
    result.x = dp.x;
    if (every_step || dp.t == detail::sample_time(options, next_sample)) {
      // emitted from a copy: emit may project, and dp.x must stay what dp_restart saw
      x_sample = dp.x;
      ds = ctx.emit(dp.t, x_sample, observer);
      if (ds != DynamicsStatus::ok) return fail(detail::simulation_status(ds), dp.t);
      ++next_sample;
    }
  }
  record_statistics();
  return result;
}

}  // namespace eomrt
