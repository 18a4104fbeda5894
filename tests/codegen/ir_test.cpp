// The IR's table of call operations: every call op has exactly one row, and the rest derives from it.
#include "eomgen/codegen/ir.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <set>
#include <string>

namespace eomgen {
namespace {

using ir::Op;

TEST(IrCallOps, EveryEnumeratorAfterNegateIsACallWithItsOwnRow) {
  std::size_t calls = 0;
  for (std::size_t k = 0; k < ir::op_count; ++k) {
    const Op op = static_cast<Op>(k);
    EXPECT_EQ(ir::is_call(op), k > static_cast<std::size_t>(Op::negate)) << k;
    if (!ir::is_call(op)) continue;
    ++calls;
    EXPECT_EQ(ir::call_op(op).op, op) << k;
  }
  EXPECT_EQ(calls, std::size(ir::call_ops));
}

TEST(IrCallOps, NamesAndSignatureCodesAreDistinct) {
  std::set<std::string> names;
  std::set<std::uint64_t> codes;
  for (const ir::CallOp& call : ir::call_ops) {
    EXPECT_TRUE(names.insert(call.cpp_name).second) << call.cpp_name;
    EXPECT_TRUE(codes.insert(call.code).second) << call.cpp_name;
    EXPECT_GE(call.arity, 1u) << call.cpp_name;
  }
}

TEST(IrCallOps, EveryCallCountsAsOneCall) {
  for (const ir::CallOp& call : ir::call_ops) {
    ir::Program p;
    p.instructions.push_back({Op::number, {}, 2.0, {}});
    p.instructions.push_back({call.op, std::vector<std::size_t>(call.arity, 0), 0.0, {}});
    p.outputs.push_back({{ir::Array::outputs, 0, 0}, 1});
    const ir::OperationCounts c = ir::count_operations(p);
    EXPECT_EQ(c.calls, 1u) << call.cpp_name;
    EXPECT_EQ(c.total(), 1u) << call.cpp_name;
  }
}

// x_{k+1} = x_k + x_k seventy times: 2^70 - 1 additions as a tree, more than a count holds
TEST(IrOperationCounts, CountsWithoutSharingSaturateInsteadOfWrappingAround) {
  ir::Program p;
  p.instructions.push_back({Op::number, {}, 2.0, {}});
  for (std::size_t k = 0; k < 70; ++k) p.instructions.push_back({Op::add, {k, k}, 0.0, {}});
  p.outputs.push_back({{ir::Array::outputs, 0, 0}, 70});
  const std::uint64_t most = std::numeric_limits<std::uint64_t>::max();
  EXPECT_EQ(ir::count_operations(p).additions, 70u);
  const ir::OperationCounts tree = ir::count_operations_without_sharing(p);
  EXPECT_EQ(tree.additions, most);
  EXPECT_EQ(tree.total(), most);
}

}  // namespace
}  // namespace eomgen
