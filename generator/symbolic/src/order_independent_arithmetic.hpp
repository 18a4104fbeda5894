#pragma once
// Sums and products whose bits do not depend on the order of their operands (see the .cpp):
// shared by the evaluators that walk GiNaC expressions and those that run a compiled tape, so
// that both give the same numbers.
#include <cstddef>
#include <vector>

namespace eomgen::detail {

/// the exact sum of terms[0..count) rounded once to the nearest double
double correctly_rounded_sum(const double* terms, std::size_t count);

/// the product of the magnitudes in increasing order, then the sign; `factors` is reordered
double ordered_product(double* factors, std::size_t count);

}  // namespace eomgen::detail
