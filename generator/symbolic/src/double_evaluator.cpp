#include "eomgen/symbolic/double_evaluator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "eomgen/base/error.hpp"
#include "double_arithmetic.hpp"

namespace eomgen {

using GiNaC::ex;
using GiNaC::is_a;

double DoubleEvaluator::finite(const ex& e, const std::string& what) const {
  const double x = value(e, what);
  if (!std::isfinite(x))
    throw Error(fmt::format("evaluating {} at this state: the result is not finite (a division by zero, "
                            "or a root or logarithm of a negative number)", what));
  return x;
}

double DoubleEvaluator::value(const ex& e, const std::string& what) const {
  Memo memo;
  return value(e, what, memo);
}

double DoubleEvaluator::value(const ex& e, const std::string& what, Memo& memo) const {
  if (e.nops() > 0) {
    const GiNaC::basic* node = &GiNaC::ex_to<GiNaC::basic>(e);
    if (const auto it = memo.find(node); it != memo.end()) return it->second.second;
  }
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
  if (is_a<GiNaC::constant>(e)) return GiNaC::ex_to<GiNaC::numeric>(e.evalf()).to_double();
  double result = 0;
  if (is_a<GiNaC::add>(e) || is_a<GiNaC::mul>(e)) {
    std::vector<double> operands(e.nops());
    for (std::size_t i = 0; i < e.nops(); ++i) operands[i] = value(e.op(i), what, memo);
    result = is_a<GiNaC::add>(e) ? detail::correctly_rounded_sum(operands.data(), operands.size())
                                 : detail::ordered_product(operands.data(), operands.size());
  } else if (is_a<GiNaC::power>(e)) {
    const double base = value(e.op(0), what, memo);
    result = e.op(1).is_equal(GiNaC::numeric(1, 2)) ? std::sqrt(base) : std::pow(base, value(e.op(1), what, memo));
  } else if (is_a<GiNaC::function>(e)) {
    result = function(e, what, memo);
  } else {
    throw Error(fmt::format("evaluating {}: this kind of expression has no numeric evaluation here", what));
  }
  memo.emplace(&GiNaC::ex_to<GiNaC::basic>(e), std::make_pair(e, result));
  return result;
}

double DoubleEvaluator::function(const ex& e, const std::string& what, Memo& memo) const {
  const std::string name = GiNaC::ex_to<GiNaC::function>(e).get_name();
  if (name == "atan2" && e.nops() == 2) return std::atan2(value(e.op(0), what, memo), value(e.op(1), what, memo));
  if (const detail::UnaryFunction f = e.nops() == 1 ? detail::unary_function(name) : nullptr)
    return f(value(e.op(0), what, memo));
  throw Error(fmt::format("evaluating {}: the function '{}' has no numeric evaluation here", what, name));
}

}  // namespace eomgen
