#pragma once
// A quick count of the floating-point operations that evaluating M and F takes, to choose between
// two derivations of one model before anything is emitted. It follows what emission does: shared
// intermediates counted once, parameter-only subexpressions free (they are computed once per
// parameter set), a sum of n terms n - 1 additions, x^k as k - 1 multiplications, and a call of sin, cos
// or sqrt weighted as the multiplications it costs: sin and cos of one argument as one call, and
// those of a sum whose terms have sines or cosines as the addition theorems' few operations (as
// emission computes them, codegen/angle_sums.hpp).
#include <ginac/ginac.h>

#include <vector>

#include "eomgen/mechanics/variables.hpp"
#include "eomgen/symbolic/subexpressions.hpp"

namespace eomgen {

/// Operations of the upper triangle of M and of F, the intermediates they use included once each.
double estimated_operations(const GiNaC::matrix& mass_matrix, const GiNaC::matrix& forcing,
                            const Subexpressions& intermediates, const Variables& variables);

/// Operations of every entry together, the intermediates of every set they use included once.
double estimated_operations(const GiNaC::exvector& entries, const std::vector<const Subexpressions*>& intermediates,
                            const Variables& variables);

}  // namespace eomgen
