#include "eomgen/codegen/cpp_printer.hpp"

#include "eomgen/base/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <vector>

#include "eomgen/codegen/cpp_identifier.hpp"

namespace eomgen {
namespace {

using ir::Op;

// binding strength of what an instruction prints as
int precedence(Op op) {
  switch (op) {
    case Op::add: return 1;
    case Op::multiply:
    case Op::divide: return 2;
    case Op::negate: return 3;
    case Op::number:
    case Op::variable:
    EOMGEN_IR_CALL_OPS(EOMGEN_IR_CALL_CASE) return 4;
  }
  EOMGEN_UNREACHABLE("an ir::Op value that is not an enumerator");
}

class Printer {
 public:
  Printer(const ir::Program& p, const CppPrintOptions& o) : program_(p), options_(o), uses_(p.instructions.size(), 0),
        names_(p.instructions.size()) {
    for (const auto& in : p.instructions)
      for (std::size_t a : in.args) ++uses_[a];
    for (const auto& out : p.outputs) ++uses_[out.value];
    // a variable reads the same way at every use
    for (std::size_t i = 0; i < p.instructions.size(); ++i)
      if (p.instructions[i].op == Op::variable) names_[i] = cpp_variable(p.instructions[i].variable, o);
    // sin(x) and cos(x) are both computed before the first output is stored: the compiler
    // merges them into one sincos only then, since an output may alias the inputs x reads
    std::vector<int> trig(p.instructions.size(), 0);
    for (const auto& in : p.instructions)
      if (in.op == Op::sin || in.op == Op::cos) ++trig[in.args[0]];
    hoisted_.assign(p.instructions.size(), false);
    for (std::size_t i = 0; i < p.instructions.size(); ++i) {
      const ir::Instruction& in = p.instructions[i];
      hoisted_[i] = (in.op == Op::sin || in.op == Op::cos) && trig[in.args[0]] > 1;
    }
  }

  std::string run() {
    std::string body;
    std::size_t temporaries = 0;
    for (std::size_t i = 0; i < program_.instructions.size(); ++i) {
      const ir::Instruction& in = program_.instructions[i];
      if (in.op == Op::number || in.op == Op::variable || (uses_[i] <= 1 && !hoisted_[i]) || !options_.share_subexpressions)
        continue;
      names_[i] = fmt::format("{}{}", options_.temporary_prefix, temporaries++);
      body += fmt::format("{}const {} {} = {};\n", options_.indent, options_.scalar, names_[i], expression(i));
    }
    for (const ir::Assignment& out : program_.outputs)
      body += fmt::format("{}{} = {};\n", options_.indent, cpp_target(out.target, options_), operand(out.value, 0));
    return body;
  }

 private:
  // the text of instruction i where an operand of at least `needed` precedence is required
  std::string operand(std::size_t i, int needed) {
    const ir::Instruction& in = program_.instructions[i];
    if (!names_[i].empty()) return names_[i];
    const std::string text = expression(i);
    return precedence(in.op) < needed ? "(" + text + ")" : text;
  }

  std::string expression(std::size_t i) {
    const ir::Instruction& in = program_.instructions[i];
    switch (in.op) {
      case Op::number:
        return cpp_number(in.number, options_.scalar);
      case Op::variable:
        return names_[i];
      case Op::add: {
        // a non-negated term first, then " - x" for negated terms
        std::vector<std::size_t> terms = in.args;
        for (std::size_t k = 0; k < terms.size(); ++k)
          if (program_.instructions[terms[k]].op != Op::negate || !names_[terms[k]].empty()) {
            std::rotate(terms.begin(), terms.begin() + static_cast<long>(k), terms.begin() + static_cast<long>(k) + 1);
            break;
          }
        std::string s;
        for (std::size_t k = 0; k < terms.size(); ++k) {
          const ir::Instruction& t = program_.instructions[terms[k]];
          if (t.op == Op::negate && names_[terms[k]].empty()) {
            s += (k ? " - " : "-") + operand(t.args[0], 2);
          } else {
            s += (k ? " + " : "") + operand(terms[k], 1);
          }
        }
        return s;
      }
      case Op::multiply: {
        std::string s;
        for (std::size_t k = 0; k < in.args.size(); ++k) {
          // a negated factor is parenthesized: a * (-b)
          const int needed = program_.instructions[in.args[k]].op == Op::negate ? 4 : 2;
          s += (k ? " * " : "") + operand(in.args[k], needed);
        }
        return s;
      }
      case Op::divide:
        return operand(in.args[0], 2) + " / " + operand(in.args[1], 3);
      case Op::negate:
        return "-" + operand(in.args[0], 3);
      EOMGEN_IR_CALL_OPS(EOMGEN_IR_CALL_CASE) {
        std::string s = std::string(ir::call_op(in.op).cpp_name) + "(";
        for (std::size_t k = 0; k < in.args.size(); ++k) s += (k ? ", " : "") + operand(in.args[k], 0);
        return s + ")";
      }
    }
    EOMGEN_UNREACHABLE("an ir::Op value that is not an enumerator");
  }

  const ir::Program& program_;
  const CppPrintOptions& options_;
  std::vector<std::size_t> uses_;
  std::vector<std::string> names_;  // of a variable or a temporary: the text that stands for it
  std::vector<bool> hoisted_;        // computed as a temporary even where used once
};

}  // namespace

std::string cpp_number(double value, const std::string& scalar) {
  if (value == std::floor(value) && std::fabs(value) < 1e15) return fmt::format("{}({})", scalar, static_cast<long long>(value));
  // shortest text that reads back to the same double
  return fmt::format("{}({})", scalar, value);
}

const char* cpp_argument_name(ir::VariableKind kind) {
  switch (kind) {
    case ir::VariableKind::time: return "t";
    case ir::VariableKind::coordinate: return "q";
    case ir::VariableKind::rate: return "qd";
    case ir::VariableKind::input: return "u";
    case ir::VariableKind::parameter: return "p";
    case ir::VariableKind::derived_parameter: return "derived";
    case ir::VariableKind::acceleration: return "qdd";
    case ir::VariableKind::multiplier: return "lambda";
    case ir::VariableKind::constant: return "c";
  }
  EOMGEN_UNREACHABLE("an ir::VariableKind value that is not an enumerator");
}

const char* cpp_array_name(ir::Array array) {
  switch (array) {
    case ir::Array::mass_matrix: return "M";
    case ir::Array::forcing: return "F";
    case ir::Array::constraint_jacobian: return "Xi";
    case ir::Array::constraint_rate_term: return "Xi_t";
    case ir::Array::constraint_acceleration_term: return "b";
    case ir::Array::holonomic_residuals: return "phi";
    case ir::Array::outputs: return "y";
    case ir::Array::kinetic_energy: return "T";
    case ir::Array::potential_energy: return "V";
    case ir::Array::stiffness: return "K";
    case ir::Array::damping: return "D";
    case ir::Array::input_matrix: return "B_u";
    case ir::Array::acceleration_constraint_by_q: return "S_q";
    case ir::Array::acceleration_constraint_by_qd: return "S_qd";
    case ir::Array::generalized_forces: return "tau";
    case ir::Array::gravity_forces: return "G";
    case ir::Array::coriolis_matrix: return "C";
    case ir::Array::output_jacobian: return "J";
    case ir::Array::output_bias: return "Jdot_qd";
    case ir::Array::regressor: return "Y";
    case ir::Array::inertial_parameters: return "pi";
    case ir::Array::multipliers: return "lambda";
    case ir::Array::constants: return "k";
    case ir::Array::accelerations: return "qdd";
    case ir::Array::acceleration_by_coordinates: return "dqdd_dq";
    case ir::Array::acceleration_by_rates: return "dqdd_dqd";
    case ir::Array::acceleration_by_inputs: return "dqdd_du";
    case ir::Array::pivots: return "pivot";
    case ir::Array::derived_parameters: return "derived";
  }
  EOMGEN_UNREACHABLE("an ir::Array value that is not an enumerator");
}

std::string cpp_variable(const ir::Variable& variable, const CppPrintOptions& options) {
  const char* name = cpp_argument_name(variable.kind);
  switch (variable.kind) {
    case ir::VariableKind::time:
      return name;
    case ir::VariableKind::parameter:
      assert(variable.index < options.parameter_names.size());
      return fmt::format("{}.{}", options.parameters, cpp_identifier(options.parameter_names.at(variable.index)));
    case ir::VariableKind::derived_parameter:
      assert(variable.index < options.derived_parameter_names.size());
      return fmt::format("{}.{}", options.derived_parameters,
                         cpp_identifier(options.derived_parameter_names.at(variable.index)));
    case ir::VariableKind::constant:
      return fmt::format("{}.k{}", name, variable.index);
    case ir::VariableKind::coordinate:
    case ir::VariableKind::rate:
    case ir::VariableKind::input:
    case ir::VariableKind::acceleration:
    case ir::VariableKind::multiplier:
      return fmt::format("{}({})", name, variable.index);
  }
  EOMGEN_UNREACHABLE("an ir::VariableKind value that is not an enumerator");
}

std::string cpp_target(const ir::Target& target, const CppPrintOptions& options) {
  if (target.array != ir::Array::derived_parameters) return cpp_target(target);
  assert(target.row < options.derived_parameter_names.size());
  return fmt::format("{}.{}", options.derived_parameters, cpp_identifier(options.derived_parameter_names.at(target.row)));
}

std::string cpp_target(const ir::Target& target) {
  EOMGEN_DEMAND(target.array != ir::Array::derived_parameters,
                "cpp_target: a derived parameter's target printed without the names of the derived parameters");
  const char* name = cpp_array_name(target.array);
  // a constant is a named member of the Constants, not an entry of an array
  if (target.array == ir::Array::constants) return fmt::format("{}{}", name, target.row);
  const std::size_t rank = ir::rank(target.array);
  if (rank == 0) return name;
  if (rank == 1) return fmt::format("{}({})", name, target.row);
  return fmt::format("{}({}, {})", name, target.row, target.column);
}

std::string print_cpp(const ir::Program& program, const CppPrintOptions& options) {
  return Printer(program, options).run();
}

}  // namespace eomgen
