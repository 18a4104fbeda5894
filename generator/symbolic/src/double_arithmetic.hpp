#pragma once
// The arithmetic of the double evaluators (DoubleEvaluator, which walks GiNaC expressions, and
// ExpressionTape, which runs them compiled), shared so that both give the same bits: sums and
// products whose result does not depend on the order of their operands (see the .cpp), and the
// double form of each GiNaC function they evaluate.
#include <cstddef>
#include <string>
#include <vector>

namespace eomgen::detail {

/// the exact sum of terms[0..count) rounded once to the nearest double
double correctly_rounded_sum(const double* terms, std::size_t count);

/// the product of the magnitudes in increasing order, then the sign; `factors` is reordered
double ordered_product(double* factors, std::size_t count);

using UnaryFunction = double (*)(double);

/// the double form of the one-argument GiNaC function `name` (sin, cos, ..., exp, log, abs), or
/// nullptr; atan2, the only one of two arguments, is the caller's
UnaryFunction unary_function(const std::string& name);

}  // namespace eomgen::detail
