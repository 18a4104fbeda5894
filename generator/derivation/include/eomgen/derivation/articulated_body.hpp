#pragma once
// Forward dynamics by the articulated-body algorithm (Featherstone), specialized to one model
// symbolically: qdd(q, qd, t, u) as a shared expression graph whose size grows linearly with the
// number of links, for models whose coordinates map to a kinematic tree and that have no
// constraints. Spatial quantities of a link are 6-vectors (angular; linear) resolved in the
// link's frame, the linear part at its mass centre, with classical accelerations.
#include <ginac/ginac.h>

#include <optional>
#include <string>
#include <variant>

#include "eomgen/mechanics/mechanical_system.hpp"
#include "eomgen/symbolic/subexpressions.hpp"

namespace eomgen {

/// qdd of M qdd = F for a tree, in the form of fewer operations.
struct ForwardDynamics {
  /// articulated_body: the recursion, without M; mass_matrix: M and F by the composite-body
  /// recursions, then M's LDL^T factors (a leaf's rows first, so a branched tree fills in no
  /// more than its chains) and two substitutions, written out
  enum class Form { articulated_body, mass_matrix };
  Form form = Form::articulated_body;
  Subexpressions subexpressions{"a"};
  GiNaC::matrix accelerations;  ///< qdd, n x 1; refers to the intermediates of `subexpressions`
  /// The pivots of the LDL^T factors of every joint's D_i = S_i^T IA_i S_i, or of M: all
  /// positive exactly when the mass matrix is positive definite, so the generated code checks them.
  GiNaC::exvector pivots;
  /// operations per call (as estimated_operations counts them), and those of the other form
  double estimated_operations = 0, estimated_operations_other = 0;
};

/// The forward dynamics of the system, or why it has none (constraints, coordinates that do not
/// map to a tree of joints): a short reason for reports.
/// \throws DerivationError if an expression cannot be differentiated (as derive_equations).
/// \param form  that form, not the one of fewer operations (for tests and comparisons)
std::variant<ForwardDynamics, std::string> derive_forward_dynamics(
    const MechanicalSystem& system, std::optional<ForwardDynamics::Form> form = std::nullopt);

}  // namespace eomgen
