#include "eomgen/symbolic/expression_tape.hpp"

#include <fmt/format.h>

#include <cmath>
#include <utility>

#include "eomgen/base/error.hpp"
#include "double_arithmetic.hpp"

namespace eomgen {

using GiNaC::ex;
using GiNaC::is_a;

ExpressionTape::ExpressionTape(const std::vector<ex>& inputs) : input_count_(inputs.size()) {
  for (const ex& s : inputs) registered_.emplace(s, registers_++);
}

void ExpressionTape::define(const ex& symbol, const ex& value, const std::string& what) {
  const std::uint32_t r = node(value, what);
  registered_[symbol] = r;
}

std::uint32_t ExpressionTape::compile(const ex& e, const std::string& what) { return node(e, what); }

std::uint32_t ExpressionTape::emit(Step step, const std::vector<std::uint32_t>& operands) {
  step.result = registers_++;
  step.first = static_cast<std::uint32_t>(operands_.size());
  step.count = static_cast<std::uint32_t>(operands.size());
  operands_.insert(operands_.end(), operands.begin(), operands.end());
  steps_.push_back(step);
  return step.result;
}

std::uint32_t ExpressionTape::node(const ex& e, const std::string& what) {
  if (const std::uint32_t* r = registered_.find(e)) return *r;
  Step step{Op::constant, 0, 0, 0, 0.0, nullptr};
  std::vector<std::uint32_t> operands;
  if (is_a<GiNaC::numeric>(e)) {
    const GiNaC::numeric& n = GiNaC::ex_to<GiNaC::numeric>(e);
    if (!n.is_real()) throw Error(fmt::format("evaluating {}: the expression has a complex number", what));
    step.constant = n.to_double();
  } else if (is_a<GiNaC::symbol>(e)) {
    throw Error(fmt::format("evaluating {}: it depends on '{}', which has no value here", what,
                            GiNaC::ex_to<GiNaC::symbol>(e).get_name()));
  } else if (is_a<GiNaC::constant>(e)) {
    step.constant = GiNaC::ex_to<GiNaC::numeric>(e.evalf()).to_double();
  } else if (is_a<GiNaC::add>(e) || is_a<GiNaC::mul>(e)) {
    step.op = is_a<GiNaC::add>(e) ? Op::sum : Op::product;
    for (std::size_t i = 0; i < e.nops(); ++i) operands.push_back(node(e.op(i), what));
  } else if (is_a<GiNaC::power>(e)) {
    operands.push_back(node(e.op(0), what));
    if (e.op(1).is_equal(GiNaC::numeric(1, 2))) {
      step.op = Op::square_root;
    } else {
      step.op = Op::power;
      operands.push_back(node(e.op(1), what));
    }
  } else if (is_a<GiNaC::function>(e)) {
    const std::string name = GiNaC::ex_to<GiNaC::function>(e).get_name();
    if (name == "atan2" && e.nops() == 2) {
      step.op = Op::atan2;
    } else if (const detail::UnaryFunction f = e.nops() == 1 ? detail::unary_function(name) : nullptr) {
      step.op = Op::unary;
      step.unary = f;
    } else {
      throw Error(fmt::format("evaluating {}: the function '{}' has no numeric evaluation here", what, name));
    }
    for (std::size_t i = 0; i < e.nops(); ++i) operands.push_back(node(e.op(i), what));
  } else {
    throw Error(fmt::format("evaluating {}: this kind of expression has no numeric evaluation here", what));
  }
  const std::uint32_t r = emit(step, operands);
  registered_.emplace(e, r);
  return r;
}

void ExpressionTape::evaluate(const std::vector<double>& inputs, std::vector<double>& registers) const {
  EOMGEN_DEMAND(inputs.size() == input_count_, "ExpressionTape::evaluate: one value per input");
  registers.resize(registers_);
  std::copy(inputs.begin(), inputs.end(), registers.begin());
  std::vector<double> values;
  for (const Step& s : steps_) {
    const std::uint32_t* in = operands_.data() + s.first;
    double& out = registers[s.result];
    switch (s.op) {
      case Op::constant:
        out = s.constant;
        break;
      case Op::sum:
      case Op::product:
        values.resize(s.count);
        for (std::uint32_t k = 0; k < s.count; ++k) values[k] = registers[in[k]];
        out = s.op == Op::sum ? detail::correctly_rounded_sum(values.data(), s.count)
                              : detail::ordered_product(values.data(), s.count);
        break;
      case Op::square_root:
        out = std::sqrt(registers[in[0]]);
        break;
      case Op::power:
        out = std::pow(registers[in[0]], registers[in[1]]);
        break;
      case Op::unary:
        out = s.unary(registers[in[0]]);
        break;
      case Op::atan2:
        out = std::atan2(registers[in[0]], registers[in[1]]);
        break;
    }
  }
}

}  // namespace eomgen
