#pragma once
// A straight-line program: the intermediate form between symbolic expressions and printed
// code. Instructions are in dependency order; each refers only to earlier ones. Lowering
// (lower.hpp) shares equal subexpressions, so each value is computed once.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace eomgen::ir {

enum class Op {
  number,    // a constant
  variable,  // an input of the function (q[0], p.m, t, ...)
  add,       // n-ary sum
  multiply,  // n-ary product
  divide,    // args[0] / args[1]
  negate,
  power,     // general power args[0]^args[1] (integer powers are lowered to products)
  sqrt, sin, cos, tan, asin, acos, atan, atan2, sinh, cosh, tanh, exp, log, abs
};

struct Instruction {
  Op op;
  std::vector<std::size_t> args;  // indices of earlier instructions
  double number = 0.0;            // Op::number
  std::string variable;           // Op::variable: the C++ text that reads it
};

/// Where a computed value goes: `target` is the C++ lvalue text, e.g. "M(0, 1)".
struct Assignment {
  std::string target;
  std::size_t value;
};

struct Program {
  std::vector<Instruction> instructions;
  std::vector<Assignment> outputs;
};

/// Floating-point operations of a program; an n-ary sum counts n - 1 additions
/// (subtractions included), a negation counts as an addition.
struct OperationCounts {
  std::uint64_t additions = 0;
  std::uint64_t multiplications = 0;
  std::uint64_t divisions = 0;
  std::uint64_t calls = 0;  // sqrt, sin, cos, pow, ...
  std::uint64_t total() const { return additions + multiplications + divisions + calls; }
};

/// Operations of the program as it is (each instruction once).
OperationCounts count_operations(const Program& program);
/// Operations if every output were evaluated as a separate tree, without any sharing: what
/// emitting the equations without common-subexpression elimination would cost.
OperationCounts count_operations_without_sharing(const Program& program);

/// True for ops that are functions (printed as calls).
bool is_call(Op op);
/// The C++ function name of a call op ("sin", "atan2", "pow", ...).
const char* call_name(Op op);

}  // namespace eomgen::ir
