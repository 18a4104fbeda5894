#pragma once
/// \file
/// Umbrella header of the eomrt runtime: include this to get every runtime algorithm, and all of
/// Eigen's dense module. The runtime's own headers include only the parts of Eigen they use (a
/// simulation program pays for every header it parses).
#include <Eigen/Dense>

#include "eomrt/tableau.hpp"
#include "eomrt/rhs.hpp"
#include "eomrt/rk_fixed.hpp"
#include "eomrt/rk_adaptive.hpp"
#include "eomrt/integrators.hpp"
#include "eomrt/model_traits.hpp"
#include "eomrt/status.hpp"
#include "eomrt/regularity.hpp"
#include "eomrt/lu_factorization.hpp"
#include "eomrt/pivoted_qr.hpp"
#include "eomrt/minimum_norm.hpp"
#include "eomrt/kkt_system.hpp"
#include "eomrt/workspace.hpp"
#include "eomrt/dynamics_unconstrained.hpp"
#include "eomrt/dynamics_kkt.hpp"
#include "eomrt/dynamics_null_space.hpp"
#include "eomrt/stabilization.hpp"
#include "eomrt/linearization.hpp"
#include "eomrt/step_derivatives.hpp"
#include "eomrt/inverse_dynamics_derivatives.hpp"
#include "eomrt/assembly.hpp"
