#include "eomgen/codegen/parameter_constants.hpp"

#include <cstring>
#include <map>
#include <tuple>

#include "eomgen/base/error.hpp"

namespace eomgen {
namespace {

using ir::Instruction;
using ir::Op;

// a program under construction in which equal instructions are one
class ProgramBuilder {
 public:
  std::size_t add(Instruction in) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &in.number, sizeof bits);
    const auto key = std::make_tuple(in.op, in.args, bits, in.variable);
    const auto it = interned_.find(key);
    if (it != interned_.end()) return it->second;
    program.instructions.push_back(std::move(in));
    interned_.emplace(key, program.instructions.size() - 1);
    return program.instructions.size() - 1;
  }

  ir::Program program;

 private:
  std::map<std::tuple<Op, std::vector<std::size_t>, std::uint64_t, ir::Variable>, std::size_t> interned_;
};

Instruction operation(Op op, std::vector<std::size_t> args) { return Instruction{op, std::move(args), 0.0, {}}; }

// depends on parameters and numbers only
std::vector<bool> classify(const ir::Program& program) {
  std::vector<bool> constant(program.instructions.size(), false);
  for (std::size_t i = 0; i < program.instructions.size(); ++i) {
    const Instruction& in = program.instructions[i];
    EOMGEN_DEMAND(!(in.op == Op::variable && in.variable.kind == ir::VariableKind::constant),
                  "split_constants: a program already reads the constants");
    bool all = !in.args.empty();
    for (std::size_t a : in.args) all = all && constant[a];
    const bool parameter = in.op == Op::variable && (in.variable.kind == ir::VariableKind::parameter ||
                                                     in.variable.kind == ir::VariableKind::derived_parameter);
    constant[i] = in.op == Op::number || parameter || all;
  }
  return constant;
}

class Splitter {
 public:
  ir::Program split(const ir::Program& program) {
    const std::vector<bool> constant = classify(program);
    // pooled: the index in pool_ of a constant instruction; placed: in the per-call program
    std::vector<std::size_t> pooled(program.instructions.size(), SIZE_MAX), placed = pooled;
    ProgramBuilder call;
    for (std::size_t i = 0; i < program.instructions.size(); ++i) {
      Instruction in = program.instructions[i];
      if (constant[i]) {
        for (std::size_t& a : in.args) a = pooled[a];
        pooled[i] = pool_.add(std::move(in));
      } else {
        placed[i] = call.add(per_call(in, constant, pooled, placed, call));
      }
    }
    for (const ir::Assignment& out : program.outputs)
      call.program.outputs.push_back(
          {out.target, constant[out.value] ? read(pooled[out.value], call) : placed[out.value]});
    return std::move(call.program);
  }

  // the constants in order of their numbers, each computed once
  ir::Program constants() const {
    std::vector<bool> needed(pool_.program.instructions.size(), false);
    for (std::size_t root : roots_) needed[root] = true;
    for (std::size_t i = needed.size(); i-- > 0;)
      if (needed[i])
        for (std::size_t a : pool_.program.instructions[i].args) needed[a] = true;
    ProgramBuilder built;
    std::vector<std::size_t> at(needed.size(), SIZE_MAX);
    for (std::size_t i = 0; i < needed.size(); ++i) {
      if (!needed[i]) continue;
      Instruction in = pool_.program.instructions[i];
      for (std::size_t& a : in.args) a = at[a];
      at[i] = built.add(std::move(in));
    }
    for (std::size_t k = 0; k < roots_.size(); ++k)
      built.program.outputs.push_back({{ir::Array::constants, k, 0}, at[roots_[k]]});
    return std::move(built.program);
  }

 private:
  // a parameter or a number, possibly negated: read where it is used, as the code always did
  bool trivial(std::size_t j) const {
    const Instruction& in = pool_.program.instructions[j];
    return in.op == Op::number || in.op == Op::variable || (in.op == Op::negate && trivial(in.args[0]));
  }

  // how a call reads pooled value j: a trivial one as it is, any other as its constant
  std::size_t read(std::size_t j, ProgramBuilder& call) {
    Instruction in = pool_.program.instructions[j];
    if (trivial(j)) {
      for (std::size_t& a : in.args) a = read(a, call);
      return call.add(std::move(in));
    }
    auto [it, inserted] = numbers_.emplace(j, roots_.size());
    if (inserted) roots_.push_back(j);
    return call.add(Instruction{Op::variable, {}, 0.0, {ir::VariableKind::constant, it->second}});
  }

  // a state-dependent instruction with its constant operands read as constants
  Instruction per_call(Instruction in, const std::vector<bool>& constant, const std::vector<std::size_t>& pooled,
                       const std::vector<std::size_t>& placed, ProgramBuilder& call) {
    // x / c = x * (1 / c): the reciprocal is computed once, and a multiplication is cheaper
    if (in.op == Op::divide && constant[in.args[1]] &&
        pool_.program.instructions[pooled[in.args[1]]].op != Op::number) {
      const std::size_t one = pool_.add(Instruction{Op::number, {}, 1.0, {}});
      const std::size_t reciprocal = pool_.add(operation(Op::divide, {one, pooled[in.args[1]]}));
      return operation(Op::multiply, {placed[in.args[0]], read(reciprocal, call)});
    }
    std::vector<std::size_t> constant_args;
    for (std::size_t a : in.args)
      if (constant[a]) constant_args.push_back(pooled[a]);
    const bool grouped = (in.op == Op::add || in.op == Op::multiply) && constant_args.size() >= 2;
    // the constant operands of a sum or product are one constant, where the first of them was
    const std::size_t group = grouped ? pool_.add(operation(in.op, constant_args)) : SIZE_MAX;
    std::vector<std::size_t> args;
    bool group_placed = false;
    for (std::size_t a : in.args) {
      if (!constant[a]) {
        args.push_back(placed[a]);
      } else if (!grouped) {
        args.push_back(read(pooled[a], call));
      } else if (!group_placed) {
        args.push_back(read(group, call));
        group_placed = true;
      }
    }
    in.args = std::move(args);
    return in;
  }

  ProgramBuilder pool_;                         // every constant value met, in order of meeting
  std::vector<std::size_t> roots_;              // the pooled value of constant k
  std::map<std::size_t, std::size_t> numbers_;  // pooled value -> its constant's number
};

}  // namespace

ConstantSplit split_constants(const std::vector<ir::Program>& programs) {
  Splitter splitter;
  ConstantSplit split;
  for (const ir::Program& program : programs) split.per_call.push_back(splitter.split(program));
  split.constants = splitter.constants();
  return split;
}

}  // namespace eomgen
