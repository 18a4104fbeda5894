#include "operation_estimate.hpp"

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "eomgen/symbolic/expression_map.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;

// A sine or cosine takes about as long as this many multiplications (15 to 20 ns against under
// 1 ns in the peer benchmark); the local resolution trades products of rotations for calls on
// summed angles, which pays only while the calls are few. With 8 here the planar chain of 4 rods
// took the local form, 16 calls against 8, and its M and F ran at 0.57 of SymPy's speed.
constexpr double call_cost = 24;
// Emission merges what sin and cos of one argument cost into one call (codegen/angle_sums.hpp:
// the compiler makes them one sincos), and computes those of a sum whose terms have sines or
// cosines of their own by the addition theorems: two products and a sum each.
constexpr double angle_sum_cost = 3;

// a local static, not one at namespace scope: GiNaC's numbers must exist before it is built
bool is_minus_one(const ex& e) {
  static const ex minus_one = -1;
  return e.is_equal(minus_one);
}

class Estimate {
 public:
  Estimate(const std::vector<const Subexpressions*>& intermediates, const Variables& variables) : variables_(variables) {
    for (const Subexpressions* z : intermediates)
      for (const auto& d : z->definitions()) definitions_.emplace(d.symbol, &d.value);
  }

  double of(const ex& e) { return count(e); }

  /// The sines and cosines met by of(): one call per argument, or the addition theorems' few
  /// operations for an angle sum whose terms' sines or cosines are computed anyway.
  double trigonometric_calls() {
    const auto has_call = [&](const ex& term) { return trig_.contains(term) || trig_.contains(-term); };
    double operations = 0;
    for (const auto& [argument, functions] : trig_arguments_) {
      bool parts_at_hand = GiNaC::is_a<GiNaC::add>(argument);
      for (std::size_t i = 0; i < argument.nops() && parts_at_hand; ++i) parts_at_hand = has_call(argument.op(i));
      operations += parts_at_hand ? angle_sum_cost * functions : call_cost;
    }
    return operations;
  }

 private:
  struct Facts {
    bool dependent = false;  // on anything but parameters and numbers (intermediates included)
    bool counted = false;    // its operations are in the total already
  };

  // the facts of e, its dependence worked out on first sight (references stay valid: the
  // table is node-based)
  Facts& facts(const ex& e) {
    if (Facts* memo = facts_.find(e)) return *memo;
    bool dependent = false;
    if (GiNaC::is_a<GiNaC::symbol>(e)) {
      if (const ex* const* definition = definitions_.find(e)) {
        dependent = facts(**definition).dependent;
      } else {
        const auto kind = variables_.kind_of(e);
        dependent = !kind || !is_parameter_kind(*kind);
      }
    } else {
      for (std::size_t i = 0; i < e.nops() && !dependent; ++i) dependent = facts(e.op(i)).dependent;
    }
    return *facts_.emplace(e, Facts{dependent, false}).first;
  }

  // operations of e, each distinct subexpression once (as emission's common-subexpression pass
  // does); the parameter-only operands of a sum or product count as one constant. A value and
  // its negation are one node, as emission shares them: GiNaC writes a - b in one process where
  // it writes -(b - a) in another, and counting both would make the estimate, and the choice it
  // makes, differ between runs.
  double count(const ex& e) {
    Facts& f = facts(e);
    if (!f.dependent || f.counted) return 0;
    f.counted = true;
    if (GiNaC::is_a<GiNaC::symbol>(e)) {
      const ex* const* definition = definitions_.find(e);
      return definition == nullptr ? 0 : count(**definition);
    }
    const bool signed_node = GiNaC::is_a<GiNaC::add>(e) || GiNaC::is_a<GiNaC::mul>(e);
    if (!signed_node) return operations_of(e);
    const ex negation = -e;
    if (facts(negation).counted) return 0;
    const double operations = operations_of(e);
    facts(negation).counted = true;
    return operations;
  }

  // the operations of e itself and of its operands not counted yet
  double operations_of(const ex& e) {
    double operations = 0, operands = 0;
    bool constant = false;
    for (std::size_t i = 0; i < e.nops(); ++i) {
      const ex operand = e.op(i);  // op() of a sum or product may build a new object: once
      if (facts(operand).dependent) {
        operations += count(operand);
        ++operands;
      } else if (!is_minus_one(operand)) {
        // a factor -1 costs nothing: emission folds the sign into a subtraction
        constant = true;
      }
    }
    if (GiNaC::is_a<GiNaC::add>(e) || GiNaC::is_a<GiNaC::mul>(e)) return operations + operands + (constant ? 1 : 0) - 1;
    if (GiNaC::is_a<GiNaC::power>(e)) {
      const ex exponent = e.op(1);
      if (GiNaC::is_a<GiNaC::numeric>(exponent) && GiNaC::ex_to<GiNaC::numeric>(exponent).is_integer()) {
        const double k = std::abs(GiNaC::ex_to<GiNaC::numeric>(exponent).to_double());
        return operations + (k - 1) + (exponent.info(GiNaC::info_flags::negative) ? 1 : 0);
      }
      return operations + 1;
    }
    if (GiNaC::is_a<GiNaC::function>(e)) {
      const std::string name = GiNaC::ex_to<GiNaC::function>(e).get_name();
      if ((name != "sin" && name != "cos") || e.nops() != 1) return operations + call_cost;
      if (const std::size_t* k = trig_.find(e.op(0))) {
        ++trig_arguments_[*k].second;
      } else {
        trig_.emplace(e.op(0), trig_arguments_.size());
        trig_arguments_.emplace_back(e.op(0), 1);
      }
      return operations;
    }
    return operations;
  }

  const Variables& variables_;
  // by value, looked up only: only counts come out
  ExpressionMap<const ex*> definitions_;
  ExpressionMap<Facts> facts_;
  // the arguments of sin and cos, and how many of the two each has
  ExpressionMap<std::size_t> trig_;
  std::vector<std::pair<ex, int>> trig_arguments_;
};

}  // namespace

double estimated_operations(const GiNaC::matrix& mass_matrix, const GiNaC::matrix& forcing,
                            const Subexpressions& intermediates, const Variables& variables) {
  Estimate estimate({&intermediates}, variables);
  double operations = 0;
  for (unsigned j = 0; j < mass_matrix.rows(); ++j) {
    for (unsigned k = j; k < mass_matrix.cols(); ++k) operations += estimate.of(mass_matrix(j, k));
    operations += estimate.of(forcing(j, 0));
  }
  return operations + estimate.trigonometric_calls();
}

double estimated_operations(const GiNaC::exvector& entries, const std::vector<const Subexpressions*>& intermediates,
                            const Variables& variables) {
  Estimate estimate(intermediates, variables);
  double operations = 0;
  for (const ex& e : entries) operations += estimate.of(e);
  return operations + estimate.trigonometric_calls();
}

}  // namespace eomgen
