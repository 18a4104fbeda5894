#pragma once
/// \file
/// What a model's module does with the runtime (eomrt) besides the generated functions: A and
/// B about a state (eomrt::linearization), a consistent state (eomrt::assemble), and a
/// simulation (eomrt::simulate_with), each with NumPy arrays in and out.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "eompy/arrays.hpp"
#include "eompy/functions.hpp"
#include "eompy/parameters.hpp"
#include "eomrt/assembly.hpp"
#include "eomrt/integrators.hpp"
#include "eomrt/linearization.hpp"
#include "eomrt/sampling.hpp"
#include "eomrt/simulate.hpp"

namespace eompy {

namespace py = pybind11;

/// The methods a module's simulate() can run: every integrator and stabilization, the
/// constraint forces by the KKT system. The null-space solver's fixed-size QR would add tens of
/// seconds to the module's compile for a constrained model (eomrt::AllMethods); `eomgen
/// simulate --solver null-space` runs it.
struct ModuleMethods {
  static constexpr bool has(eomrt::Integrator) { return true; }
  static constexpr bool has(eomrt::ConstraintSolver s) { return s == eomrt::ConstraintSolver::kkt; }
  static constexpr bool has(eomrt::Stabilization) { return true; }
};

/// Why the dynamics failed, as a sentence fragment.
inline const char* dynamics_failure(eomrt::DynamicsStatus status) {
  switch (status) {
    case eomrt::DynamicsStatus::ok: return nullptr;
    case eomrt::DynamicsStatus::non_finite:
      return "the terms of the equations are not finite (a NaN or infinite argument, or a singular configuration)";
    case eomrt::DynamicsStatus::singular_mass_matrix: return "the mass matrix is not positive definite";
    case eomrt::DynamicsStatus::singular_kkt_matrix:
      return "the KKT matrix is singular (dependent constraints, or M singular on the constraints)";
    case eomrt::DynamicsStatus::singular_constraint_jacobian: return "the constraint Jacobian Xi lost rank";
    case eomrt::DynamicsStatus::projection_failed: return "the projection onto the constraints did not converge";
  }
  return "an unknown failure";
}

/// linearization(t, q, qd, u=None, p=None) -> (A, B) of dx' = A dx + B du, x = [q; qd], by
/// eomrt::linearization from the exact derivatives the header holds.
template <class Model>
void define_linearization(py::module_& m, const ParameterSet<Model>& defaults) {
  using Types = eomrt::ModelTypes<Model, double>;
  constexpr int n = 2 * Model::nq;
  FunctionDefinition<Model, Returns::status, Reads<Arg::t, Arg::q, Arg::qd, Arg::u, Arg::p>, Out<n, n, false>,
                     Out<n, Model::nu, false>>::
      define(m, "linearization",
             "linearization(t, q, qd, u=None, p=None) -> ((nx, nx), (nx, nu))\n\n"
             "A (2 nq x 2 nq) and B (2 nq x nu) of dx' = A dx + B du about the state x = [q; qd] and the inputs u, "
             "x' = [qd; qdd], from the exact derivatives of the equations (eomrt::linearization; with constraints, "
             "qdd and lambda from the KKT system).",
             defaults, [](const Point<Model>& x, auto&& A, auto&& B) -> const char* {
               thread_local eomrt::LinearizationWorkspace<Model, double> ws;
               const typename Types::Coordinates q = x.q, qd = x.qd;
               const typename Types::Inputs u = x.u;
               const eomrt::DynamicsStatus status = eomrt::linearization<Model>(*x.c, ws, x.t, q, qd, u);
               if (status != eomrt::DynamicsStatus::ok) return dynamics_failure(status);
               A = ws.A;
               B = ws.B;
               return nullptr;
             });
}

namespace detail {

/// A state argument of 2 nq finite entries, as the runtime's State.
template <class Model>
typename eomrt::ModelTypes<Model, double>::State state_argument(py::handle value, const ArgumentName& name) {
  Argument a;
  read_vector(value, 2 * Model::nq, name, a);
  if (a.batch >= 0)
    throw py::value_error(name.text() + ": expected one state of shape (" + std::to_string(2 * Model::nq) +
                          ",), got a batch");
  typename eomrt::ModelTypes<Model, double>::State x;
  for (int k = 0; k < 2 * Model::nq; ++k) x(k) = a.data[k * a.inner];
  if (!x.allFinite()) throw py::value_error(name.text() + ": expected finite numbers, got NaN or infinity");
  return x;
}

/// The constraint an assembly could not satisfy.
template <class Model>
std::string worst_constraint(const eomrt::AssemblyReport<double>& report) {
  if (report.worst_row < 0 || report.worst_row >= Model::nc) return "?";
  return Model::constraint_names[static_cast<std::size_t>(report.worst_row)];
}

/// The held entries of an assembly: a sequence of state names ("theta", "theta_dot").
template <class Model>
eomrt::HeldEntries<Model> held_entries(py::handle given, py::object error) {
  eomrt::HeldEntries<Model> held = eomrt::HeldEntries<Model>::Constant(false);
  if (given.is_none()) return held;
  if (py::isinstance<py::str>(given))
    throw py::type_error("assemble(): given: expected a sequence of names, got a string");
  for (py::handle item : given) {
    const std::string name = py::str(item);
    int k = -1;
    for (int i = 0; i < Model::nq; ++i) {
      if (name == Model::coordinate_names[static_cast<std::size_t>(i)]) k = i;
      if (name == std::string(Model::coordinate_names[static_cast<std::size_t>(i)]) + "_dot") k = Model::nq + i;
    }
    if (k < 0) {
      std::string names;
      for (const char* c : Model::coordinate_names) names += (names.empty() ? "" : ", ") + std::string(c);
      PyErr_SetString(error.ptr(), ("assemble(): given: " + std::string(Model::name) + " has no coordinate or rate '" +
                                    name + "'; its coordinates: " + names + " (rates: the same with _dot)")
                                       .c_str());
      throw py::error_already_set();
    }
    held(k) = true;
  }
  return held;
}

/// The parameters of a call that needs Parameters (simulate), from Parameters, Constants or None.
template <class Model>
typename Model::template Parameters<double> parameters_of(py::handle p, const char* function) {
  using Set = ParameterSet<Model>;
  if (p.is_none()) return Set().values();
  if (py::isinstance<Set>(p)) return p.cast<const Set&>().values();
  if (py::isinstance<typename Set::Constants>(p)) return p.cast<const typename Set::Constants&>().parameters();
  throw py::type_error(std::string(function) + "(): p: expected " + Model::name + ".Parameters or " + Model::name +
                       ".Constants (or None for the defaults), got an object of type " +
                       std::string(py::str(py::type::handle_of(p).attr("__name__"))));
}

/// A positive, finite number option of simulate(), or nullopt for None.
inline std::optional<double> positive_option(py::handle value, const char* name) {
  if (value.is_none()) return std::nullopt;
  const double v = detail::parameter_value(value, name);
  if (!(v > 0)) throw py::value_error(std::string("simulate(): ") + name + ": expected a number above 0, got " + std::to_string(v));
  return v;
}

inline std::string integrator_list(bool adaptive) {
  std::string s;
  for (const eomrt::IntegratorInfo& info : eomrt::integrators)
    if (info.adaptive == adaptive) s += (s.empty() ? "" : ", ") + std::string(info.name);
  return s;
}

/// The options of simulate(), checked as `eomgen simulate` checks its command line.
inline eomrt::SimulationOptions<double> simulation_options(double t0, double t_end, py::handle method, py::handle dt,
                                                           py::handle rtol, py::handle atol, py::handle sample,
                                                           const std::string& solver,
                                                           const std::string& stabilization) {
  eomrt::SimulationOptions<double> o;
  if (!std::isfinite(t0) || !std::isfinite(t_end) || !(t_end >= t0))
    throw py::value_error("simulate(): expected finite times with t_end >= t0, got t0 = " + std::to_string(t0) +
                          ", t_end = " + std::to_string(t_end));
  o.t0 = t0;
  o.t_end = t_end;
  const std::optional<double> step = positive_option(dt, "dt"), r = positive_option(rtol, "rtol"),
                              interval = positive_option(sample, "sample");
  std::optional<double> a;
  if (!atol.is_none()) {
    a = detail::parameter_value(atol, "atol");
    if (*a < 0) throw py::value_error("simulate(): atol: expected a number >= 0");
  }
  const eomrt::IntegratorInfo* info = nullptr;
  if (method.is_none()) {
    info = eomrt::find_integrator(step ? eomrt::default_fixed_step_integrator : eomrt::default_integrator);
  } else {
    const std::string name = py::str(method);
    info = eomrt::find_integrator(std::string_view(name));
    if (info == nullptr)
      throw py::value_error("simulate(): method: expected one of " + integrator_list(false) + ", " +
                            integrator_list(true) + ", got '" + name + "'");
  }
  if (info->adaptive && step)
    throw py::value_error(std::string("simulate(): dt: ") + info->name + " chooses its own steps; give rtol, or a " +
                          "fixed-step method (" + integrator_list(false) + ")");
  if (!info->adaptive && (r || a))
    throw py::value_error(std::string("simulate(): rtol/atol: ") + info->name + " takes fixed steps; give dt");
  if (!info->adaptive && !step)
    throw py::value_error(std::string("simulate(): ") + info->name + " takes fixed steps: give dt");
  o.integrator = info->method;
  if (step) o.step = *step;
  if (r) o.adaptive.rtol = *r;
  if (a) o.adaptive.atol = *a;
  if (solver == "kkt")
    o.solver = eomrt::ConstraintSolver::kkt;
  else if (solver == "null-space")
    throw py::value_error("simulate(): solver: the module runs the KKT system only; `eomgen simulate --solver "
                          "null-space` runs the null-space method");
  else
    throw py::value_error("simulate(): solver: expected 'kkt', got '" + solver + "'");
  if (stabilization == "projection")
    o.stabilization = eomrt::Stabilization::projection;
  else if (stabilization == "baumgarte")
    o.stabilization = eomrt::Stabilization::baumgarte;
  else if (stabilization == "none")
    o.stabilization = eomrt::Stabilization::none;
  else
    throw py::value_error("simulate(): stabilization: expected 'projection', 'baumgarte' or 'none', got '" +
                          stabilization + "'");
  o.sample_interval = interval ? *interval : eomrt::default_sample_interval(o);
  try {
    eomrt::detail::check_options(o);
  } catch (const std::invalid_argument& e) {
    throw py::value_error(std::string("simulate(): ") + e.what());
  }
  return o;
}

/// The inputs of a simulation: constant, or a Python callable u(t, x) -> array of nu. A
/// callable's exception ends the run (the inputs become NaN, so the state does) and is raised
/// again when simulate() returns.
template <class Model>
struct SimulationInputs {
  using Types = eomrt::ModelTypes<Model, double>;
  typename Types::Inputs constant = Types::Inputs::Zero();
  py::object callable;
  std::optional<py::error_already_set> error;
  std::string shape_error;

  template <class State, class Inputs>
  void operator()(double t, const State& x, Inputs& u) {
    if (!callable) {
      u = constant;
      return;
    }
    if (error || !shape_error.empty()) {
      u.setConstant(std::numeric_limits<double>::quiet_NaN());
      return;
    }
    try {
      py::array_t<double> state(2 * Model::nq);
      for (int k = 0; k < 2 * Model::nq; ++k) state.mutable_data()[k] = x(k);
      const py::object value = callable(t, state);
      Argument a;
      read_vector(value, Model::nu, ArgumentName{"simulate", "u(t, x)"}, a);
      if (a.batch >= 0) throw py::value_error("simulate(): u(t, x): expected one value of shape (" +
                                              std::to_string(Model::nu) + ",), got a batch");
      for (int k = 0; k < Model::nu; ++k) u(k) = a.data[k * a.inner];
    } catch (py::error_already_set& e) {
      error.emplace(std::move(e));
      u.setConstant(std::numeric_limits<double>::quiet_NaN());
    } catch (const std::exception& e) {  // a pybind11 builtin_exception from read_vector
      shape_error = e.what();
      u.setConstant(std::numeric_limits<double>::quiet_NaN());
    }
  }
};

}  // namespace detail

/// simulate(t_end, x0, p=None, u=None, *, t0=0, method=None, dt=None, rtol=None, atol=None,
/// sample=None, solver="kkt", stabilization="projection") -> (t, x)
template <class Model>
void define_simulate(py::module_& m) {
  using Types = eomrt::ModelTypes<Model, double>;
  const py::object simulation_error = m.attr("SimulationError");
  m.def(
      "simulate",
      [simulation_error](double t_end, py::handle x0, py::handle p, py::handle u, double t0, py::handle method,
                         py::handle dt, py::handle rtol, py::handle atol, py::handle sample, const std::string& solver,
                         const std::string& stabilization) {
        const eomrt::SimulationOptions<double> options =
            detail::simulation_options(t0, t_end, method, dt, rtol, atol, sample, solver, stabilization);
        const typename Model::template Parameters<double> parameters = detail::parameters_of<Model>(p, "simulate");
        typename Types::State x = detail::state_argument<Model>(x0, ArgumentName{"simulate", "x0"});
        detail::SimulationInputs<Model> inputs;
        if (!u.is_none() && PyCallable_Check(u.ptr())) {
          inputs.callable = py::reinterpret_borrow<py::object>(u);
        } else if (!u.is_none()) {
          Argument a;
          read_vector(u, Model::nu, ArgumentName{"simulate", "u"}, a);
          if (a.batch >= 0) throw py::value_error("simulate(): u: expected constant inputs or a callable u(t, x)");
          for (int k = 0; k < Model::nu; ++k) inputs.constant(k) = a.data[k * a.inner];
          if (!inputs.constant.allFinite()) throw py::value_error("simulate(): u: expected finite numbers");
        }
        // the start on the constraints, as eomgen simulate makes it with every value given
        if constexpr (Model::nc > 0) {
          const eomrt::AssemblyReport<double> report = eomrt::assemble<Model>(
              parameters, options.t0, x, eomrt::HeldEntries<Model>::Constant(true));
          if (report.status == eomrt::AssemblyStatus::unreachable ||
              report.status == eomrt::AssemblyStatus::non_finite)
            throw py::value_error(std::string("simulate(): x0: no start near it satisfies the constraint '") +
                                  detail::worst_constraint<Model>(report) + "' (" +
                                  eomrt::describe(report.status) + ")");
        }
        std::vector<double> times, states;
        const auto observe = [&](const eomrt::Sample<Model, double>& s) {
          times.push_back(s.t);
          states.insert(states.end(), s.q.data(), s.q.data() + Model::nq);
          states.insert(states.end(), s.qd.data(), s.qd.data() + Model::nq);
        };
        eomrt::SimulationResult<Model, double> result;
        if (inputs.callable) {
          result = eomrt::simulate_with<ModuleMethods, Model>(parameters, x, options, inputs, observe);
        } else {
          py::gil_scoped_release release;  // nothing below touches Python
          result = eomrt::simulate_with<ModuleMethods, Model>(parameters, x, options, inputs, observe);
        }
        if (inputs.error) throw std::move(*inputs.error);
        if (!inputs.shape_error.empty()) throw py::value_error(inputs.shape_error);
        const auto n = static_cast<py::ssize_t>(times.size());
        py::array_t<double> t_array(n), x_array(std::vector<py::ssize_t>{n, 2 * Model::nq});
        std::copy(times.begin(), times.end(), t_array.mutable_data());
        std::copy(states.begin(), states.end(), x_array.mutable_data());
        if (result.status != eomrt::SimulationStatus::ok) {
          py::object error = simulation_error(std::string("simulate(): stopped at t = ") +
                                              std::to_string(result.failure_time) + " s: " +
                                              eomrt::describe(result.status));
          error.attr("t") = t_array;
          error.attr("x") = x_array;
          error.attr("failure_time") = result.failure_time;
          error.attr("status") = eomrt::to_string(result.status);
          PyErr_SetObject(simulation_error.ptr(), error.ptr());
          throw py::error_already_set();
        }
        return py::make_tuple(t_array, x_array);
      },
      py::arg("t_end"), py::arg("x0"), py::arg("p") = py::none(), py::arg("u") = py::none(), py::kw_only(),
      py::arg("t0") = 0.0, py::arg("method") = py::none(), py::arg("dt") = py::none(), py::arg("rtol") = py::none(),
      py::arg("atol") = py::none(), py::arg("sample") = py::none(), py::arg("solver") = "kkt",
      py::arg("stabilization") = "projection",
      "simulate(t_end, x0, p=None, u=None, *, t0=0, method=None, dt=None, rtol=None, atol=None, sample=None, "
      "solver='kkt', stabilization='projection') -> (t, x)\n\n"
      "Simulates from (t0, x0) to t_end with the runtime (eomrt::simulate): returns t (N,) and the states x (N, "
      "2 nq) at the samples (by default about 1000, as eomgen simulate writes). u: constant inputs, or a callable "
      "u(t, x) returning them. method: an integrator of eomgen simulate --method (default dp5, or rk4 with dt). "
      "A constrained model's x0 is first brought onto the constraints, the least each value must move. A run that "
      "fails raises SimulationError, whose t and x hold the samples up to the failure.");
}

/// assemble(x, given=None, t=0, p=None) -> x on the constraints: the consistent state nearest x,
/// holding the entries named in `given` (eomrt::assemble; docs/conventions.md, Assembly).
template <class Model>
void define_assemble(py::module_& m) {
  using Types = eomrt::ModelTypes<Model, double>;
  const py::object error = m.attr("UnknownNameError");
  m.def(
      "assemble",
      [error](py::handle x_value, py::handle given, double t, py::handle p) {
        typename Types::State x = detail::state_argument<Model>(x_value, ArgumentName{"assemble", "x"});
        const eomrt::HeldEntries<Model> held = detail::held_entries<Model>(given, error);
        const typename Model::template Parameters<double> parameters = detail::parameters_of<Model>(p, "assemble");
        if (!std::isfinite(t)) throw py::value_error("assemble(): t: expected a finite number");
        const eomrt::AssemblyReport<double> report = eomrt::assemble<Model>(parameters, t, x, held);
        switch (report.status) {
          case eomrt::AssemblyStatus::ok:
          case eomrt::AssemblyStatus::held_values_moved:
            break;
          case eomrt::AssemblyStatus::unreachable:
          case eomrt::AssemblyStatus::non_finite:
            throw py::value_error(std::string("assemble(): no state near x satisfies the constraint '") +
                                  detail::worst_constraint<Model>(report) + "': " +
                                  eomrt::describe(report.status));
        }
        py::array_t<double> out(2 * Model::nq);
        std::copy(x.data(), x.data() + 2 * Model::nq, out.mutable_data());
        return out;
      },
      py::arg("x"), py::arg("given") = py::none(), py::arg("t") = 0.0, py::arg("p") = py::none(),
      "assemble(x, given=None, t=0, p=None) -> x\n\n"
      "The state on the constraints nearest x (each coordinate weighted by sqrt(M_jj)), holding the coordinates "
      "and rates named in `given` where the constraints allow (docs/conventions.md, Assembly). A model without "
      "constraints returns x.");
}

}  // namespace eompy
