#pragma once
/// \file
/// The sample grid a simulation takes when its caller gives none: about 1000 samples over the
/// run, as `eomgen simulate` writes its CSV rows and a Python module's simulate() returns them.
#include <algorithm>
#include <cmath>

#include "eomrt/integrators.hpp"

namespace eomrt {

template <class Scalar>
struct SimulationOptions;

/// The interval of about 1000 samples from o.t0 to o.t_end; with a fixed step, a whole number
/// of steps (at least one), so every sample falls on a step. 0 (every step) for an empty span.
template <class Scalar>
Scalar default_sample_interval(const SimulationOptions<Scalar>& o) {
  using std::max;
  using std::round;
  const Scalar target = (o.t_end - o.t0) / Scalar(1000);
  const Scalar interval = is_adaptive(o.integrator) ? target : o.step * max(Scalar(1), round(target / o.step));
  return interval > 0 ? interval : Scalar(0);
}

}  // namespace eomrt
