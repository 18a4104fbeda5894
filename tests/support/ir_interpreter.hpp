#pragma once
// The outputs of an IR program at given inputs, computed by an interpreter independent of the
// C++ printer: for the tests of the passes over the IR (a pass must keep every value).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <vector>

#include "eomgen/codegen/ir.hpp"

namespace eomgen::testing {

inline std::map<ir::Target, double> evaluate(const ir::Program& program,
                                             const std::map<ir::Variable, double>& inputs) {
  std::vector<double> v;
  for (const ir::Instruction& in : program.instructions) {
    const auto arg = [&](std::size_t k) { return v.at(in.args.at(k)); };
    double x = 0;
    switch (in.op) {
      case ir::Op::number: x = in.number; break;
      case ir::Op::variable: x = inputs.at(in.variable); break;
      case ir::Op::add:
        for (std::size_t a : in.args) x += v.at(a);
        break;
      case ir::Op::multiply:
        x = 1;
        for (std::size_t a : in.args) x *= v.at(a);
        break;
      case ir::Op::divide: x = arg(0) / arg(1); break;
      case ir::Op::negate: x = -arg(0); break;
      case ir::Op::sin: x = std::sin(arg(0)); break;
      case ir::Op::cos: x = std::cos(arg(0)); break;
      case ir::Op::tan: x = std::tan(arg(0)); break;
      case ir::Op::asin: x = std::asin(arg(0)); break;
      case ir::Op::acos: x = std::acos(arg(0)); break;
      case ir::Op::atan: x = std::atan(arg(0)); break;
      case ir::Op::atan2: x = std::atan2(arg(0), arg(1)); break;
      case ir::Op::sinh: x = std::sinh(arg(0)); break;
      case ir::Op::cosh: x = std::cosh(arg(0)); break;
      case ir::Op::tanh: x = std::tanh(arg(0)); break;
      case ir::Op::sqrt: x = std::sqrt(arg(0)); break;
      case ir::Op::exp: x = std::exp(arg(0)); break;
      case ir::Op::log: x = std::log(arg(0)); break;
      case ir::Op::abs: x = std::fabs(arg(0)); break;
      case ir::Op::power: x = std::pow(arg(0), arg(1)); break;
    }
    v.push_back(x);
  }
  std::map<ir::Target, double> out;
  for (const ir::Assignment& a : program.outputs) out[a.target] = v.at(a.value);
  return out;
}

}  // namespace eomgen::testing
