#pragma once
// dqdd/dq, dqdd/dqd and dqdd/du of an unconstrained model's forward dynamics, for the header's
// forward_dynamics_derivatives (header_functions.hpp says which forms there are).
#include <ginac/ginac.h>

#include <vector>

#include "eomgen/derivation/header_functions.hpp"
#include "eomgen/derivation/linearization.hpp"

namespace eomgen {

/// What the derivatives are taken from: M and F as the header computes them, the sets of
/// intermediates they refer to, the linearization's K, D, B_u (at the symbols qdd), and the
/// recursive forward dynamics where the model has one.
struct ForwardDynamicsSources {
  const GiNaC::matrix& mass_matrix;
  const GiNaC::matrix& forcing;
  std::vector<const Subexpressions*> intermediates;  ///< every set M, F and fd refer to
  const SymbolicLinearization& linearization;
  const ForwardDynamics* forward_dynamics = nullptr;
};

/// The derivatives in each form the model admits, keeping the one of fewer estimated
/// operations (the other's estimate stays in form.estimated_operations_other, NaN where the
/// model has no recursive forward dynamics).
/// \pre the model has no constraints
/// \throws DerivationError if an expression of the forward dynamics cannot be differentiated
ForwardDynamicsDerivatives derive_forward_dynamics_derivatives(const Variables& variables,
                                                               const ForwardDynamicsSources& sources);

}  // namespace eomgen
