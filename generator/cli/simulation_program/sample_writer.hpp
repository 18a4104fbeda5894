#pragma once
// The CSV the simulation program writes, one row per sample, and what it keeps of the samples
// for its summary: the energy drift, the largest constraint residuals, the first output that
// is not a finite number.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "eomrt/simulate.hpp"

namespace eomgen::simulation_program {

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
    std::fprintf(stderr, "\r  [%-30.*s] %3d%%  t = %.4g s", filled,
                 "==============================", static_cast<int>(fraction * 100), t);
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

/// Writes the header: t, q, q_dot, lambda_c, inputs, T, V, T+V, phi_c, rate_residual_c, outputs.
/// \p csv_outputs: how many output components go to the CSV (the others, when there are, are
/// the animation's recording and go to the scene file)
template <class Model>
void write_csv_header(std::FILE* csv, int csv_outputs) {
  std::fprintf(csv, "t");
  for (const char* n : Model::coordinate_names) std::fprintf(csv, ",%s", n);
  for (const char* n : Model::coordinate_names) std::fprintf(csv, ",%s_dot", n);
  for (const char* n : Model::constraint_names) std::fprintf(csv, ",lambda_%s", n);
  for (const char* n : Model::input_names) std::fprintf(csv, ",%s", n);
  std::fprintf(csv, ",T,V,T+V");
  for (int i = 0; i < Model::nh; ++i) std::fprintf(csv, ",phi_%s", Model::constraint_names[Model::holonomic_rows[i]]);
  for (const char* n : Model::constraint_names) std::fprintf(csv, ",rate_residual_%s", n);
  if constexpr (eomrt::has_outputs_v<Model>)
    for (int i = 0; i < csv_outputs; ++i) std::fprintf(csv, ",%s", Model::output_names[static_cast<std::size_t>(i)]);
  std::fprintf(csv, "\n");
}

/// The observer of simulate(): writes each sample as a row (%.17g, enough digits to read every
/// double back exactly) and keeps the summary's statistics.
template <class Model>
class SampleWriter {
 public:
  using Types = eomrt::ModelTypes<Model, double>;

  /// \p scene: where the animation's samples go, null when there is none: per sample a line of
  /// t, q, lambda, T, V and the output components from \p csv_outputs on (the recording of
  /// scene_recording.hpp), in %.9g (positions to a nanometre in a metre)
  SampleWriter(std::FILE* csv, const typename Types::Parameters& p, ProgressLine progress, int csv_outputs,
               std::FILE* scene)
      : csv_(csv), p_(p), progress_(progress), csv_outputs_(csv_outputs), scene_(scene) {}

  void operator()(const eomrt::Sample<Model, double>& s) {
    put(s.t);
    for (int i = 0; i < Model::nq; ++i) next(s.q(i));
    for (int i = 0; i < Model::nq; ++i) next(s.qd(i));
    for (int i = 0; i < Model::nc; ++i) next(s.ws.lambda(i));
    for (int i = 0; i < Model::nu; ++i) next(s.u(i));
    const double energy = s.kinetic_energy + s.potential_energy;
    for (const double v : {s.kinetic_energy, s.potential_energy, energy}) next(v);
    if constexpr (Model::nh > 0) {
      Model::holonomic_residuals(s.t, s.q, p_, phi_);
      for (int i = 0; i < Model::nh; ++i) next(phi_(i));
    }
    // ws holds Xi qd + Xi_t at this sample (constraint_residuals evaluated it last)
    for (int i = 0; i < Model::nc; ++i) next(s.ws.velocity_residual(i));
    if constexpr (eomrt::has_outputs_v<Model>) write_outputs(s);
    std::fputc('\n', csv_);
    if (rows_++ == 0) energy0_ = energy;
    max_energy_drift_ = std::max(max_energy_drift_, std::abs(energy - energy0_));
    max_phi_ = std::max(max_phi_, s.residuals.position);
    max_rate_ = std::max(max_rate_, s.residuals.velocity);
    progress_.update(s.t);
  }

  /// clears the progress line, so that messages start on a clean line
  void finish() { progress_.finish(); }

  long long rows() const { return rows_; }
  double energy0() const { return energy0_; }
  double max_energy_drift() const { return max_energy_drift_; }
  double max_phi() const { return max_phi_; }
  double max_rate() const { return max_rate_; }
  /// the first output found not finite (-1: none), and when
  int bad_output() const { return bad_output_; }
  double bad_output_time() const { return bad_output_time_; }

 private:
  void put(double v) { std::fprintf(csv_, "%.17g", v); }
  void next(double v) {
    std::fputc(',', csv_);
    put(v);
  }

  void write_outputs(const eomrt::Sample<Model, double>& s) {
    Eigen::Matrix<double, Model::ny, 1> y;
    Model::outputs(s.t, s.q, s.qd, s.u, p_, y);
    for (int i = 0; i < csv_outputs_; ++i) next(y(i));
    if (scene_ != nullptr) write_scene(s, y);
    // the state is fine (simulate checks it) but an output can still leave its domain
    // the recording only matters, and is only checked, when it is written
    for (int i = 0; i < (scene_ != nullptr ? Model::ny : csv_outputs_) && bad_output_ < 0; ++i)
      if (!std::isfinite(y(i))) bad_output_ = i, bad_output_time_ = s.t;
  }

  void write_scene(const eomrt::Sample<Model, double>& s, const Eigen::Matrix<double, Model::ny, 1>& y) {
    std::fprintf(scene_, "%.9g", s.t);
    for (int i = 0; i < Model::nq; ++i) std::fprintf(scene_, ",%.9g", s.q(i));
    for (int i = 0; i < Model::nc; ++i) std::fprintf(scene_, ",%.9g", s.ws.lambda(i));
    std::fprintf(scene_, ",%.9g,%.9g", s.kinetic_energy, s.potential_energy);
    for (int i = csv_outputs_; i < Model::ny; ++i) std::fprintf(scene_, ",%.9g", y(i));
    std::fputc('\n', scene_);
  }

  std::FILE* csv_;
  const typename Types::Parameters& p_;
  ProgressLine progress_;
  int csv_outputs_;
  std::FILE* scene_;
  typename Types::HolonomicVector phi_;
  long long rows_ = 0;
  int bad_output_ = -1;
  double bad_output_time_ = 0;
  double energy0_ = 0, max_energy_drift_ = 0, max_phi_ = 0, max_rate_ = 0;
};

}  // namespace eomgen::simulation_program
