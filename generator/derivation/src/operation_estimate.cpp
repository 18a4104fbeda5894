#include "operation_estimate.hpp"

#include <ginac/hash_map.h>

#include <cmath>
#include <unordered_set>

namespace eomgen {
namespace {

using GiNaC::ex;

// A sine or cosine takes about as long as this many multiplications (15 to 20 ns against under
// 1 ns in the peer benchmark); the local resolution trades products of rotations for calls on
// summed angles, which pays only while the calls are few. With 8 here the planar chain of 4 rods
// took the local form, 16 calls against 8, and its M and F ran at 0.57 of SymPy's speed.
constexpr double call_cost = 24;

class Estimate {
 public:
  Estimate(const Subexpressions& intermediates, const Variables& variables) : variables_(variables) {
    for (const auto& d : intermediates.definitions()) definitions_.emplace(d.symbol, &d.value);
  }

  double of(const ex& e) { return state_dependent(e) ? count(e) : 0; }

 private:
  // true when e depends on anything but parameters and numbers (intermediates included)
  bool state_dependent(const ex& e) {
    auto memo = dependent_.find(e);
    if (memo != dependent_.end()) return memo->second;
    bool result = false;
    if (GiNaC::is_a<GiNaC::symbol>(e)) {
      auto definition = definitions_.find(e);
      if (definition != definitions_.end()) {
        result = state_dependent(*definition->second);
      } else {
        const auto kind = variables_.kind_of(e);
        result = !kind || *kind != SymbolKind::parameter;
      }
    } else {
      for (std::size_t i = 0; i < e.nops() && !result; ++i) result = state_dependent(e.op(i));
    }
    dependent_.emplace(e, result);
    return result;
  }

  // operations of e, each distinct subexpression once (as emission's common-subexpression pass
  // does); the parameter-only operands of a sum or product count as one constant
  double count(const ex& e) {
    if (!state_dependent(e) || !counted_.insert(e).second) return 0;
    if (GiNaC::is_a<GiNaC::symbol>(e)) {
      auto definition = definitions_.find(e);
      return definition == definitions_.end() ? 0 : count(*definition->second);
    }
    double operations = 0, operands = 0;
    bool constant = false;
    for (std::size_t i = 0; i < e.nops(); ++i) {
      if (state_dependent(e.op(i))) {
        operations += count(e.op(i));
        ++operands;
      } else {
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
    if (GiNaC::is_a<GiNaC::function>(e)) return operations + call_cost;
    return operations;
  }

  const Variables& variables_;
  // hashed, not ordered: GiNaC's ordering compares whole trees, and only counts come out
  GiNaC::exhashmap<const ex*> definitions_;
  GiNaC::exhashmap<bool> dependent_;
  std::unordered_set<ex> counted_;
};

}  // namespace

double estimated_operations(const GiNaC::matrix& mass_matrix, const GiNaC::matrix& forcing,
                            const Subexpressions& intermediates, const Variables& variables) {
  Estimate estimate(intermediates, variables);
  double operations = 0;
  for (unsigned j = 0; j < mass_matrix.rows(); ++j) {
    for (unsigned k = j; k < mass_matrix.cols(); ++k) operations += estimate.of(mass_matrix(j, k));
    operations += estimate.of(forcing(j, 0));
  }
  return operations;
}

}  // namespace eomgen
