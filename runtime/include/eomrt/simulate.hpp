#pragma once
/// \file
/// simulate(): integrates a model's first-order form x = [q; qd], x' = [qd; qdd(t, q, qd, u)],
/// with a method of the registry (integrators.hpp: fixed-step Euler and RK4, adaptive
/// Dormand-Prince 5(4)), the constraints
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
#include <tuple>
#include <type_traits>
#include <utility>

#include "eomrt/dynamics_kkt.hpp"
#include "eomrt/dynamics_null_space.hpp"
#include "eomrt/dynamics_unconstrained.hpp"
#include "eomrt/integrators.hpp"
#include "eomrt/rk_adaptive.hpp"
#include "eomrt/rk_fixed.hpp"
#include "eomrt/stabilization.hpp"
#include "eomrt/tableau.hpp"

namespace eomrt {

enum class ConstraintSolver { kkt, null_space };
enum class Stabilization { none, baumgarte, projection };

/// The methods an instantiation of simulate() can run: every integrator, constraint solver and
/// the projection it contains is compiled for the model. With the model's fixed-size matrices
/// each costs seconds of compile time (the null-space solver's QR, 15 s of the 35 s a rolling
/// coin's program took), so a program that knows its options when it is compiled, as eomgen
/// simulate's does, names only those (OnlyMethods).
struct AllMethods {
  static constexpr bool has(Integrator) { return true; }
  static constexpr bool has(ConstraintSolver) { return true; }
  static constexpr bool has(Stabilization) { return true; }
};

/// One integrator, one constraint solver and one stabilization.
template <Integrator method, ConstraintSolver solver, Stabilization stabilization>
struct OnlyMethods {
  static constexpr bool has(Integrator i) { return i == method; }
  static constexpr bool has(ConstraintSolver c) { return c == solver; }
  static constexpr bool has(Stabilization s) { return s == stabilization; }
};

/// How a simulation is run. Defaults suit a first look at most models.
template <class Scalar>
struct SimulationOptions {
  Integrator integrator = default_integrator;  ///< a method of the registry (integrators.hpp)
  Scalar t0 = 0;                    ///< [s] start time
  Scalar t_end = 1;                 ///< [s] end time, t_end >= t0
  Scalar step = Scalar(1e-3);       ///< [s] step of the fixed-step methods
  AdaptiveOptions<Scalar> adaptive;  ///< tolerances of the adaptive methods
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
  /// ws.qdd, ws.lambda, ws.M, ... at this state; for a model that uses its forward_dynamics()
  /// (uses_forward_dynamics_v) only ws.qdd: forward_dynamics_unconstrained does not evaluate M
  /// and F then
  const DynamicsWorkspace<Model, Scalar>& ws;
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
template <class Model, class Scalar, class InputFn, class Methods>
struct SimulationContext {
  using Types = ModelTypes<Model, Scalar>;
  static constexpr int nq = Model::nq;

  /// the parameters' Constants, computed once for the whole run (a copy of the parameters for
  /// a model without them)
  const ParameterSet<Model, Scalar> p;
  const SimulationOptions<Scalar>& options;
  InputFn& input;
  DynamicsWorkspace<Model, Scalar> ws;
  typename Types::Coordinates q, qd;
  typename Types::Inputs u;
  DynamicsStatus failure = DynamicsStatus::ok;
  const SpeedPartition<Model>* partition = nullptr;

  SimulationContext(const typename Types::Parameters& p_, const SimulationOptions<Scalar>& o,
                    InputFn& in, const SpeedPartition<Model>* part)
      : p(make_parameter_set<Model, Scalar>(p_)), options(o), input(in), partition(part) {
    q.setZero();
    qd.setZero();
    u.setZero();
  }

  /// qdd (and lambda) at (t, x) into ws, with the configured solver and Baumgarte terms
  DynamicsStatus dynamics(const Scalar& t, const typename Types::State& x) {
    q = x.template head<nq>();
    qd = x.template tail<nq>();
    input(t, x, u);
    // without constraints: the model's own forward_dynamics() where it prefers it (linear in the
    // number of bodies), M, F and Cholesky otherwise; nothing to stabilize
    if constexpr (Model::nc == 0)
      return forward_dynamics_unconstrained<Model, Scalar>(p, ws, t, q, qd, u);
    const Baumgarte<Scalar> stab = options.stabilization == Stabilization::baumgarte
                                       ? options.baumgarte
                                       : Baumgarte<Scalar>{};
    if constexpr (Methods::has(ConstraintSolver::null_space))
      if (options.solver == ConstraintSolver::null_space)
        return forward_dynamics_null_space<Model, Scalar>(p, ws, t, q, qd, u, stab, partition);
    if constexpr (Methods::has(ConstraintSolver::kkt))
      return forward_dynamics_kkt<Model, Scalar>(p, ws, t, q, qd, u, stab);
    return DynamicsStatus::ok;  // not reached: simulate() refuses a solver Methods lacks
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
    if constexpr (!Methods::has(Stabilization::projection)) {
      return DynamicsStatus::ok;
    } else {
      if (options.stabilization != Stabilization::projection || Model::nc == 0)
        return DynamicsStatus::ok;
      q = x.template head<nq>();
      qd = x.template tail<nq>();
      const DynamicsStatus s = project_onto_constraints<Model, Scalar>(p, ws, t, q, qd);
      x.template head<nq>() = q;
      x.template tail<nq>() = qd;
      return s;
    }
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
  const bool adaptive = is_adaptive(o.integrator);
  if (find_integrator(o.integrator) == nullptr)
    msg << "simulate: integrator expected a registered method, got " << static_cast<int>(o.integrator);
  else if (!isfinite(o.t0) || !isfinite(o.t_end) || o.t_end < o.t0)
    msg << "simulate: time span expected finite with t_end >= t0, got [" << o.t0 << ", " << o.t_end
        << "]";
  else if (!adaptive && !(isfinite(o.step) && o.step > 0))
    msg << "simulate: step expected positive and finite, got " << o.step;
  else if (!adaptive && !((o.t_end - o.t0) / o.step <= Scalar(1e15)))
    msg << "simulate: (t_end - t0) / step expected at most 1e15 steps, got " << (o.t_end - o.t0) / o.step;
  else if (!(isfinite(o.sample_interval) && o.sample_interval >= 0))
    msg << "simulate: sample interval expected >= 0 and finite, got " << o.sample_interval;
  else if (o.sample_interval > 0 && !((o.t_end - o.t0) / o.sample_interval <= Scalar(1e15)))
    msg << "simulate: (t_end - t0) / sample_interval expected at most 1e15 samples";
  else if (adaptive &&
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
  return is_adaptive(o.integrator) ? Scalar(0) : o.step;
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

namespace detail {

/// Records a failure detected at time \p when; the result keeps the last good state.
template <class Model, class Scalar>
void fail(SimulationResult<Model, Scalar>& result, SimulationStatus status, const Scalar& when) {
  result.status = status;
  result.failure_time = when;
}

inline SimulationStatus simulation_status(AdaptiveStatus s, DynamicsStatus rhs_failure) {
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
      return simulation_status(rhs_failure);
  }
  return SimulationStatus::non_finite_state;
}

/// Fixed steps from result.t to the sample time t_target: the interval is cut into equal steps
/// no longer than options.step, so that the sample lands on a step.
/// \return false if a step failed (recorded in result, which keeps the last good state)
template <std::size_t S, class Model, class Scalar, class InputFn, class Methods, class Rhs, class State>
bool fixed_steps_to(const ButcherTableau<S>& tableau,
                    SimulationContext<Model, Scalar, InputFn, Methods>& ctx, Rhs& rhs,
                    RkWorkspace<State, S>& ws, const Scalar& t_target,
                    SimulationResult<Model, Scalar>& result) {
  using std::abs;
  using std::ceil;
  using std::round;
  const Scalar ratio = (t_target - result.t) / ctx.options.step;
  // a ratio within rounding of an integer takes that many steps, not one more sliver
  const Scalar whole =
      abs(ratio - round(ratio)) <= Scalar(1e-9) * (1 + ratio) ? round(ratio) : ceil(ratio);
  const long long n_steps = whole < 1 ? 1 : static_cast<long long>(whole);
  const Scalar t_start = result.t;
  for (long long k = 0; k < n_steps; ++k) {
    const Scalar t_next = k + 1 == n_steps
                              ? t_target
                              : t_start + (t_target - t_start) * static_cast<Scalar>(k + 1) /
                                              static_cast<Scalar>(n_steps);
    const State x_before = result.x;
    const bool ok = rk_step(tableau, rhs, result.t, result.x, t_next - result.t, ws);
    result.evaluations += static_cast<long long>(S);
    SimulationStatus status = SimulationStatus::ok;
    Scalar when = t_next;
    if (!ok) {
      status = simulation_status(ctx.failure);
      when = result.t;
    } else if (!result.x.allFinite()) {
      status = SimulationStatus::non_finite_state;
    } else {
      status = simulation_status(ctx.stabilize(t_next, result.x));
    }
    if (status != SimulationStatus::ok) {
      result.x = x_before;
      fail(result, status, when);
      return false;
    }
    result.t = t_next;
    ++result.steps;
  }
  return true;
}

/// A fixed-step method from the first sample to t_end, marching from sample to sample.
template <std::size_t S, class Model, class Scalar, class InputFn, class Methods, class Observer>
void march_fixed(const ButcherTableau<S>& tableau, SimulationContext<Model, Scalar, InputFn, Methods>& ctx,
                 Observer& observer, SimulationResult<Model, Scalar>& result) {
  using State = typename ModelTypes<Model, Scalar>::State;
  auto rhs = [&ctx](const Scalar& t, const State& x, State& dxdt) { return ctx.rhs(t, x, dxdt); };
  RkWorkspace<State, S> ws(2 * Model::nq);
  for (long long next_sample = 1; result.t < ctx.options.t_end; ++next_sample) {
    if (!fixed_steps_to(tableau, ctx, rhs, ws, sample_time(ctx.options, next_sample), result))
      return;
    const DynamicsStatus ds = ctx.emit(result.t, result.x, observer);
    if (ds != DynamicsStatus::ok) return fail(result, simulation_status(ds), result.t);
  }
}

/// The samples of the grid inside the step just accepted, from its dense output: before the
/// end state is projected. \return false if one failed (recorded in result)
template <class Model, class Scalar, class InputFn, class Methods, class Observer, class Workspace, class State>
bool emit_dense_samples(SimulationContext<Model, Scalar, InputFn, Methods>& ctx, const Workspace& ws,
                        Observer& observer, long long& next_sample, State& x_sample,
                        SimulationResult<Model, Scalar>& result) {
  for (Scalar ts = sample_time(ctx.options, next_sample); ts < ws.t;
       ts = sample_time(ctx.options, ++next_sample)) {
    dense_output(ws, ts, x_sample);
    const DynamicsStatus ds = ctx.emit(ts, x_sample, observer);
    if (ds != DynamicsStatus::ok) {
      fail(result, simulation_status(ds), ts);
      return false;
    }
  }
  return true;
}

/// An adaptive method from the first sample to t_end: steps as the error control chooses,
/// samples from the dense output (or after every step when there is no grid), and the end of
/// each step projected onto the constraints, the stepper then restarted from the projection.
template <std::size_t S, class Model, class Scalar, class InputFn, class Methods, class Observer>
void march_adaptive(const EmbeddedTableau<S>& pair, SimulationContext<Model, Scalar, InputFn, Methods>& ctx,
                    Observer& observer, SimulationResult<Model, Scalar>& result) {
  using State = typename ModelTypes<Model, Scalar>::State;
  const SimulationOptions<Scalar>& o = ctx.options;
  auto rhs = [&ctx](const Scalar& t, const State& x, State& dxdt) { return ctx.rhs(t, x, dxdt); };
  AdaptiveWorkspace<State, S> ws(2 * Model::nq);
  const auto record_statistics = [&]() {
    result.steps = ws.accepted;
    result.rejected_steps = ws.rejected;
    result.evaluations = ws.evaluations;
  };
  const bool every_step = sample_interval(o) == 0;
  const bool restart = o.stabilization == Stabilization::projection && Model::nc > 0;
  long long next_sample = 1;  // index of the next sample time on the grid
  State x_sample = result.x;

  AdaptiveStatus as = adaptive_start(pair, rhs, o.t0, result.x, o.t_end, o.adaptive, ws);
  if (as != AdaptiveStatus::ok) return fail(result, simulation_status(as, ctx.failure), o.t0);
  while (ws.t < o.t_end) {
    as = adaptive_step(pair, rhs, o.t_end, o.adaptive, ws);
    record_statistics();
    if (as != AdaptiveStatus::ok) {
      result.t = ws.t;
      result.x = ws.x;
      return fail(result, simulation_status(as, ctx.failure), ws.t);
    }
    if (!every_step && !emit_dense_samples(ctx, ws, observer, next_sample, x_sample, result))
      return;
    const DynamicsStatus ds = ctx.stabilize(ws.t, ws.x);
    if (ds != DynamicsStatus::ok) return fail(result, simulation_status(ds), ws.t);
    if (restart) {
      as = adaptive_restart(rhs, ws);
      if (as != AdaptiveStatus::ok) return fail(result, simulation_status(as, ctx.failure), ws.t);
    }
    result.t = ws.t;
    result.x = ws.x;
    if (every_step || ws.t == sample_time(o, next_sample)) {
      // emitted from a copy: emit may project, and ws.x must stay what adaptive_restart saw
      x_sample = ws.x;
      const DynamicsStatus emitted = ctx.emit(ws.t, x_sample, observer);
      if (emitted != DynamicsStatus::ok) return fail(result, simulation_status(emitted), ws.t);
      ++next_sample;
    }
  }
  record_statistics();
}

}  // namespace detail

namespace detail {

/// visit_integrator over the rows Methods has: the others are not compiled.
template <class Methods, std::size_t I = 0, class F>
void visit_integrator_of(Integrator method, F& f) {
  constexpr auto& entry = std::get<I>(integrator_registry);
  if constexpr (Methods::has(entry.method))
    if (entry.method == method) return f(entry);
  if constexpr (I + 1 < std::tuple_size_v<std::decay_t<decltype(integrator_registry)>>)
    visit_integrator_of<Methods, I + 1>(method, f);
}

}  // namespace detail

/// simulate() compiled with the methods of Methods only (AllMethods, OnlyMethods).
/// @throws std::invalid_argument if the options ask for an integrator, constraint solver or
///         stabilization Methods lacks, and where simulate() throws
template <class Methods, class Model, class Scalar = double, class InputFn = ZeroInputs,
          class Observer = IgnoreSamples>
SimulationResult<Model, Scalar> simulate_with(const typename ModelTypes<Model, Scalar>::Parameters& p,
                                              const typename ModelTypes<Model, Scalar>::State& x0,
                                              const SimulationOptions<Scalar>& options,
                                              InputFn&& input = InputFn{},
                                              Observer&& observer = Observer{}) {
  static_assert(check_model<Model, Scalar>());
  detail::check_options(options);
  if (!Methods::has(options.integrator) || !Methods::has(options.solver) ||
      !Methods::has(options.stabilization))
    throw std::invalid_argument(std::string("simulate: the integrator ") + to_string(options.integrator) +
                                ", its constraint solver or its stabilization is not compiled into this program");

  // the declared partition is built (and validated) here, before the loop
  std::optional<SpeedPartition<Model>> declared;
  if constexpr (has_independent_speeds_v<Model> && Methods::has(ConstraintSolver::null_space)) {
    if (options.use_declared_speeds && options.solver == ConstraintSolver::null_space)
      declared = declared_speed_partition<Model>();
  }
  const SpeedPartition<Model>* partition = declared ? &*declared : nullptr;

  using Input = std::remove_reference_t<InputFn>;
  detail::SimulationContext<Model, Scalar, Input, Methods> ctx(p, options, input, partition);
  SimulationResult<Model, Scalar> result;
  result.t = options.t0;
  result.x = x0;
  if (!result.x.allFinite()) {
    detail::fail(result, SimulationStatus::non_finite_state, options.t0);
    return result;
  }

  // the first sample stabilizes x0 (projection) and proves the dynamics regular there
  const DynamicsStatus ds = ctx.emit(options.t0, result.x, observer);
  if (ds != DynamicsStatus::ok) {
    detail::fail(result, detail::simulation_status(ds), options.t0);
    return result;
  }
  if (options.t_end == options.t0) return result;

  const auto march = [&](const auto& entry) {
    if constexpr (std::decay_t<decltype(entry)>::adaptive)
      detail::march_adaptive(entry.tableau, ctx, observer, result);
    else
      detail::march_fixed(entry.tableau, ctx, observer, result);
  };
  detail::visit_integrator_of<Methods>(options.integrator, march);
  return result;
}

/// Simulates a model from (t0, x0) to t_end.
/// \param[in] p         parameters; a model with Constants is evaluated through Constants built
///                      once from them (make_parameter_set)
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
  return simulate_with<AllMethods, Model, Scalar>(p, x0, options, std::forward<InputFn>(input),
                                                  std::forward<Observer>(observer));
}

}  // namespace eomrt
