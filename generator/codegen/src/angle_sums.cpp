#include "eomgen/codegen/angle_sums.hpp"

#include <algorithm>
#include <iterator>
#include <map>
#include <optional>
#include <tuple>
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
  std::size_t size;  // terms
};

struct Split {
  Part first, second;
};

enum class Trig { sine, cosine };

class AngleSums {
 public:
  explicit AngleSums(const ir::Program& program) : program_(program), code_(program.instructions) {
    for (std::size_t i = 0; i < code_.size(); ++i) {
      const ir::Instruction& in = code_[i];
      if (in.op == Op::sin) calls_[in.args[0]].sine = i;
      if (in.op == Op::cos) calls_[in.args[0]].cosine = i;
      if (shareable(in.op)) interned_.emplace(key(in), i);
    }
  }

  ir::Program run() {
    // sums first by their number of terms, so a sum's parts are decided before it
    std::vector<std::pair<std::size_t, std::size_t>> sums;  // (terms, argument)
    for (const auto& [argument, calls] : calls_)
      if (code_[argument].op == Op::add) sums.emplace_back(code_[argument].args.size(), argument);
    std::sort(sums.begin(), sums.end());
    for (const auto& [terms, argument] : sums) {
      const Angle angle = angle_of(argument);
      if (const std::optional<Split> split = split_of(angle)) splits_.emplace(argument, *split);
      available_.emplace(angle, argument);
    }
    if (splits_.empty()) return program_;
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

  Angle angle_of(std::size_t value) const {
    Angle angle;
    if (code_[value].op != Op::add) return {{value, false}};
    for (std::size_t term : code_[value].args) {
      if (code_[term].op == Op::negate) angle.emplace_back(code_[term].args[0], true);
      else angle.emplace_back(term, false);
    }
    std::sort(angle.begin(), angle.end());
    return angle;
  }

  // the angle as one part: a term whose sine or cosine is computed, or a sum met before
  std::optional<Part> part(const Angle& angle) const {
    if (angle.size() == 1) {
      if (calls_.count(angle[0].first)) return Part{angle[0].first, angle[0].second, 1};
      return std::nullopt;
    }
    if (const auto it = available_.find(angle); it != available_.end()) return Part{it->second, false, angle.size()};
    if (const auto it = available_.find(negated(angle)); it != available_.end())
      return Part{it->second, true, angle.size()};
    return std::nullopt;
  }

  static Angle without(const Angle& whole, const Angle& part) {
    Angle rest;
    std::set_difference(whole.begin(), whole.end(), part.begin(), part.end(), std::back_inserter(rest));
    return rest;
  }

  // the angle as two parts, the larger first and as large as can be (the fewest new values
  // down the line); nothing when no split has both parts at hand
  std::optional<Split> split_of(const Angle& angle) const {
    std::vector<std::pair<Angle, Part>> candidates;
    for (const Term& t : angle)
      if (const std::optional<Part> p = part({t})) candidates.emplace_back(Angle{t}, *p);
    for (const auto& [sum, argument] : available_) {
      if (sum.size() >= angle.size()) continue;
      if (std::includes(angle.begin(), angle.end(), sum.begin(), sum.end()))
        candidates.emplace_back(sum, Part{argument, false, sum.size()});
      const Angle opposite = negated(sum);
      if (std::includes(angle.begin(), angle.end(), opposite.begin(), opposite.end()))
        candidates.emplace_back(opposite, Part{argument, true, sum.size()});
    }
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const auto& a, const auto& b) { return a.first.size() > b.first.size(); });
    for (const auto& [taken, first] : candidates)
      if (const std::optional<Part> second = part(without(angle, taken))) return Split{first, *second};
    return std::nullopt;
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
  std::vector<ir::Instruction> code_;  // the program's instructions, then the new ones
  std::map<std::pair<Op, std::vector<std::size_t>>, std::size_t> interned_;
  std::map<std::size_t, Calls> calls_;       // by argument
  std::map<Angle, std::size_t> available_;  // sums with a sine or cosine, decided so far
  std::map<std::size_t, Split> splits_;      // by argument: the sums rewritten
  std::map<std::pair<std::size_t, Trig>, Signed> trig_memo_;
};

}  // namespace

ir::Program expand_angle_sums(const ir::Program& program) { return AngleSums(program).run(); }

}  // namespace eomgen
