#pragma once
// The unit in brackets after a parameter, coordinate or input, to its dimension.
#include <vector>

#include "eomgen/base/source_location.hpp"
#include "eomgen/mechanics/dimension.hpp"
#include "model_lexer.hpp"

namespace eomgen::syntax {

/// The dimension of the unit spelled by `tokens`, those between '[' (at `open`) and ']'.
/// Factors are separated by spaces or '*', '/' divides by the next factor or parenthesized
/// group, '^' takes an integer with an optional sign: kg m^2, N s/m, m/s^2, 1/s. '-' and '1'
/// are dimensionless. Only coherent SI units are accepted (coherent_unit()).
/// \throws SourceError at the offending token.
Dimension unit_dimension(const std::vector<Token>& tokens, const SourceLocation& open);

}  // namespace eomgen::syntax
