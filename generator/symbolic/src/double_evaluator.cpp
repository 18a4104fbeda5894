#include "eomgen/symbolic/double_evaluator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "eomgen/base/error.hpp"

namespace eomgen {

using GiNaC::ex;
using GiNaC::is_a;

namespace {

// GiNaC orders the operands of a sum or product by hash values seeded from addresses, so the
// order differs from process to process. Floating-point addition and multiplication are not
// associative: evaluating operands in GiNaC's order would make the last digits of M, F, T, V
// (and the verdicts that compare them with a tolerance) depend on the run. Both reductions
// below give the same bits for any order of the same values, and the same bits with the
// opposite sign for negated operands (GiNaC writes one value as l*(a - b) in one run and as
// -l*(b - a) in another).

bool all_finite(const std::vector<double>& xs) {
  return std::all_of(xs.begin(), xs.end(), [](double x) { return std::isfinite(x); });
}

// A zero result is +0: -0 would print as "-0" in some runs and flip atan2's branch.
double without_negative_zero(double x) { return x == 0.0 ? 0.0 : x; }

// The exact sum rounded once to the nearest double (Shewchuk's non-overlapping partials, then
// a round-half-even correction from the partials below the leading one), hence independent of
// the order of the terms.
double correctly_rounded_sum(const std::vector<double>& terms) {
  if (!all_finite(terms)) {
    // inf, -inf, NaN: the IEEE sum of these does not depend on order (inf - inf is NaN)
    double x = 0.0;
    for (double t : terms) x += std::isfinite(t) ? 0.0 : t;
    return x;
  }
  std::vector<double> partials;  // non-overlapping, increasing magnitude; their sum is exact
  for (double x : terms) {
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
      std::vector<double> sorted = terms;
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
double ordered_product(std::vector<double> factors) {
  if (std::any_of(factors.begin(), factors.end(), [](double x) { return std::isnan(x); }))
    return std::numeric_limits<double>::quiet_NaN();
  bool negative = false;
  for (double& x : factors) {
    negative ^= std::signbit(x);
    x = std::fabs(x);
  }
  std::sort(factors.begin(), factors.end());
  double p = 1.0;
  for (double x : factors) p *= x;
  return without_negative_zero(negative ? -p : p);
}

}  // namespace

double DoubleEvaluator::finite(const ex& e, const std::string& what) const {
  const double x = value(e, what);
  if (!std::isfinite(x))
    throw Error(fmt::format("evaluating {} at this state: the result is not finite (a division by zero, "
                            "or a root or logarithm of a negative number)", what));
  return x;
}

double DoubleEvaluator::value(const ex& e, const std::string& what) const {
  if (is_a<GiNaC::numeric>(e)) {
    const GiNaC::numeric& n = GiNaC::ex_to<GiNaC::numeric>(e);
    if (!n.is_real()) throw Error(fmt::format("evaluating {}: the expression has a complex number", what));
    return n.to_double();
  }
  if (is_a<GiNaC::symbol>(e)) {
    const auto it = values_.find(e);
    if (it == values_.end())
      throw Error(fmt::format("evaluating {}: it depends on '{}', which has no value here", what,
                              GiNaC::ex_to<GiNaC::symbol>(e).get_name()));
    return it->second;
  }
  if (is_a<GiNaC::add>(e) || is_a<GiNaC::mul>(e)) {
    std::vector<double> operands(e.nops());
    for (std::size_t i = 0; i < e.nops(); ++i) operands[i] = value(e.op(i), what);
    return is_a<GiNaC::add>(e) ? correctly_rounded_sum(operands) : ordered_product(std::move(operands));
  }
  if (is_a<GiNaC::power>(e)) {
    const double base = value(e.op(0), what);
    if (e.op(1).is_equal(GiNaC::numeric(1, 2))) return std::sqrt(base);
    return std::pow(base, value(e.op(1), what));
  }
  if (is_a<GiNaC::constant>(e)) return GiNaC::ex_to<GiNaC::numeric>(e.evalf()).to_double();
  if (is_a<GiNaC::function>(e)) return function(e, what);
  throw Error(fmt::format("evaluating {}: this kind of expression has no numeric evaluation here", what));
}

double DoubleEvaluator::function(const ex& e, const std::string& what) const {
  using unary = double (*)(double);
  static const std::pair<const char*, unary> functions[] = {
      {"sin", std::sin},     {"cos", std::cos},     {"tan", std::tan},     {"asin", std::asin},
      {"acos", std::acos},   {"atan", std::atan},   {"sinh", std::sinh},   {"cosh", std::cosh},
      {"tanh", std::tanh},   {"asinh", std::asinh}, {"acosh", std::acosh}, {"atanh", std::atanh},
      {"exp", std::exp},     {"log", std::log},     {"abs", std::fabs}};
  const std::string name = GiNaC::ex_to<GiNaC::function>(e).get_name();
  if (name == "atan2" && e.nops() == 2) return std::atan2(value(e.op(0), what), value(e.op(1), what));
  for (const auto& [known, f] : functions)
    if (name == known && e.nops() == 1) return f(value(e.op(0), what));
  throw Error(fmt::format("evaluating {}: the function '{}' has no numeric evaluation here", what, name));
}

}  // namespace eomgen
