// Differentiation and substitution over the graph of shared nodes (graph_calculus.hpp).
#include "eomgen/symbolic/graph_calculus.hpp"
#include "eomgen/symbolic/operand.hpp"

#include <map>
#include <utility>
#include <vector>

#include "eomgen/symbolic/expression_map.hpp"
#include "eomgen/symbolic/expression_size.hpp"

namespace eomgen {
namespace detail {

using GiNaC::ex;

constexpr double small_tree = small_tree_limit;

bool fits(const ex& e, double& budget) {
  if (--budget < 0) return false;
  if (e.nops() == 0) return true;
  if (const GiNaC::epvector* pairs = sum_pairs(e)) {
    // a term c*x counts as the product of x and c
    for (const GiNaC::expair& pair : *pairs) {
      if (!pair.coeff.is_equal(1)) budget -= 2;
      if (!fits(pair.rest, budget)) return false;
    }
    return pairs->size() == e.nops() || --budget >= 0;  // the sum's number
  }
  for (std::size_t i = 0; i < e.nops(); ++i)
    if (!fits(e.op(i), budget)) return false;
  return true;
}

// Builds nodes. GiNaC's evaluation of a node may walk its operands as a tree (a sum with a
// number among its terms asks its first term for its return type, a product asks every factor,
// a function asks its first argument, and which term comes first follows hash values that differ
// between processes), so a node over a large graph is built held, with only the simplifications
// by zeros and ones that keep a substitution of numbers from leaving dead terms. A node whose
// tree is small, or whose operands are all numbers, is evaluated as GiNaC would.
class NodeBuilder {
 public:
  ex sum(const GiNaC::exvector& terms) {
    if (evaluates(terms)) return terms.empty() ? ex(0) : ex(GiNaC::add(terms));
    GiNaC::exvector kept;
    for (const ex& term : terms)
      if (!term.is_zero()) kept.push_back(term);
    if (kept.empty()) return 0;
    if (kept.size() == 1) return kept.front();
    return GiNaC::add(kept).hold();
  }
  ex product(const GiNaC::exvector& factors) {
    if (evaluates(factors)) return GiNaC::mul(factors);
    GiNaC::exvector kept;
    GiNaC::numeric coefficient = 1;
    for (const ex& factor : factors) {
      if (factor.is_zero()) return 0;
      if (GiNaC::is_a<GiNaC::numeric>(factor))
        coefficient *= GiNaC::ex_to<GiNaC::numeric>(factor);
      else
        kept.push_back(factor);
    }
    if (kept.empty()) return coefficient;
    if (coefficient.is_equal(1) && kept.size() == 1) return kept.front();
    if (kept.size() == 1 && GiNaC::is_a<GiNaC::add>(kept.front())) {
      // a number times one sum, distributed as GiNaC's evaluation would: a sum holding it as a
      // term keeps the pair (sum, number) and builds the distributed sum anew, new nodes and
      // all, each time the term is read, so every walk over it would start afresh
      GiNaC::exvector terms;
      for (std::size_t i = 0; i < kept.front().nops(); ++i) terms.push_back(product({coefficient, kept.front().op(i)}));
      return sum(terms);
    }
    if (!coefficient.is_equal(1)) kept.push_back(coefficient);
    return GiNaC::mul(kept).hold();
  }
  ex power(const ex& base, const ex& exponent) {
    if (evaluates({base, exponent})) return GiNaC::pow(base, exponent);
    if (exponent.is_zero()) return 1;
    if (exponent.is_equal(1)) return base;
    return GiNaC::power(base, exponent).hold();
  }
  ex function(unsigned serial, const GiNaC::exvector& arguments) {
    const GiNaC::function f(serial, arguments);
    return evaluates(arguments) ? ex(f) : f.hold();
  }
  /// A node of e's kind with new operands.
  /// \pre e is a sum, a product, a power or a function
  ex like(const ex& e, const GiNaC::exvector& operands) {
    if (GiNaC::is_a<GiNaC::add>(e)) return sum(operands);
    if (GiNaC::is_a<GiNaC::mul>(e)) return product(operands);
    if (GiNaC::is_a<GiNaC::power>(e)) return power(operands[0], operands[1]);
    return function(GiNaC::ex_to<GiNaC::function>(e).get_serial(), operands);
  }

 private:
  bool evaluates(const GiNaC::exvector& operands) {
    double size = 1;
    bool numbers = true;
    for (const ex& operand : operands) {
      size += sizes_.tree(operand);
      numbers = numbers && GiNaC::is_a<GiNaC::numeric>(operand);
    }
    return numbers || size <= small_tree;
  }

  ExpressionSizes sizes_;
};

bool is_node(const ex& e) {
  return GiNaC::is_a<GiNaC::add>(e) || GiNaC::is_a<GiNaC::mul>(e) || GiNaC::is_a<GiNaC::power>(e) ||
         GiNaC::is_a<GiNaC::function>(e);
}

class Substitution {
 public:
  Substitution(const GiNaC::exmap& values, NodeBuilder& build) : values_(values), build_(build) {}

  ex of(const ex& e) {
    if (GiNaC::is_a<GiNaC::symbol>(e)) {
      const auto it = values_.find(e);
      return it == values_.end() ? e : it->second;
    }
    if (e.nops() == 0) return e;
    if (const ex* known = memo_.find(e)) return *known;
    GiNaC::exvector operands;
    bool changed = false;
    for (std::size_t i = 0; i < e.nops(); ++i) {
      const ex o = operand(e, i);
      operands.push_back(of(o));
      changed = changed || !operands.back().is_equal(o);
    }
    const ex result = !changed        ? e
                      : is_node(e) ? build_.like(e, operands)
                                   : e.subs(values_, GiNaC::subs_options::no_pattern);
    memo_.emplace(e, result);
    return result;
  }

 private:
  const GiNaC::exmap& values_;
  NodeBuilder& build_;
  ExpressionMap<ex> memo_;
};

// The partial derivative of a function with respect to its argument i, taken by GiNaC once per
// function and argument in dummy arguments, into which the arguments are then substituted.
class FunctionPartials {
 public:
  explicit FunctionPartials(NodeBuilder& build) : build_(build) {}

  ex at(const ex& f, std::size_t i) {
    const GiNaC::function& fn = GiNaC::ex_to<GiNaC::function>(f);
    const std::size_t n = f.nops();
    while (dummies_.size() < n) dummies_.emplace_back();
    const auto key = std::make_pair(fn.get_serial(), std::make_pair(n, i));
    auto it = partials_.find(key);
    if (it == partials_.end()) {
      GiNaC::exvector arguments(dummies_.begin(), dummies_.begin() + static_cast<long>(n));
      const ex general = GiNaC::function(fn.get_serial(), arguments);
      it = partials_.emplace(key, general.diff(dummies_[i])).first;
    }
    GiNaC::exmap arguments;
    for (std::size_t j = 0; j < n; ++j) arguments[dummies_[j]] = f.op(j);
    return Substitution(arguments, build_).of(it->second);
  }

 private:
  NodeBuilder& build_;
  std::vector<GiNaC::symbol> dummies_;
  std::map<std::pair<unsigned, std::pair<std::size_t, std::size_t>>, ex> partials_;
};

class Directional {
 public:
  Directional(const GiNaC::exmap& rates, NodeBuilder& build) : rates_(rates), build_(build), partials_(build) {}

  ex of(const ex& e) {
    if (GiNaC::is_a<GiNaC::symbol>(e)) {
      const auto it = rates_.find(e);
      return it == rates_.end() ? ex(0) : it->second;
    }
    if (e.nops() == 0) return 0;
    if (const ex* known = memo_.find(e)) return *known;
    const ex d = compute(e);
    memo_.emplace(e, d);
    return d;
  }

 private:
  ex compute(const ex& e) {
    GiNaC::exvector terms;
    if (GiNaC::is_a<GiNaC::add>(e)) {
      for (std::size_t i = 0; i < e.nops(); ++i)
        if (const ex d = of(operand(e, i)); !d.is_zero()) terms.push_back(d);
      return build_.sum(terms);
    }
    if (GiNaC::is_a<GiNaC::mul>(e)) {
      // the product rule: each factor differentiated, times the others
      for (std::size_t i = 0; i < e.nops(); ++i) {
        const ex d = of(e.op(i));
        if (d.is_zero()) continue;
        GiNaC::exvector factors{d};
        for (std::size_t j = 0; j < e.nops(); ++j)
          if (j != i) factors.push_back(e.op(j));
        terms.push_back(build_.product(factors));
      }
      return build_.sum(terms);
    }
    if (GiNaC::is_a<GiNaC::power>(e)) {
      const ex base = e.op(0), exponent = e.op(1);
      const ex db = of(base);
      if (GiNaC::is_a<GiNaC::numeric>(exponent))
        return db.is_zero() ? ex(0) : build_.product({exponent, build_.power(base, exponent - 1), db});
      // d(b^k) = b^k (dk log b + k db / b)
      const ex dk = of(exponent);
      if (!dk.is_zero()) terms.push_back(build_.product({dk, build_.function(GiNaC::log_SERIAL::serial, {base})}));
      if (!db.is_zero()) terms.push_back(build_.product({exponent, db, build_.power(base, -1)}));
      return terms.empty() ? ex(0) : build_.product({e, build_.sum(terms)});
    }
    if (GiNaC::is_a<GiNaC::function>(e)) {
      // the chain rule through each argument
      for (std::size_t i = 0; i < e.nops(); ++i) {
        const ex d = of(e.op(i));
        if (!d.is_zero()) terms.push_back(build_.product({partials_.at(e, i), d}));
      }
      return build_.sum(terms);
    }
    // nothing the derivation builds: GiNaC's own rule, symbol by symbol
    for (const auto& [symbol, rate] : rates_)
      terms.push_back(build_.product({e.diff(GiNaC::ex_to<GiNaC::symbol>(symbol)), rate}));
    return build_.sum(terms);
  }

  const GiNaC::exmap& rates_;
  NodeBuilder& build_;
  ExpressionMap<ex> memo_;
  FunctionPartials partials_;
};

}  // namespace detail

using GiNaC::ex;
using detail::fits;
using detail::NodeBuilder;
using detail::small_tree;

bool is_small_tree(const ex& e, double limit) {
  double budget = limit;
  return fits(e, budget);
}

ex derivative(const ex& e, const GiNaC::symbol& x) {
  if (is_small_tree(e, small_tree)) return e.diff(x);
  const GiNaC::exmap rates{{x, 1}};
  NodeBuilder build;
  return detail::Directional(rates, build).of(e);
}

ex directional_derivative(const ex& e, const GiNaC::exmap& rates) {
  if (is_small_tree(e, small_tree)) {
    ex result = 0;
    for (const auto& [symbol, rate] : rates)
      if (e.has(symbol)) result += e.diff(GiNaC::ex_to<GiNaC::symbol>(symbol)) * rate;
    return result;
  }
  NodeBuilder build;
  return detail::Directional(rates, build).of(e);
}

ex substitute(const ex& e, const GiNaC::exmap& values) {
  if (is_small_tree(e, small_tree)) return e.subs(values, GiNaC::subs_options::no_pattern);
  NodeBuilder build;
  return detail::Substitution(values, build).of(e);
}

DirectionalDerivative::DirectionalDerivative(GiNaC::exmap rates)
    : rates_(std::move(rates)), build_(std::make_unique<NodeBuilder>()),
      large_(std::make_unique<detail::Directional>(rates_, *build_)) {}

DirectionalDerivative::~DirectionalDerivative() = default;

ex DirectionalDerivative::operator()(const ex& e) {
  if (!is_small_tree(e, detail::small_tree)) return large_->of(e);
  // GiNaC's own, symbol by symbol in the map's order, as directional_derivative (the symbols
  // found in one walk: the map may hold every coordinate and rate of a long chain)
  GiNaC::exset present;
  for (auto it = e.preorder_begin(); it != e.preorder_end(); ++it)
    if (GiNaC::is_a<GiNaC::symbol>(*it)) present.insert(*it);
  ex result = 0;
  for (const auto& [symbol, rate] : rates_)
    if (present.count(symbol) != 0) result += e.diff(GiNaC::ex_to<GiNaC::symbol>(symbol)) * rate;
  return result;
}

Substitution::Substitution(GiNaC::exmap values)
    : values_(std::move(values)), build_(std::make_unique<NodeBuilder>()),
      large_(std::make_unique<detail::Substitution>(values_, *build_)) {}

Substitution::~Substitution() = default;

ex Substitution::operator()(const ex& e) {
  if (!is_small_tree(e, detail::small_tree)) return large_->of(e);
  return e.subs(values_, GiNaC::subs_options::no_pattern);
}

}  // namespace eomgen
