#pragma once
// The values of a model's functions that depend on parameters and numbers only, taken out of
// the per-call programs and computed once per parameter set (the generated Constants), as
// SD/FAST's initialization did: a call then does only state-dependent work.
#include <vector>

#include "eomgen/codegen/ir.hpp"

namespace eomgen {

/// Programs split into their once-per-parameter-set part and their per-call parts.
struct ConstantSplit {
  /// Computes constant k into Target{Array::constants, k, 0}, k = 0, 1, ...; reads parameters
  /// and numbers only.
  ir::Program constants;
  /// The given programs, one each, reading constant k as Variable{VariableKind::constant, k}.
  std::vector<ir::Program> per_call;
};

/// Takes out of `programs` every maximal subexpression that depends on parameters and numbers
/// only and is more than a parameter or a number (possibly negated), which a call reads as it
/// is. The constant operands of a sum or a product that also depends on the state become one
/// constant, and a division by a constant becomes a multiplication by its reciprocal.
/// Constants are shared between the programs and numbered in order of first use (program by
/// program, instruction by instruction), so the split depends only on the programs.
/// \pre no program reads a VariableKind::constant
ConstantSplit split_constants(const std::vector<ir::Program>& programs);

}  // namespace eomgen
