#pragma once
// Instructions and targets of hand-built IR programs, for the tests of the printer and of the
// passes over the IR: q(0) is coordinate 0, p(1) parameter 1, op(Op::mul, {0, 1}) a product of
// the values of instructions 0 and 1, y(2) output 2.
#include <cstddef>
#include <utility>
#include <vector>

#include "eomgen/codegen/ir.hpp"

namespace eomgen::testing::ir_builders {

inline ir::Instruction var(ir::VariableKind kind, std::size_t index) {
  return ir::Instruction{ir::Op::variable, {}, 0.0, {kind, index}};
}
inline ir::Instruction q(std::size_t index) { return var(ir::VariableKind::coordinate, index); }
inline ir::Instruction p(std::size_t index) { return var(ir::VariableKind::parameter, index); }
inline ir::Instruction num(double v) { return ir::Instruction{ir::Op::number, {}, v, {}}; }
inline ir::Instruction op(ir::Op o, std::vector<std::size_t> args) {
  return ir::Instruction{o, std::move(args), 0.0, {}};
}
inline ir::Target y(std::size_t row) { return {ir::Array::outputs, row, 0}; }

}  // namespace eomgen::testing::ir_builders
