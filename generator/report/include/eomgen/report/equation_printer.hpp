#pragma once
// Renders a model's derived equations for people to read: plain text, a LaTeX document, or
// Markdown. Small systems are shown written out and simplified (the forms one derives by hand);
// large ones in terms of the shared intermediates, followed by their definitions in order,
// because writing those out grows exponentially with the length of a chain.
#include <cstddef>
#include <ostream>
#include <string>

#include "eomgen/derivation/equations_of_motion.hpp"
#include "eomgen/derivation/header_functions.hpp"
#include "eomgen/derivation/model_equations.hpp"

namespace eomgen {

enum class EquationFormat { text, latex, markdown };

/// Which parts of the equations to print; each flag is named after its key in
/// parse_equation_parts.
struct EquationParts {
  bool mass_matrix = true;           ///< "M"
  bool forcing = true;               ///< "F"
  bool constraint_jacobian = true;   ///< "Xi"
  bool constraint_rate_term = true;  ///< "Xi_t"
  bool constraint_acceleration_term = true;  ///< "b" = dXi/dt qd + dXi_t/dt
  bool holonomic_residuals = true;   ///< "phi"
  bool kinetic_energy = true;        ///< "T"
  bool potential_energy = true;      ///< "V"
  bool outputs = true;               ///< "outputs"
  // the functions for controllers (header_functions.hpp), printed only when selected
  bool inverse_dynamics = false;     ///< "tau": M qdd - F
  bool gravity_forces = false;       ///< "g": dV/dq
  bool coriolis_matrix = false;      ///< "C"
  bool output_jacobians = false;     ///< "J": every output Jacobian and its bias
  bool regressor = false;            ///< "regressor": Y and the inertial parameters pi
  /// Whether a part needs derive_header_functions (print_equations' `functions`).
  bool needs_header_functions() const {
    return inverse_dynamics || gravity_forces || coriolis_matrix || output_jacobians || regressor;
  }
};

/// Parses a comma-separated selection such as "M,F,b"; only the named parts are set.
/// \throws Error for an empty list or an unknown key; the message lists the accepted keys.
EquationParts parse_equation_parts(const std::string& list);

/// How intermediates of EquationsOfMotion::subexpressions are shown.
enum class IntermediateForm {
  automatic,    ///< written out unless the system is large (see PrintOptions)
  written_out,  ///< always written out and simplified (may be slow for long chains)
  shared,       ///< equations in terms of intermediates, then "where" with their definitions
};

struct PrintOptions {
  EquationFormat format = EquationFormat::text;
  EquationParts parts;
  IntermediateForm intermediates = IntermediateForm::automatic;
  /// automatic: use the shared form when the derivation has more intermediates than this...
  std::size_t max_intermediates = 400;
  /// ...or when the selected parts written out would have more expression nodes than this
  /// (a 4-link planar chain has about 13,000 and prints in well under a second; the
  /// simplification cost grows about tenfold per further link).
  double max_written_out_size = 20000;
  /// ...or when multiplying them out (as the written-out form does) would give more nodes than
  /// this, counted before like terms combine: the tree size misses products of sums (the
  /// bicycle's kinetic energy, a few thousand nodes, multiplies out to 340 KB of text and took
  /// 5 s; the universal chain's, estimated at 3 million, prints in 0.3 s).
  double max_multiplied_out_size = 1e7;
  /// The equations name each derived parameter; true writes them out in the parameters they are
  /// defined from instead (a chain of derived parameters, each using the one before twice,
  /// writes out exponentially large).
  bool expand_derived_parameters = false;
};

/// Number of expression-tree nodes of the selected parts with every intermediate written out,
/// computed without writing them out (linear in the size of the shared graph).
double written_out_size(const Model& model, const ModelEquations& eom, const EquationParts& parts);

/// Number of expression nodes of the selected parts written out and multiplied out, before
/// like terms combine (an upper bound), computed without doing either.
double multiplied_out_size(const Model& model, const ModelEquations& eom, const EquationParts& parts);

/// True if IntermediateForm::automatic would print the shared form.
bool uses_shared_form(const Model& model, const ModelEquations& eom, const PrintOptions& options);

/// Writes the selected parts of `eom` (derived from model.system) to `out`, preceded by a
/// summary of the model (coordinates, parameters with defaults and units, inputs,
/// constraints). M is symmetric: only its upper triangle is printed. LaTeX output is a
/// complete document needing only amsmath. Deterministic for a given model. The functions for
/// controllers (EquationParts::needs_header_functions) are printed from `functions`,
/// derive_header_functions(model, eom), which those parts require.
/// \throws Error if a part of the functions is selected and `functions` is null.
void print_equations(std::ostream& out, const Model& model, const ModelEquations& eom,
                     const PrintOptions& options = {}, const HeaderFunctions* functions = nullptr);

/// print_equations into a string.
std::string format_equations(const Model& model, const ModelEquations& eom,
                             const PrintOptions& options = {}, const HeaderFunctions* functions = nullptr);

}  // namespace eomgen
