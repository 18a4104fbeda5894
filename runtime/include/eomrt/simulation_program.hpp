#pragma once
/// \file
/// The program `eomgen simulate` compiles for a model: simulation_main<Model>(argc, argv)
/// reads the run's settings from the command line, simulates, and writes one CSV row per
/// sample. It needs a generated model (names, parameter defaults), the runtime and POSIX
/// (isatty for the progress line); eomgen passes it well-formed arguments, but it checks them
/// again so that it can be run by hand:
///
///   program --t-end T [--method euler|rk4|dp5] [--dt H] [--rtol R] [--atol A] [--sample S]
///           [--solver kkt|null-space] [--stabilization projection|baumgarte|none]
///           [--set p=v]... [--init q=v | q_dot=v]... [--input u=v]... --csv FILE [--progress]
///
/// Exit status: 0 success; 1 the simulation failed (the message gives the time, the reason
/// and the last good state; the CSV is then incomplete and the caller discards it); 2 usage.
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "eomrt/simulate.hpp"

namespace eomrt {

namespace detail {

/// A malformed command line of the simulation program.
class ProgramUsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

inline double parse_number(const std::string& text, const std::string& what) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v))
    throw ProgramUsageError(what + ": '" + text + "' is not a finite number");
  return v;
}

template <std::size_t N>
std::string name_list(const std::array<const char*, N>& names, const char* suffix = "") {
  std::string out;
  for (std::size_t i = 0; i < N; ++i) out += (i ? ", " : "") + std::string(names[i]) + suffix;
  return N == 0 ? std::string("none") : out;
}

template <std::size_t N>
int index_of(const std::array<const char*, N>& names, const std::string& name) {
  for (std::size_t i = 0; i < N; ++i)
    if (name == names[i]) return static_cast<int>(i);
  return -1;
}

/// "name=value" split at the first '='
inline std::pair<std::string, double> assignment(const std::string& item, const std::string& option) {
  const auto eq = item.find('=');
  if (eq == std::string::npos || eq == 0)
    throw ProgramUsageError(option + ": expected NAME=VALUE, got '" + item + "'");
  return {item.substr(0, eq), parse_number(item.substr(eq + 1), option + " " + item.substr(0, eq))};
}

/// Prints %.17g: enough digits to read every double back exactly.
inline void put_number(std::FILE* f, double v) { std::fprintf(f, "%.17g", v); }

/// One line of progress on a terminal, redrawn at most 10 times a second.
class ProgressLine {
 public:
  ProgressLine(bool enabled, double t0, double t_end) : enabled_(enabled), t0_(t0), t_end_(t_end) {}
  void update(double t) {
    if (!enabled_) return;
    const auto now = std::chrono::steady_clock::now();
    if (drawn_ && now - last_ < std::chrono::milliseconds(100)) return;
    last_ = now;
    drawn_ = true;
    const double fraction = t_end_ > t0_ ? (t - t0_) / (t_end_ - t0_) : 1.0;
    const int filled = static_cast<int>(fraction * 30);
    std::fprintf(stderr, "\r  [%-30.*s] %3d%%  t = %.4g s", filled, "==============================",
                 static_cast<int>(fraction * 100), t);
    std::fflush(stderr);
  }
  void finish() {
    if (enabled_ && drawn_) std::fprintf(stderr, "\r%60s\r", "");
  }

 private:
  bool enabled_;
  double t0_, t_end_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point last_;
};

}  // namespace detail

/// Runs a simulation of Model as described in the file comment.
/// \return the exit status (0, 1 or 2)
template <class Model>
int simulation_main(int argc, char** argv) {
  using Types = ModelTypes<Model, double>;
  using State = typename Types::State;
  constexpr int nq = Model::nq;
  try {
    SimulationOptions<double> options;
    options.t_end = std::numeric_limits<double>::quiet_NaN();
    typename Types::Parameters p;
    State x0 = State::Zero();
    typename Types::Inputs u_constant = Types::Inputs::Zero();
    std::string csv_path;
    bool progress = false, step_given = false;
    const auto parameter_fields = p.fields();

    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      const auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw detail::ProgramUsageError(arg + ": expected a value");
        return argv[++i];
      };
      if (arg == "--t-end") {
        options.t_end = detail::parse_number(value(), arg);
      } else if (arg == "--method") {
        const std::string m = value();
        if (m == "euler") options.integrator = Integrator::euler;
        else if (m == "rk4") options.integrator = Integrator::rk4;
        else if (m == "dp5") options.integrator = Integrator::dormand_prince;
        else throw detail::ProgramUsageError("--method: expected euler, rk4 or dp5, got '" + m + "'");
      } else if (arg == "--dt") {
        options.step = detail::parse_number(value(), arg);
        step_given = true;
      } else if (arg == "--rtol") {
        options.adaptive.rtol = detail::parse_number(value(), arg);
      } else if (arg == "--atol") {
        options.adaptive.atol = detail::parse_number(value(), arg);
      } else if (arg == "--sample") {
        options.sample_interval = detail::parse_number(value(), arg);
      } else if (arg == "--solver") {
        const std::string s = value();
        if (s == "kkt") options.solver = ConstraintSolver::kkt;
        else if (s == "null-space") options.solver = ConstraintSolver::null_space;
        else throw detail::ProgramUsageError("--solver: expected kkt or null-space, got '" + s + "'");
      } else if (arg == "--stabilization") {
        const std::string s = value();
        if (s == "projection") options.stabilization = Stabilization::projection;
        else if (s == "baumgarte") options.stabilization = Stabilization::baumgarte;
        else if (s == "none") options.stabilization = Stabilization::none;
        else
          throw detail::ProgramUsageError("--stabilization: expected projection, baumgarte or none, got '" + s + "'");
      } else if (arg == "--set") {
        const auto [name, v] = detail::assignment(value(), arg);
        const int k = detail::index_of(Model::parameter_names, name);
        if (k < 0)
          throw detail::ProgramUsageError("--set: '" + name + "' is not a parameter; the model's parameters: " +
                                          detail::name_list(Model::parameter_names));
        *parameter_fields[static_cast<std::size_t>(k)] = v;
      } else if (arg == "--init") {
        const auto [name, v] = detail::assignment(value(), arg);
        int k = detail::index_of(Model::coordinate_names, name);
        if (k < 0 && name.size() > 4 && name.compare(name.size() - 4, 4, "_dot") == 0) {
          k = detail::index_of(Model::coordinate_names, name.substr(0, name.size() - 4));
          if (k >= 0) k += nq;
        }
        if (k < 0)
          throw detail::ProgramUsageError("--init: '" + name + "' is neither a coordinate nor a rate; expected one of " +
                                          detail::name_list(Model::coordinate_names) + " or " +
                                          detail::name_list(Model::coordinate_names, "_dot"));
        x0(k) = v;
      } else if (arg == "--input") {
        const auto [name, v] = detail::assignment(value(), arg);
        const int k = detail::index_of(Model::input_names, name);
        if (k < 0)
          throw detail::ProgramUsageError("--input: '" + name + "' is not an input; the model's inputs: " +
                                          detail::name_list(Model::input_names));
        u_constant(k) = v;
      } else if (arg == "--csv") {
        csv_path = value();
      } else if (arg == "--progress") {
        progress = true;
      } else {
        throw detail::ProgramUsageError("unknown argument '" + arg + "'");
      }
    }
    if (std::isnan(options.t_end)) throw detail::ProgramUsageError("--t-end is required");
    if (csv_path.empty()) throw detail::ProgramUsageError("--csv is required");
    if (step_given && options.integrator == Integrator::dormand_prince)
      throw detail::ProgramUsageError("--dt: dp5 chooses its own steps; give --rtol, or a fixed-step --method");
    if (options.sample_interval == 0) {
      // about 1000 rows; a fixed step keeps its exact size by sampling every k-th step
      const double target = (options.t_end - options.t0) / 1000;
      options.sample_interval =
          options.integrator == Integrator::dormand_prince
              ? target
              : options.step * std::max(1.0, std::round(target / options.step));
      if (!(options.sample_interval > 0)) options.sample_interval = 0;  // t_end == t0: one sample
    }

    std::FILE* csv = std::fopen(csv_path.c_str(), "w");
    if (csv == nullptr) {
      std::fprintf(stderr, "error: cannot write '%s': %s\n", csv_path.c_str(), std::strerror(errno));
      return 1;
    }
    // header: t, q, q_dot, lambda_c, inputs, T, V, T+V, phi_c, rate_residual_c, outputs
    std::fprintf(csv, "t");
    for (const char* n : Model::coordinate_names) std::fprintf(csv, ",%s", n);
    for (const char* n : Model::coordinate_names) std::fprintf(csv, ",%s_dot", n);
    for (const char* n : Model::constraint_names) std::fprintf(csv, ",lambda_%s", n);
    for (const char* n : Model::input_names) std::fprintf(csv, ",%s", n);
    std::fprintf(csv, ",T,V,T+V");
    for (int i = 0; i < Model::nh; ++i) std::fprintf(csv, ",phi_%s", Model::constraint_names[Model::holonomic_rows[i]]);
    for (const char* n : Model::constraint_names) std::fprintf(csv, ",rate_residual_%s", n);
    if constexpr (has_outputs_v<Model>)
      for (const char* n : Model::output_names) std::fprintf(csv, ",%s", n);
    std::fprintf(csv, "\n");

    detail::ProgressLine line(progress && ::isatty(STDERR_FILENO), options.t0, options.t_end);
    long long rows = 0;
    int bad_output = -1;  // the first output found not finite, and when
    double bad_output_time = 0;
    double energy0 = 0, max_energy_drift = 0, max_phi = 0, max_rate = 0;
    typename Types::HolonomicVector phi;
    const auto observer = [&](const Sample<Model, double>& s) {
      detail::put_number(csv, s.t);
      for (int i = 0; i < nq; ++i) std::fputc(',', csv), detail::put_number(csv, s.q(i));
      for (int i = 0; i < nq; ++i) std::fputc(',', csv), detail::put_number(csv, s.qd(i));
      for (int i = 0; i < Model::nc; ++i) std::fputc(',', csv), detail::put_number(csv, s.ws.lambda(i));
      for (int i = 0; i < Model::nu; ++i) std::fputc(',', csv), detail::put_number(csv, s.u(i));
      const double energy = s.kinetic_energy + s.potential_energy;
      for (const double v : {s.kinetic_energy, s.potential_energy, energy})
        std::fputc(',', csv), detail::put_number(csv, v);
      if constexpr (Model::nh > 0) {
        Model::holonomic_residuals(s.t, s.q, p, phi);
        for (int i = 0; i < Model::nh; ++i) std::fputc(',', csv), detail::put_number(csv, phi(i));
      }
      // ws holds Xi qd + Xi_t at this sample (constraint_residuals evaluated it last)
      for (int i = 0; i < Model::nc; ++i) std::fputc(',', csv), detail::put_number(csv, s.ws.velocity_residual(i));
      if constexpr (has_outputs_v<Model>) {
        Eigen::Matrix<double, Model::ny, 1> y;
        Model::outputs(s.t, s.q, s.qd, s.u, p, y);
        for (int i = 0; i < Model::ny; ++i) std::fputc(',', csv), detail::put_number(csv, y(i));
        // the state is fine (simulate checks it) but an output can still leave its domain
        for (int i = 0; i < Model::ny && bad_output < 0; ++i)
          if (!std::isfinite(y(i))) bad_output = i, bad_output_time = s.t;
      }
      std::fputc('\n', csv);
      if (rows++ == 0) energy0 = energy;
      max_energy_drift = std::max(max_energy_drift, std::abs(energy - energy0));
      max_phi = std::max(max_phi, s.residuals.position);
      max_rate = std::max(max_rate, s.residuals.velocity);
      line.update(s.t);
    };
    const auto inputs = [&u_constant](double, const State&, typename Types::Inputs& u) { u = u_constant; };

    const auto start = std::chrono::steady_clock::now();
    const SimulationResult<Model, double> r = simulate<Model>(p, x0, options, inputs, observer);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    line.finish();
    const bool written = std::fclose(csv) == 0;

    if (r.status != SimulationStatus::ok) {
      std::fprintf(stderr, "error: the simulation stopped at t = %.17g s: %s\n", r.failure_time,
                   describe(r.status));
      std::fprintf(stderr, "  last good state, at t = %.17g s:\n", r.t);
      for (int i = 0; i < nq; ++i)
        std::fprintf(stderr, "    %s = %.17g, %s_dot = %.17g\n", Model::coordinate_names[i], r.x(i),
                     Model::coordinate_names[i], r.x(nq + i));
      if constexpr (Model::nc > 0) {
        if (r.failure_time == options.t0) {
          // the usual cause: coordinates left at 0 where the constraints do not hold
          DynamicsWorkspace<Model, double> ws;
          const typename Types::Coordinates q = x0.template head<nq>(), qd = x0.template tail<nq>();
          const ConstraintResiduals<double> res = constraint_residuals<Model, double>(p, ws, options.t0, q, qd);
          std::fprintf(stderr,
                       "  at the initial state max |phi| = %.3g and max |Xi qd + Xi_t| = %.3g: give coordinates "
                       "(and rates) that satisfy the constraints with --init\n",
                       res.position, res.velocity);
        }
      }
      return 1;
    }
    if constexpr (has_outputs_v<Model>) {
      if (bad_output >= 0) {
        std::fprintf(stderr, "error: the output %s is not a finite number at t = %.17g s\n",
                     Model::output_names[static_cast<std::size_t>(bad_output)], bad_output_time);
        return 1;
      }
    }
    if (!written) {
      std::fprintf(stderr, "error: writing '%s' failed: %s\n", csv_path.c_str(), std::strerror(errno));
      return 1;
    }
    std::printf("simulated %s from t = %g to %g s with %s", Model::name, options.t0, options.t_end,
                to_string(options.integrator));
    if (options.integrator == Integrator::dormand_prince)
      std::printf(" (rtol %g, atol %g): %lld steps, %lld rejected", options.adaptive.rtol,
                  options.adaptive.atol, r.steps, r.rejected_steps);
    else
      std::printf(" (dt %g): %lld steps", options.step, r.steps);
    std::printf(", %lld evaluations, %.3g s\n", r.evaluations, seconds);
    std::printf("energy T+V: %.10g at t0, max |change| %.3g (relative %.3g)\n", energy0, max_energy_drift,
                energy0 != 0 ? max_energy_drift / std::abs(energy0) : max_energy_drift);
    if constexpr (Model::nc > 0)
      std::printf("constraint residuals: max |phi| %.3g, max |Xi qd + Xi_t| %.3g\n", max_phi, max_rate);
    std::printf("rows: %lld\n", rows);
    return 0;
  } catch (const detail::ProgramUsageError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
}

}  // namespace eomrt
