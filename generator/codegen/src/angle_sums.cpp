#include "eomgen/codegen/angle_sums.hpp"

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <map>
#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

#include "eomgen/base/error.hpp"

namespace eomgen {
namespace {

using ir::Op;

// A value of the program or its negation.
struct Signed {
  std::size_t value;
  bool negative;
};

// An angle as the sorted signed terms of its sum: q1 - q2 is {(q1, +), (q2, -)}.
using Term = std::pair<std::size_t, bool>;
using Angle = std::vector<Term>;

Angle negated(Angle a) {
  for (Term& t : a) t.second = !t.second;
  std::sort(a.begin(), a.end());
  return a;
}

// An angle whose sine and cosine can be had: `argument` is the value whose sine or cosine the
// program computes (a term of the sum, or a smaller sum), taken with a sign.
struct Part {
  std::size_t argument;
  bool negative;
};

struct Split {
  Part first, second;
};

enum class Trig { sine, cosine };

class AngleSums {
 public:
  explicit AngleSums(const ir::Program& program) : program_(program) {
    for (std::size_t i = 0; i < program.instructions.size(); ++i) {
      const ir::Instruction& in = program.instructions[i];
      if (in.op == Op::sin) calls_[in.args[0]].sine = i;
      if (in.op == Op::cos) calls_[in.args[0]].cosine = i;
    }
  }

  ir::Program run() {
    // sums first by their number of terms, so a sum's parts are decided before it
    std::vector<std::pair<std::size_t, std::size_t>> sums;  // (terms, argument)
    for (const auto& [argument, calls] : calls_)
      if (program_.instructions[argument].op == Op::add)
        sums.emplace_back(program_.instructions[argument].args.size(), argument);
    std::sort(sums.begin(), sums.end());
    if (sums.empty()) return program_;
    add_single_parts();
    for (const auto& [terms, argument] : sums) {
      const Angle angle = angle_of(argument);
      if (const std::optional<Split> split = split_of(angle)) splits_.emplace(argument, *split);
      add_sum_part(angle, argument);
    }
    if (splits_.empty()) return program_;
    code_ = program_.instructions;
    // the program's values, to share what the theorems build with what it has (only now: a long
    // chain's programs have no angle sums and a hundred thousand instructions)
    for (std::size_t i = 0; i < code_.size(); ++i)
      if (shareable(code_[i].op)) interned_.emplace(key(code_[i]), i);
    std::vector<std::size_t> replacement(code_.size());
    for (std::size_t i = 0; i < replacement.size(); ++i) replacement[i] = i;
    for (const auto& [argument, split] : splits_) {
      const Calls& calls = calls_.at(argument);
      if (calls.sine) replacement[*calls.sine] = materialized(trig(argument, Trig::sine));
      if (calls.cosine) replacement[*calls.cosine] = materialized(trig(argument, Trig::cosine));
    }
    return reemitted(replacement);
  }

 private:
  struct Calls {
    std::optional<std::size_t> sine, cosine;
  };

  static bool shareable(Op op) {
    return op == Op::add || op == Op::multiply || op == Op::negate || op == Op::sin || op == Op::cos;
  }

  // sums and products match whatever the order of their operands
  static std::pair<Op, std::vector<std::size_t>> key(const ir::Instruction& in) {
    std::vector<std::size_t> args = in.args;
    if (in.op == Op::add || in.op == Op::multiply) std::sort(args.begin(), args.end());
    return {in.op, std::move(args)};
  }

  std::size_t instruction(Op op, std::vector<std::size_t> args) {
    ir::Instruction in{op, std::move(args), 0.0, {}};
    if (op == Op::add || op == Op::multiply) std::sort(in.args.begin(), in.args.end());
    const auto [it, inserted] = interned_.emplace(key(in), code_.size());
    if (inserted) code_.push_back(std::move(in));
    return it->second;
  }

  // (of the program's own instructions only)
  Angle angle_of(std::size_t value) const {
    const std::vector<ir::Instruction>& code = program_.instructions;
    Angle angle;
    if (code[value].op != Op::add) return {{value, false}};
    for (std::size_t term : code[value].args) {
      if (code[term].op == Op::negate) angle.emplace_back(code[term].args[0], true);
      else angle.emplace_back(term, false);
    }
    std::sort(angle.begin(), angle.end());
    return angle;
  }

  // An additive hash of an angle: the hash of a sum of two parts is the sum of theirs, so the
  // part that completes a given one is found by one lookup instead of a search over all pairs
  // (a chain's outputs take sines of a hundred nested sums).
  static std::uint64_t hash_of(const Term& t) {
    std::uint64_t z = (static_cast<std::uint64_t>(t.first) << 1 | (t.second ? 1u : 0u)) + 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  static std::uint64_t hash_of(const Angle& a) {
    std::uint64_t h = 0;
    for (const Term& t : a) h += hash_of(t);
    return h;
  }

  // an angle whose sine and cosine are at hand, as a part of larger ones
  void add_part(Angle angle, Part part) {
    const std::uint64_t h = hash_of(angle);
    by_hash_.emplace(h, parts_.size());
    parts_.push_back({std::move(angle), part, h});
  }

  // every argument of a call, either way round, before any sum is split
  void add_single_parts() {
    for (const auto& [argument, calls] : calls_)
      for (const bool negative : {false, true}) add_part(Angle{{argument, negative}}, Part{argument, negative});
  }

  void add_sum_part(const Angle& angle, std::size_t argument) {
    add_part(angle, Part{argument, false});
    add_part(negated(angle), Part{argument, true});
  }

  static Angle without(const Angle& whole, const Angle& part) {
    Angle rest;
    std::set_difference(whole.begin(), whole.end(), part.begin(), part.end(), std::back_inserter(rest));
    return rest;
  }

  // the angle as two parts at hand, the larger as large as can be (the fewest new values down
  // the line; the first such split in the parts' order); nothing when no split has both parts
  std::optional<Split> split_of(const Angle& angle) const {
    const std::uint64_t whole = hash_of(angle);
    std::optional<Split> best;
    std::size_t best_size = 0;
    for (const PartEntry& first : parts_) {
      if (first.angle.size() >= angle.size() || 2 * first.angle.size() < angle.size()) continue;
      if (first.angle.size() <= best_size) continue;
      const auto [from, to] = by_hash_.equal_range(whole - first.hash);
      for (auto it = from; it != to; ++it) {
        const PartEntry& second = parts_[it->second];
        // the hashes may collide; the terms decide (with the sizes adding up, angle less first
        // equal to second means first is a part of angle)
        if (first.angle.size() + second.angle.size() != angle.size()) continue;
        if (without(angle, first.angle) != second.angle) continue;
        best = Split{first.part, second.part};
        best_size = first.angle.size();
        break;
      }
    }
    return best;
  }

  // sin or cos of the value `argument`: by its split, or the program's call (a new call for the
  // partner of a computed one, which the compiler merges with it into one sincos)
  Signed trig(std::size_t argument, Trig f) {
    const auto memo = trig_memo_.find({argument, f});
    if (memo != trig_memo_.end()) return memo->second;
    Signed result{0, false};
    if (const auto split = splits_.find(argument); split != splits_.end()) {
      const Part a = split->second.first, b = split->second.second;
      const Signed sa = of(a, Trig::sine), ca = of(a, Trig::cosine), sb = of(b, Trig::sine), cb = of(b, Trig::cosine);
      result = f == Trig::sine ? sum(product(sa, cb), product(ca, sb), false) : sum(product(ca, cb), product(sa, sb), true);
    } else {
      const Op op = f == Trig::sine ? Op::sin : Op::cos;
      result = Signed{instruction(op, {argument}), false};
    }
    trig_memo_.emplace(std::make_pair(argument, f), result);
    return result;
  }

  // sin is odd, cos even
  Signed of(const Part& p, Trig f) {
    Signed s = trig(p.argument, f);
    if (f == Trig::sine && p.negative) s.negative = !s.negative;
    return s;
  }

  Signed product(Signed a, Signed b) {
    return Signed{instruction(Op::multiply, {a.value, b.value}), a.negative != b.negative};
  }

  // a + b, or a - b
  Signed sum(Signed a, Signed b, bool subtract) {
    if (subtract) b.negative = !b.negative;
    if (a.negative && b.negative) return Signed{instruction(Op::add, {a.value, b.value}), true};
    return Signed{instruction(Op::add, {materialized(a), materialized(b)}), false};
  }

  std::size_t materialized(Signed s) { return s.negative ? instruction(Op::negate, {s.value}) : s.value; }

  // the instructions the outputs need, depth first from the outputs in their order, as the
  // lowering emits them
  ir::Program reemitted(const std::vector<std::size_t>& replacement) const {
    const auto source = [&](std::size_t i) { return i < replacement.size() ? replacement[i] : i; };
    std::vector<std::size_t> order(code_.size(), SIZE_MAX);
    ir::Program result;
    std::vector<std::pair<std::size_t, bool>> stack;
    for (const ir::Assignment& out : program_.outputs) {
      const std::size_t root = source(out.value);
      stack.push_back({root, false});
      while (!stack.empty()) {
        const auto [n, expanded] = stack.back();
        stack.pop_back();
        if (order[n] != SIZE_MAX) continue;
        if (!expanded) {
          stack.push_back({n, true});
          for (auto a = code_[n].args.rbegin(); a != code_[n].args.rend(); ++a)
            if (order[source(*a)] == SIZE_MAX) stack.push_back({source(*a), false});
          continue;
        }
        ir::Instruction in = code_[n];
        for (std::size_t& a : in.args) {
          a = order[source(a)];
          EOMGEN_DEMAND(a != SIZE_MAX, "angle sums: an operand emitted after its use");
        }
        order[n] = result.instructions.size();
        result.instructions.push_back(std::move(in));
      }
      result.outputs.push_back(ir::Assignment{out.target, order[root]});
    }
    return result;
  }

  const ir::Program& program_;
  std::vector<ir::Instruction> code_;  // the program's instructions, then the new ones (once rewriting)
  std::map<std::pair<Op, std::vector<std::size_t>>, std::size_t> interned_;
  std::map<std::size_t, Calls> calls_;       // by argument
  struct PartEntry {
    Angle angle;
    Part part;
    std::uint64_t hash;
  };
  std::vector<PartEntry> parts_;  // the angles at hand: the calls' arguments, then the sums decided so far
  std::unordered_multimap<std::uint64_t, std::size_t> by_hash_;  // into parts_
  std::map<std::size_t, Split> splits_;      // by argument: the sums rewritten
  std::map<std::pair<std::size_t, Trig>, Signed> trig_memo_;
};

}  // namespace

ir::Program expand_angle_sums(const ir::Program& program) { return AngleSums(program).run(); }

}  // namespace eomgen
