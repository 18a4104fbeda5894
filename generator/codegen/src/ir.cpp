#include "eomgen/codegen/ir.hpp"

#include "eomgen/base/error.hpp"

#include <cassert>

namespace eomgen::ir {
namespace {

constexpr bool codes_are_distinct_and_above_the_other_ops() {
  for (std::size_t i = 0; i < std::size(call_ops); ++i) {
    if (call_ops[i].code <= static_cast<std::uint64_t>(Op::negate)) return false;
    for (std::size_t j = 0; j < i; ++j)
      if (call_ops[i].code == call_ops[j].code) return false;
  }
  return true;
}
static_assert(codes_are_distinct_and_above_the_other_ops(),
              "each call op needs a signature code of its own, above those of number ... negate");

constexpr bool rows_are_in_enum_order() {
  for (std::size_t i = 0; i < std::size(call_ops); ++i)
    if (static_cast<std::size_t>(call_ops[i].op) != static_cast<std::size_t>(Op::negate) + 1 + i) return false;
  return true;
}
static_assert(rows_are_in_enum_order(), "call_ops[i] describes the i-th call enumerator");

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
    EOMGEN_IR_CALL_OPS(EOMGEN_IR_CALL_CASE)
      ++c.calls;
      break;
  }
}

OperationCounts plus(OperationCounts a, const OperationCounts& b) {
  a.additions = saturating_sum(a.additions, b.additions);
  a.multiplications = saturating_sum(a.multiplications, b.multiplications);
  a.divisions = saturating_sum(a.divisions, b.divisions);
  a.calls = saturating_sum(a.calls, b.calls);
  return a;
}

}  // namespace

std::size_t rank(Array array) {
  switch (array) {
    case Array::kinetic_energy:
    case Array::potential_energy:
      return 0;
    case Array::forcing:
    case Array::constraint_rate_term:
    case Array::constraint_acceleration_term:
    case Array::holonomic_residuals:
    case Array::outputs:
    case Array::generalized_forces:
    case Array::gravity_forces:
    case Array::output_bias:
    case Array::inertial_parameters:
    case Array::multipliers:
    case Array::constants:
    case Array::accelerations:
    case Array::pivots:
    case Array::derived_parameters:
      return 1;
    case Array::mass_matrix:
    case Array::constraint_jacobian:
    case Array::stiffness:
    case Array::damping:
    case Array::input_matrix:
    case Array::acceleration_constraint_by_q:
    case Array::acceleration_constraint_by_qd:
    case Array::coriolis_matrix:
    case Array::acceleration_by_coordinates:
    case Array::acceleration_by_rates:
    case Array::acceleration_by_inputs:
    case Array::output_jacobian:
    case Array::regressor:
      return 2;
  }
  EOMGEN_UNREACHABLE("an ir::Array value that is not an enumerator");
}

bool is_call(Op op) {
  switch (op) {
    case Op::number:
    case Op::variable:
    case Op::add:
    case Op::multiply:
    case Op::divide:
    case Op::negate:
      return false;
    EOMGEN_IR_CALL_OPS(EOMGEN_IR_CALL_CASE)
      return true;
  }
  EOMGEN_UNREACHABLE("an ir::Op value that is not an enumerator");
}

const CallOp& call_op(Op op) {
  assert(is_call(op));
  return call_ops[static_cast<std::size_t>(op) - static_cast<std::size_t>(Op::negate) - 1];
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
