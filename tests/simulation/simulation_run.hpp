#pragma once
// The definition of run() (declared in simulation_helpers.hpp), for the translation units that
// instantiate it, one per model: EOMRT_TESTING_INSTANTIATE_RUN(Model, Inputs).
#include "simulation/simulation_helpers.hpp"

namespace eomrt::testing {

template <class Model, class InputFn>
Trajectory<Model> run(const State<Model>& x0, const SimulationOptions<double>& options, const Parameters<Model>& p,
                      InputFn input) {
  Trajectory<Model> tr;
  tr.result = simulate<Model>(p, x0, options, input, [&tr](const Sample<Model, double>& s) {
    tr.t.push_back(s.t);
    State<Model> x;
    x << s.q, s.qd;
    tr.x.push_back(x);
    tr.lambda.push_back(s.ws.lambda);
    tr.energy.push_back(s.kinetic_energy + s.potential_energy);
    tr.max_position_residual = std::max(tr.max_position_residual, s.residuals.position);
    tr.max_velocity_residual = std::max(tr.max_velocity_residual, s.residuals.velocity);
  });
  return tr;
}

}  // namespace eomrt::testing

#define EOMRT_TESTING_INSTANTIATE_RUN(MODEL, INPUTS)                                                          \
  template eomrt::testing::Trajectory<MODEL> eomrt::testing::run<MODEL, INPUTS>(                                \
      const eomrt::testing::State<MODEL>&, const eomrt::SimulationOptions<double>&,                             \
      const eomrt::testing::Parameters<MODEL>&, INPUTS);
