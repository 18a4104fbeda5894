#pragma once
// M and F of M qdd = F by the recursive algorithms of a kinematic tree, specialized to one model
// symbolically: M by the composite-rigid-body algorithm (O(n d) for depth d: n^2/2 entries of a
// chain) and F by the recursive Newton-Euler algorithm at qdd = 0 (O(n)). Beside Kane's closed
// form (equations_of_motion.hpp) it is an independent derivation of the same M and F, and the
// smaller one for long chains, whose closed-form entries grow with their depth. The same models
// as derive_forward_dynamics qualify: trees without constraints.
#include <ginac/ginac.h>

#include <string>
#include <variant>

#include "eomgen/mechanics/mechanical_system.hpp"
#include "eomgen/symbolic/subexpressions.hpp"

namespace eomgen {

/// M and F from the recursions, sharing the intermediates of `subexpressions`.
struct CompositeBodyEquations {
  Subexpressions subexpressions{"c"};
  GiNaC::matrix mass_matrix;  ///< n x n, symmetric
  GiNaC::matrix forcing;      ///< n x 1
  /// operations of the upper triangle of M and of F per call (as estimated_operations counts them)
  double estimated_operations = 0;
};

/// M and F from the recursions, bound to intermediates of a caller's Subexpressions.
struct RecursiveMassMatrixAndForcing {
  GiNaC::matrix mass_matrix;  ///< n x n, symmetric
  GiNaC::matrix forcing;      ///< n x 1
};

/// The recursive M and F of the system bound to `subexpressions` (derive_equations takes them for
/// long chains, beside its kinematics), or why it has none (the reason of derive_forward_dynamics).
/// \throws DerivationError if an expression cannot be differentiated (as derive_equations).
std::variant<RecursiveMassMatrixAndForcing, std::string> derive_composite_body_terms(const MechanicalSystem& system,
                                                                                     Subexpressions& subexpressions);

/// The recursive M and F of the system, or why it has none (the reason of
/// derive_forward_dynamics).
/// \throws DerivationError if an expression cannot be differentiated (as derive_equations).
std::variant<CompositeBodyEquations, std::string> derive_composite_body_equations(const MechanicalSystem& system);

}  // namespace eomgen
