#pragma once
// Symbolic expressions -> straight-line program, sharing every repeated subexpression across
// all outputs at once. The result depends only on the expressions' content: operands of sums
// and products are put in a canonical order computed from names and values (never from
// pointers, hashes of addresses or GiNaC's own term order, which varies between runs), so
// the same model always gives the same program.
#include <ginac/ginac.h>

#include <map>
#include <string>
#include <vector>

#include "eomgen/codegen/ir.hpp"
#include "eomgen/symbolic/subexpressions.hpp"

namespace eomgen {

/// A value to compute and where it goes.
struct LoweringTarget {
  ir::Target target;
  GiNaC::ex value;
};

/// An input of the generated functions as the lowering sees it: the IR variable, and a name
/// unique to it that places it among the operands of sums and products (the canonical order
/// comes from names, values and structure only).
struct NamedVariable {
  ir::Variable variable;
  std::string name;
};

/// Maps each model symbol to the input it reads.
using VariableNames = std::map<GiNaC::ex, NamedVariable, GiNaC::ex_is_less>;

/// Lowers the targets jointly. Intermediates of `subexpressions` are followed to their
/// definitions. Targets whose value is exactly zero are dropped (the caller zeroes the output).
/// \throws EmitError for a symbol missing from `variables` or a function with no C++ form.
ir::Program lower(const std::vector<LoweringTarget>& targets, const Subexpressions& subexpressions,
                  const VariableNames& variables);

/// One program per function, lowering the shared graph once: M and F appear in mass_matrix,
/// forcing and mass_matrix_and_forcing alike. Each program is what lower() gives for its
/// targets alone. Several sets of intermediates may be given (the derivation's, then the
/// linearization's derivatives, which refer to them); their symbols must be distinct.
std::vector<ir::Program> lower_functions(const std::vector<std::vector<LoweringTarget>>& functions,
                                         const std::vector<const Subexpressions*>& subexpressions,
                                         const VariableNames& variables);

}  // namespace eomgen
