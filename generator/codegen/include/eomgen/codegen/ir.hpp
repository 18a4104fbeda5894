#pragma once
// A straight-line program: the intermediate form between symbolic expressions and printed
// code. Instructions are in dependency order; each refers only to earlier ones. Lowering
// (lower.hpp) shares equal subexpressions, so each value is computed once.
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

namespace eomgen::ir {

// The call operations, listed once: the enumerators of Op, is_call, the C++ names, the
// lowering of GiNaC functions (by name), the generated code's using-declarations and the
// names an identifier may not take all derive from this list, so a new call is one line.
//   X(op, C++ name, arity, symmetry, code)
// symmetry: odd (f(-x) = -f(x)), even (f(-x) = f(x)) or none, for moving signs out of calls.
// code: the op's number in the lowering's content signatures, which decide the order of
// operands in every generated header; fixed per op, whatever the order here, so never change
// or reuse one (a new op takes the next free code, 21).
// The order is that of the generated `using std::...` declarations.
#define EOMGEN_IR_CALL_OPS(X)      \
  X(sin, "sin", 1, odd, 8)         \
  X(cos, "cos", 1, even, 9)        \
  X(tan, "tan", 1, odd, 10)        \
  X(asin, "asin", 1, odd, 11)      \
  X(acos, "acos", 1, none, 12)     \
  X(atan, "atan", 1, odd, 13)      \
  X(atan2, "atan2", 2, none, 14)   \
  X(sinh, "sinh", 1, odd, 15)      \
  X(cosh, "cosh", 1, even, 16)     \
  X(tanh, "tanh", 1, odd, 17)      \
  X(sqrt, "sqrt", 1, none, 7)      \
  X(exp, "exp", 1, none, 18)       \
  X(log, "log", 1, none, 19)       \
  X(abs, "abs", 1, even, 20)       \
  X(power, "pow", 2, none, 6) /* general power; integer powers are lowered to products */

enum class Op {
  number,    // a constant
  variable,  // an input of the function (a coordinate, a parameter, t, ...)
  add,       // n-ary sum
  multiply,  // n-ary product
  divide,    // args[0] / args[1]
  negate,
#define EOMGEN_IR_ENUMERATOR(op, name, arity, symmetry, code) op,
  EOMGEN_IR_CALL_OPS(EOMGEN_IR_ENUMERATOR)
#undef EOMGEN_IR_ENUMERATOR
};

/// `case Op::sin: case Op::cos: ...` for every call op, in a switch over Op:
/// `EOMGEN_IR_CALL_OPS(EOMGEN_IR_CALL_CASE) return ...;`
#define EOMGEN_IR_CALL_CASE(op, name, arity, symmetry, code) case ::eomgen::ir::Op::op:

/// How a call treats a negated argument.
enum class Symmetry { odd, even, none };

/// One row of EOMGEN_IR_CALL_OPS.
struct CallOp {
  Op op;
  const char* cpp_name;  ///< the function of <cmath> it prints as
  std::size_t arity;
  Symmetry symmetry;
  std::uint64_t code;  ///< its fixed number in content signatures
};

/// Every call op, in the order of EOMGEN_IR_CALL_OPS.
inline constexpr CallOp call_ops[] = {
#define EOMGEN_IR_CALL_ROW(op, name, arity, symmetry, code) {Op::op, name, arity, Symmetry::symmetry, code},
    EOMGEN_IR_CALL_OPS(EOMGEN_IR_CALL_ROW)
#undef EOMGEN_IR_CALL_ROW
};

/// Number of enumerators of Op (the calls come last).
inline constexpr std::size_t op_count = static_cast<std::size_t>(Op::negate) + 1 + std::size(call_ops);

/// Which input of a generated function a variable reads, in the order of the function's
/// arguments.
enum class VariableKind {
  time,          // t
  coordinate,    // q(index)
  rate,          // qd(index)
  input,         // u(index)
  parameter,     // the model's parameter number `index`
  derived_parameter,  // the model's derived parameter number `index`, computed by the Constants
  acceleration,  // qdd(index), given to the linearization's terms
  multiplier,    // lambda(index), given to the linearization's terms
  constant,      // the per-parameter-set constant number `index` (parameter_constants.hpp)
};

/// One input value of a generated function, named symbolically (the printer spells it).
struct Variable {
  VariableKind kind = VariableKind::time;
  std::size_t index = 0;  ///< of the coordinate, input, parameter or constraint; 0 for time

  friend bool operator==(const Variable& a, const Variable& b) { return a.kind == b.kind && a.index == b.index; }
  friend bool operator<(const Variable& a, const Variable& b) {
    return a.kind != b.kind ? a.kind < b.kind : a.index < b.index;
  }
};

/// What a generated function writes: a matrix, a vector or a scalar of the equations.
enum class Array {
  mass_matrix,                    // M
  forcing,                        // F
  constraint_jacobian,            // Xi
  constraint_rate_term,           // Xi_t
  constraint_acceleration_term,   // b
  holonomic_residuals,            // phi
  outputs,                        // y
  kinetic_energy,                 // T, a scalar
  potential_energy,               // V, a scalar
  stiffness,                      // K = dR/dq of R = M qdd - F (- Xi^T lambda)
  damping,                        // D = dR/dqd
  input_matrix,                   // B_u = dF/du
  acceleration_constraint_by_q,   // S_q = dS/dq of S = Xi qdd + b
  acceleration_constraint_by_qd,  // S_qd = dS/dqd
  generalized_forces,             // tau = M qdd - F of the inverse dynamics (less Xi^T lambda with constraints)
  gravity_forces,                 // G = dV/dq
  coriolis_matrix,                // C(q, qd) of the Christoffel symbols
  output_jacobian,                // J of one output
  output_bias,                    // Jdot qd of one output: its acceleration (or rate) at qdd = 0
  regressor,                      // Y of M qdd - F = Y pi + ...
  inertial_parameters,            // pi, the bodies' inertial parameters
  multipliers,                    // lambda of the inverse dynamics with constraints (solved, never a target)
  constants,                      // the per-parameter-set constants, computed once by Constants
  accelerations,                  // qdd of the generated forward dynamics
  acceleration_by_coordinates,    // dqdd/dq of the forward dynamics
  acceleration_by_rates,          // dqdd/dqd
  acceleration_by_inputs,         // dqdd/du
  pivots,                         // the forward dynamics' pivots: a local array, checked, not returned
  derived_parameters,             // the derived parameters, computed by the Constants from the parameters
};

/// 0 for a scalar, 1 for a vector, 2 for a matrix.
std::size_t rank(Array array);

/// One entry of an array a generated function writes.
struct Target {
  Array array = Array::mass_matrix;
  std::size_t row = 0;     ///< 0 for a scalar
  std::size_t column = 0;  ///< 0 for a vector or a scalar

  friend bool operator==(const Target& a, const Target& b) {
    return a.array == b.array && a.row == b.row && a.column == b.column;
  }
  friend bool operator<(const Target& a, const Target& b) {
    if (a.array != b.array) return a.array < b.array;
    return a.row != b.row ? a.row < b.row : a.column < b.column;
  }
};

struct Instruction {
  Op op;
  std::vector<std::size_t> args;  // indices of earlier instructions
  double number = 0.0;            // Op::number
  Variable variable;              // Op::variable: which input it reads
};

/// Where a computed value goes.
struct Assignment {
  Target target;
  std::size_t value;
};

struct Program {
  std::vector<Instruction> instructions;
  std::vector<Assignment> outputs;
};

/// a + b, or the largest count where that does not fit: a graph written out as a tree (the
/// articulated-body algorithm's, say) can need more than 2^64 operations
constexpr std::uint64_t saturating_sum(std::uint64_t a, std::uint64_t b) {
  return a > std::numeric_limits<std::uint64_t>::max() - b ? std::numeric_limits<std::uint64_t>::max() : a + b;
}

/// Floating-point operations of a program; an n-ary sum counts n - 1 additions
/// (subtractions included), a negation counts as an addition. Counts saturate at 2^64 - 1.
struct OperationCounts {
  std::uint64_t additions = 0;
  std::uint64_t multiplications = 0;
  std::uint64_t divisions = 0;
  std::uint64_t calls = 0;  // sqrt, sin, cos, pow, ...
  std::uint64_t total() const {
    return saturating_sum(saturating_sum(additions, multiplications), saturating_sum(divisions, calls));
  }
  friend OperationCounts operator+(const OperationCounts& a, const OperationCounts& b) {
    return {saturating_sum(a.additions, b.additions), saturating_sum(a.multiplications, b.multiplications),
            saturating_sum(a.divisions, b.divisions), saturating_sum(a.calls, b.calls)};
  }
};

/// Operations of the program as it is (each instruction once).
OperationCounts count_operations(const Program& program);
/// Operations if every output were evaluated as a separate tree, without any sharing: what
/// emitting the equations without common-subexpression elimination would cost.
OperationCounts count_operations_without_sharing(const Program& program);

/// True for ops that are functions (printed as calls): those of EOMGEN_IR_CALL_OPS.
bool is_call(Op op);
/// The row of EOMGEN_IR_CALL_OPS of a call op. \pre is_call(op)
const CallOp& call_op(Op op);

}  // namespace eomgen::ir
