#pragma once
// The derived equations of a model that gives units, checked against them: a second line of
// defence behind the model language's unit check, which checks what a model writes. Every term
// of row i of M qdd and of F has dimension J / dim(q_i), T and V are energies, and each
// constraint row agrees with itself. A failure is a derivation that breaks the units, or a path
// of the language the unit check misses: a bug either way.
#include "eomgen/derivation/equations_of_motion.hpp"
#include "eomgen/mechanics/dimension.hpp"
#include "eomgen/mechanics/variables.hpp"

namespace eomgen {

/// \throws DerivationError naming the part (M, F, T, V, Xi, Xi_t, b, phi), its row and entry,
/// the term and its dimension with the one expected. Does nothing for empty `dimensions` (a
/// model without units).
void check_dimensions(const EquationsOfMotion& equations, const Variables& variables, const DimensionMap& dimensions);

}  // namespace eomgen
