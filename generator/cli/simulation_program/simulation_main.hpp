#pragma once
// The main() that `eomgen simulate` compiles around a generated model: the driver it writes is
//
//   #include "model.hpp"
//   #include "simulation_main.hpp"
//   int main(int argc, char** argv) {
//     return eomgen::simulation_program::simulation_main<eomgen_models::NAME::Model>(argc, argv);
//   }
//
// It reads the run's settings from the command line (run_settings.hpp), simulates with the
// runtime, writes one CSV row per sample (sample_writer.hpp) and prints a summary. It is not
// part of the runtime: it needs POSIX (isatty for the progress line) and is built only by
// eomgen, from the source tree or from share/eomgen/simulation_program when installed.
//
// Exit status: 0 success; 1 the simulation failed (the message gives the time, the reason and
// the last good state; the CSV is then incomplete and eomgen discards it); 2 a malformed
// argument (a bug in eomgen) or options simulate() rejects.
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>

#include "eomrt/assembly.hpp"
#include "eomrt/integrators.hpp"
#include "eomrt/simulate.hpp"
#include "run_settings.hpp"
#include "sample_writer.hpp"

namespace eomgen::simulation_program {

/// Explains a failed simulation on stderr: when, why, and the last good state; at the start of
/// a constrained model, how far the initial state is from the constraints.
template <class Model>
void report_failure(const RunSettings<Model>& run, const eomrt::SimulationResult<Model, double>& r) {
  constexpr int nq = Model::nq;
  std::fprintf(stderr, "error: the simulation stopped at t = %.17g s: %s\n", r.failure_time, eomrt::describe(r.status));
  std::fprintf(stderr, "  last good state, at t = %.17g s:\n", r.t);
  for (int i = 0; i < nq; ++i)
    std::fprintf(stderr, "    %s = %.17g, %s_dot = %.17g\n", Model::coordinate_names[i], r.x(i),
                 Model::coordinate_names[i], r.x(nq + i));
  if constexpr (Model::nc > 0) {
    if (r.failure_time == run.options.t0) {
      // the usual cause: coordinates left at 0 where the constraints do not hold
      using Types = eomrt::ModelTypes<Model, double>;
      eomrt::DynamicsWorkspace<Model, double> ws;
      const typename Types::Coordinates q = run.x0.template head<nq>(), qd = run.x0.template tail<nq>();
      const eomrt::ConstraintResiduals<double> res =
          eomrt::constraint_residuals<Model, double>(run.p, ws, run.options.t0, q, qd);
      std::fprintf(stderr,
                   "  at the initial state max |phi| = %.3g and max |Xi qd + Xi_t| = %.3g: give coordinates "
                   "(and rates) that satisfy the constraints with --init\n",
                   res.position, res.velocity);
    }
  }
}

/// Brings run.x0 onto the constraints (eomrt::assemble: the --init values kept, the rest solved
/// nearest their guesses) and says on stderr what the start became wherever it differs from
/// the request. \return false, with the reason on stderr, if no start near the request exists.
template <class Model>
bool assemble_start(RunSettings<Model>& run) {
  if constexpr (Model::nc == 0) {
    return true;
  } else {
    constexpr int nq = Model::nq;
    const typename RunSettings<Model>::Types::State request = run.x0;
    const eomrt::AssemblyReport<double> report = eomrt::assemble<Model>(run.p, run.options.t0, run.x0, run.held);
    switch (report.status) {
      case eomrt::AssemblyStatus::ok:
      case eomrt::AssemblyStatus::held_values_moved:
        break;
      case eomrt::AssemblyStatus::unreachable:
        std::fprintf(stderr,
                     "error: no start near the request satisfies the constraint '%s': the nearest the search came "
                     "leaves %s = %.3g; give --init values (and --guess values) near an assembly\n",
                     Model::constraint_names[static_cast<std::size_t>(report.worst_row)],
                     report.worst_is_position ? "phi" : "Xi qd + Xi_t", report.worst_residual);
        return false;
      case eomrt::AssemblyStatus::non_finite:
        std::fprintf(stderr, "error: the constraints' terms are not finite numbers near the requested start\n");
        return false;
    }
    bool any = false;
    for (int k = 0; k < 2 * nq; ++k) {
      if (run.x0(k) == request(k)) continue;
      if (!any)
        std::fprintf(stderr, "note: the start was brought onto the constraints (docs/conventions.md, Assembly):\n");
      any = true;
      const char* name = Model::coordinate_names[static_cast<std::size_t>(k % nq)];
      std::fprintf(stderr, "  %s%s = %.17g (%s %.17g, moved by %.3g)\n", name, k < nq ? "" : "_dot", run.x0(k),
                   run.held(k) ? "given" : "guess", request(k), run.x0(k) - request(k));
    }
    if (report.status == eomrt::AssemblyStatus::held_values_moved)
      std::fprintf(stderr, "  the given %s admit no consistent start: they moved too, each the least it must\n",
                   report.positions_released && report.rates_released ? "coordinates and rates"
                   : report.positions_released                        ? "coordinates"
                                                                      : "rates");
    return true;
  }
}

/// Prints what was simulated, with which method and at what cost, and the invariants' drift.
template <class Model>
void report_summary(const RunSettings<Model>& run, const eomrt::SimulationResult<Model, double>& r,
                    const SampleWriter<Model>& samples, double seconds) {
  const eomrt::SimulationOptions<double>& o = run.options;
  std::printf("simulated %s from t = %g to %g s with %s", Model::name, o.t0, o.t_end, eomrt::to_string(o.integrator));
  if (eomrt::is_adaptive(o.integrator))
    std::printf(" (rtol %g, atol %g): %lld steps, %lld rejected", o.adaptive.rtol, o.adaptive.atol, r.steps,
                r.rejected_steps);
  else
    std::printf(" (dt %g): %lld steps", o.step, r.steps);
  std::printf(", %lld evaluations, %.3g s\n", r.evaluations, seconds);
  const double drift = samples.max_energy_drift(), energy0 = samples.energy0();
  std::printf("energy T+V: %.10g at t0, max |change| %.3g (relative %.3g)\n", energy0, drift,
              energy0 != 0 ? drift / std::abs(energy0) : drift);
  if constexpr (Model::nc > 0)
    std::printf("constraint residuals: max |phi| %.3g, max |Xi qd + Xi_t| %.3g\n", samples.max_phi(),
                samples.max_rate());
  std::printf("rows: %lld\n", samples.rows());
}

/// Runs a simulation of Model as described in the file comment, with the methods of Methods
/// (eomrt::simulate_with): the others are not compiled.
/// \return the exit status (0, 1 or 2)
template <class Model, class Methods = eomrt::AllMethods>
int simulation_main(int argc, char** argv) {
  using Types = eomrt::ModelTypes<Model, double>;
  try {
    RunSettings<Model> run = parse_arguments<Model>(argc, argv);
    if (!assemble_start(run)) return 1;
    std::FILE* csv = std::fopen(run.csv_path.c_str(), "w");
    if (csv == nullptr) {
      std::fprintf(stderr, "error: cannot write '%s': %s\n", run.csv_path.c_str(), std::strerror(errno));
      return 1;
    }
    std::FILE* scene = nullptr;
    if (!run.scene_path.empty() && (scene = std::fopen(run.scene_path.c_str(), "w")) == nullptr) {
      std::fprintf(stderr, "error: cannot write '%s': %s\n", run.scene_path.c_str(), std::strerror(errno));
      std::fclose(csv);
      return 1;
    }
    const int csv_outputs = run.scene_first;
    write_csv_header<Model>(csv, csv_outputs);
    SampleWriter<Model> samples(
        csv, run.p, ProgressLine(run.progress && ::isatty(STDERR_FILENO), run.options.t0, run.options.t_end),
        csv_outputs, scene);
    const auto inputs = [&run](double, const typename Types::State&, typename Types::Inputs& u) { u = run.u; };

    const auto start = std::chrono::steady_clock::now();
    const eomrt::SimulationResult<Model, double> r =
        eomrt::simulate_with<Methods, Model>(run.p, run.x0, run.options, inputs, samples);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    samples.finish();
    const bool csv_written = std::fclose(csv) == 0;
    const bool written = (scene == nullptr || std::fclose(scene) == 0) && csv_written;

    if (r.status != eomrt::SimulationStatus::ok) {
      report_failure(run, r);
      return 1;
    }
    if constexpr (eomrt::has_outputs_v<Model>) {
      if (samples.bad_output() >= csv_outputs) {
        std::fprintf(stderr, "error: the animation's recording (a point's position or a frame's attitude) is not a "
                     "finite number at t = %.17g s\n", samples.bad_output_time());
        return 1;
      }
      if (samples.bad_output() >= 0) {
        std::fprintf(stderr, "error: the output %s is not a finite number at t = %.17g s\n",
                     Model::output_names[static_cast<std::size_t>(samples.bad_output())], samples.bad_output_time());
        return 1;
      }
    }
    if (!written) {
      std::fprintf(stderr, "error: writing '%s' failed: %s\n",
                   (run.scene_path.empty() ? run.csv_path : run.csv_path + "' or '" + run.scene_path).c_str(),
                   std::strerror(errno));
      return 1;
    }
    report_summary(run, r, samples, seconds);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
}

}  // namespace eomgen::simulation_program
