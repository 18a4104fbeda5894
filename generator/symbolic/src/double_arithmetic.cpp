#include "double_arithmetic.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace eomgen::detail {

// GiNaC orders the operands of a sum or product by hash values seeded from addresses, so the
// order differs from process to process. Floating-point addition and multiplication are not
// associative: evaluating operands in GiNaC's order would make the last digits of M, F, T, V
// (and the verdicts that compare them with a tolerance) depend on the run. Both reductions
// below give the same bits for any order of the same values, and the same bits with the
// opposite sign for negated operands (GiNaC writes one value as l*(a - b) in one run and as
// -l*(b - a) in another).

namespace {

// A zero result is +0: -0 would print as "-0" in some runs and flip atan2's branch.
double without_negative_zero(double x) { return x == 0.0 ? 0.0 : x; }

}  // namespace

// The exact sum rounded once to the nearest double (Shewchuk's non-overlapping partials, then
// a round-half-even correction from the partials below the leading one), hence independent of
// the order of the terms.
double correctly_rounded_sum(const double* terms, std::size_t count) {
  if (!std::all_of(terms, terms + count, [](double x) { return std::isfinite(x); })) {
    // inf, -inf, NaN: the IEEE sum of these does not depend on order (inf - inf is NaN)
    double x = 0.0;
    for (std::size_t i = 0; i < count; ++i) x += std::isfinite(terms[i]) ? 0.0 : terms[i];
    return x;
  }
  // non-overlapping, increasing magnitude; their sum is exact. One buffer per thread, reused:
  // a tape runs thousands of short sums per evaluation
  thread_local std::vector<double> partials;
  partials.clear();
  for (std::size_t term = 0; term < count; ++term) {
    double x = terms[term];
    std::size_t kept = 0;
    for (double y : partials) {
      if (std::fabs(x) < std::fabs(y)) std::swap(x, y);
      const double hi = x + y;
      const double lo = y - (hi - x);
      if (lo != 0.0) partials[kept++] = lo;
      x = hi;
    }
    if (!std::isfinite(x)) {
      // an intermediate overflow; the ordered sum of sorted terms is still order-independent
      std::vector<double> sorted(terms, terms + count);
      std::sort(sorted.begin(), sorted.end());
      double s = 0.0;
      for (double t : sorted) s += t;
      return s;
    }
    partials.resize(kept);
    partials.push_back(x);
  }
  if (partials.empty()) return 0.0;
  std::size_t n = partials.size() - 1;
  double hi = partials[n], lo = 0.0;
  while (n > 0) {
    const double x = hi, y = partials[--n];
    hi = x + y;
    lo = y - (hi - x);
    if (lo != 0.0) break;
  }
  // hi + lo is exact here; when lo is exactly half an ulp of hi, the partials further down
  // decide which way the true sum rounds
  if (n > 0 && ((lo < 0.0 && partials[n - 1] < 0.0) || (lo > 0.0 && partials[n - 1] > 0.0))) {
    const double twice = lo * 2.0;
    const double x = hi + twice;
    if (twice == x - hi) hi = x;
  }
  return without_negative_zero(hi);
}

// The product of the magnitudes in increasing order, then the sign: the same bits for any
// order of the factors.
double ordered_product(double* factors, std::size_t count) {
  if (std::any_of(factors, factors + count, [](double x) { return std::isnan(x); }))
    return std::numeric_limits<double>::quiet_NaN();
  bool negative = false;
  for (std::size_t i = 0; i < count; ++i) {
    negative ^= std::signbit(factors[i]);
    factors[i] = std::fabs(factors[i]);
  }
  std::sort(factors, factors + count);
  double p = 1.0;
  for (std::size_t i = 0; i < count; ++i) p *= factors[i];
  return without_negative_zero(negative ? -p : p);
}

UnaryFunction unary_function(const std::string& name) {
  static const std::pair<const char*, UnaryFunction> functions[] = {
      {"sin", std::sin},     {"cos", std::cos},     {"tan", std::tan},     {"asin", std::asin},
      {"acos", std::acos},   {"atan", std::atan},   {"sinh", std::sinh},   {"cosh", std::cosh},
      {"tanh", std::tanh},   {"asinh", std::asinh}, {"acosh", std::acosh}, {"atanh", std::atanh},
      {"exp", std::exp},     {"log", std::log},     {"abs", std::fabs}};
  for (const auto& [known, f] : functions)
    if (name == known) return f;
  return nullptr;
}

}  // namespace eomgen::detail
