#pragma once
// dqdd/dq, dqdd/dqd and dqdd/du of an unconstrained model's forward dynamics, for the header's
// forward_dynamics_derivatives (header_functions.hpp says which forms there are).
#include <ginac/ginac.h>

#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "eomgen/mechanics/mechanical_system.hpp"

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

/// The derivatives in each form the model admits (the chain rule through the recursion where
/// it has one, Newton-Euler where its bodies form a tree), keeping the one of fewer estimated
/// operations; the first of them on a tie, so the choice is the same in every run. With `only`,
/// that form alone, or why the model does not admit it.
/// \pre the system has no constraints
/// \throws DerivationError if an expression cannot be differentiated
std::variant<ForwardDynamicsDerivatives, std::string> derive_forward_dynamics_derivatives(
    const MechanicalSystem& system, const ForwardDynamicsSources& sources,
    std::optional<ForwardDynamicsDerivatives::Form> only = std::nullopt);

}  // namespace eomgen
