#pragma once
// Exact derivatives through the derivation's shared graph: every intermediate z_i gets its
// derivatives dz_i/dv as intermediates of their own, so nothing is written out as a tree and
// nothing is differenced. The linearization, the Coriolis matrix and the output Jacobians
// (header_functions.hpp) take their derivatives here.
#include <ginac/ginac.h>

#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "eomgen/symbolic/subexpressions.hpp"

namespace eomgen {

/// Derivatives with respect to a list of variables of expressions in model symbols and the
/// intermediates of `sources`, bound in `out`: dz_i/dv = d value_i/dv + sum_j d value_i/dz_j dz_j/dv.
/// A derivative that is structurally zero stays the number 0, which is how cyclic coordinates
/// show. Each intermediate's derivatives are taken when first needed: many serve only the
/// energies and outputs. The sources must outlive the rule, and none of them may be `out`.
class ChainRule {
 public:
  ChainRule(std::vector<const Subexpressions*> sources, std::vector<GiNaC::ex> variables, Subexpressions& out);
  ChainRule(const Subexpressions& source, std::vector<GiNaC::ex> variables, Subexpressions& out)
      : ChainRule(std::vector<const Subexpressions*>{&source}, std::move(variables), out) {}

  /// d e / d v for every variable v. Each partial derivative of e is taken once and reused
  /// along every variable: differentiating a large expression is the expensive step, not the
  /// accumulation.
  std::vector<GiNaC::ex> total(const GiNaC::ex& e) const;

 private:
  const std::vector<GiNaC::ex>& derivative(std::size_t i) const;
  void derive_intermediates_of(const GiNaC::ex& e) const;

  // (source, index) of every definition, in order: a source may grow after the rule is made
  std::vector<std::pair<const Subexpressions*, std::size_t>> definitions_;
  const GiNaC::ex& value(std::size_t i) const { return definitions_[i].first->definitions()[definitions_[i].second].value; }
  std::vector<GiNaC::ex> variables_;
  Subexpressions& out_;
  std::map<GiNaC::ex, std::size_t, GiNaC::ex_is_less> variable_index_;
  std::map<GiNaC::ex, std::size_t, GiNaC::ex_is_less> index_;
  mutable std::vector<std::optional<std::vector<GiNaC::ex>>> derivative_;  // filled on demand
};

/// The derivative along given rates (q -> qd, t -> 1, ...) of expressions in model symbols and the
/// intermediates of `sources`, each intermediate's own derivative bound in `out` once: the cost
/// follows the graph, where a ChainRule's gradient over every coordinate would cost the graph
/// times the coordinates. The output biases (Jdot qd) are such derivatives.
class DirectionalRule {
 public:
  DirectionalRule(std::vector<const Subexpressions*> sources, GiNaC::exmap rates, Subexpressions& out);

  /// sum over the symbols s of e of de/ds * rate(s), an intermediate's rate its own derivative,
  /// for every e: one forward pass over each, whatever the number of its symbols
  std::vector<GiNaC::ex> operator()(const std::vector<GiNaC::ex>& es);

 private:
  void derive_intermediates(const GiNaC::ex& e);
  GiNaC::ex along(const GiNaC::ex& e) const;

  std::vector<std::pair<const Subexpressions*, std::size_t>> definitions_;
  std::map<GiNaC::ex, std::size_t, GiNaC::ex_is_less> index_;
  std::vector<bool> done_;
  GiNaC::exmap rates_;  // the given rates, then the nonzero derivative of every intermediate done
  Subexpressions& out_;
};

}  // namespace eomgen
