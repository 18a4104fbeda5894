#pragma once
// Running a generated model through eomrt::simulate() and keeping what the tests look at.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <vector>

#include "eomrt/eomrt.hpp"
#include "eomrt/simulate.hpp"

namespace eomrt::testing {

template <class Model>
using State = typename ModelTypes<Model, double>::State;
template <class Model>
using Parameters = typename ModelTypes<Model, double>::Parameters;

/// x = [q; qd] from two lists in coordinate order.
template <class Model>
State<Model> make_state(std::initializer_list<double> q, std::initializer_list<double> qd) {
  EXPECT_EQ(q.size(), static_cast<std::size_t>(Model::nq));
  EXPECT_EQ(qd.size(), static_cast<std::size_t>(Model::nq));
  State<Model> x;
  std::copy(q.begin(), q.end(), x.data());
  std::copy(qd.begin(), qd.end(), x.data() + Model::nq);
  return x;
}

/// The samples of one simulation.
template <class Model>
struct Trajectory {
  SimulationResult<Model, double> result;
  std::vector<double> t;
  std::vector<State<Model>> x;
  std::vector<typename ModelTypes<Model, double>::ConstraintVector> lambda;
  std::vector<double> energy;      ///< T + V
  double max_position_residual = 0;
  double max_velocity_residual = 0;

  /// max over the samples of |E(t) - E(0)| / |E(0)|
  double relative_energy_drift() const {
    double drift = 0;
    for (double e : energy) drift = std::max(drift, std::abs(e - energy.front()));
    return drift / std::abs(energy.front());
  }
};

/// inputs that keep the knife edge and the quaternion body busy: a steady push and a
/// time-varying torque, so the constraints carry real load
struct WobblyInputs {
  template <class Scalar, class X, class U>
  void operator()(const Scalar& t, const X&, U& u) const {
    for (int i = 0; i < u.size(); ++i) u(i) = 0.3 * std::sin(1.7 * t + i) + 0.1 * i;
  }
};

/// Simulates `Model` from x0 and keeps every sample. Only declared here: each model's
/// simulation is compiled once, in its own translation unit (simulation_run.hpp, instantiated
/// for ZeroInputs and WobblyInputs by tests/CMakeLists.txt), instead of once in every test file
/// that runs it; a missing instantiation is a link error naming the model.
template <class Model, class InputFn = ZeroInputs>
Trajectory<Model> run(const State<Model>& x0, const SimulationOptions<double>& options,
                      const Parameters<Model>& p = {}, InputFn input = {});

/// Dormand-Prince 5(4) at the given tolerance, sampled every 10 ms.
inline SimulationOptions<double> adaptive(double t_end, double rtol) {
  SimulationOptions<double> o;
  o.integrator = Integrator::dormand_prince;
  o.t_end = t_end;
  o.adaptive.rtol = rtol;
  o.adaptive.atol = rtol * 1e-2;
  o.sample_interval = 0.01;
  return o;
}

/// A fixed-step method, sampled every 10 ms.
inline SimulationOptions<double> fixed(Integrator method, double t_end, double step) {
  SimulationOptions<double> o;
  o.integrator = method;
  o.t_end = t_end;
  o.step = step;
  o.sample_interval = 0.01;
  return o;
}

}  // namespace eomrt::testing
