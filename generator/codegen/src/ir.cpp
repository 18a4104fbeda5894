#include "eomgen/codegen/ir.hpp"

namespace eomgen::ir {
namespace {

void add_own(const Instruction& in, OperationCounts& c) {
  switch (in.op) {
    case Op::number:
    case Op::variable:
      break;
    case Op::add:
      c.additions += in.args.size() - 1;
      break;
    case Op::multiply:
      c.multiplications += in.args.size() - 1;
      break;
    case Op::divide:
      ++c.divisions;
      break;
    case Op::negate:
      ++c.additions;
      break;
    case Op::power:
    case Op::sqrt:
    case Op::sin:
    case Op::cos:
    case Op::tan:
    case Op::asin:
    case Op::acos:
    case Op::atan:
    case Op::atan2:
    case Op::sinh:
    case Op::cosh:
    case Op::tanh:
    case Op::exp:
    case Op::log:
    case Op::abs:
      ++c.calls;
      break;
  }
}

OperationCounts plus(OperationCounts a, const OperationCounts& b) {
  a.additions += b.additions;
  a.multiplications += b.multiplications;
  a.divisions += b.divisions;
  a.calls += b.calls;
  return a;
}

}  // namespace

bool is_call(Op op) {
  switch (op) {
    case Op::number:
    case Op::variable:
    case Op::add:
    case Op::multiply:
    case Op::divide:
    case Op::negate:
      return false;
    case Op::power:
    case Op::sqrt:
    case Op::sin:
    case Op::cos:
    case Op::tan:
    case Op::asin:
    case Op::acos:
    case Op::atan:
    case Op::atan2:
    case Op::sinh:
    case Op::cosh:
    case Op::tanh:
    case Op::exp:
    case Op::log:
    case Op::abs:
      return true;
  }
  return false;
}

const char* call_name(Op op) {
  switch (op) {
    case Op::power: return "pow";
    case Op::sqrt: return "sqrt";
    case Op::sin: return "sin";
    case Op::cos: return "cos";
    case Op::tan: return "tan";
    case Op::asin: return "asin";
    case Op::acos: return "acos";
    case Op::atan: return "atan";
    case Op::atan2: return "atan2";
    case Op::sinh: return "sinh";
    case Op::cosh: return "cosh";
    case Op::tanh: return "tanh";
    case Op::exp: return "exp";
    case Op::log: return "log";
    case Op::abs: return "abs";
    case Op::number:
    case Op::variable:
    case Op::add:
    case Op::multiply:
    case Op::divide:
    case Op::negate:
      break;
  }
  return "";
}

OperationCounts count_operations(const Program& program) {
  OperationCounts c;
  for (const Instruction& in : program.instructions) add_own(in, c);
  return c;
}

OperationCounts count_operations_without_sharing(const Program& program) {
  // cost of the whole tree under each instruction, in order (arguments come first)
  std::vector<OperationCounts> tree(program.instructions.size());
  for (std::size_t i = 0; i < program.instructions.size(); ++i) {
    const Instruction& in = program.instructions[i];
    add_own(in, tree[i]);
    for (std::size_t a : in.args) tree[i] = plus(tree[i], tree[a]);
  }
  OperationCounts total;
  for (const Assignment& out : program.outputs) total = plus(total, tree[out.value]);
  return total;
}

}  // namespace eomgen::ir
