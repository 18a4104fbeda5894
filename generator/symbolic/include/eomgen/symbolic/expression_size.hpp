#pragma once
// The size of an expression written out: as a tree (what printing it, or differentiating it
// without intermediates, costs) and multiplied out (what expanding it costs). GiNaC shares equal
// subtrees in memory, so an expression of modest memory can be an exponentially large tree, and
// a product of sums multiplies out to the product of their numbers of terms. Both are computed
// visiting each shared node once.
#include <ginac/ginac.h>

#include "eomgen/symbolic/expression_map.hpp"

namespace eomgen {

/// Number of nodes of e written out as a tree (symbols count as leaves).
double tree_size(const GiNaC::ex& e);

/// Sizes of expressions that may refer to intermediates, each of which counts at the size of
/// its definition; remembered per node, so many expressions over one graph cost its size once.
class ExpressionSizes {
 public:
  struct Expanded {
    double terms = 1;  ///< terms of the sum it multiplies out to, before like terms combine
    double nodes = 1;  ///< nodes of that sum
  };

  /// `symbol` stands for `value` (whose intermediates are defined already).
  void define(const GiNaC::ex& symbol, const GiNaC::ex& value);

  /// Nodes of e as a tree, each intermediate written out.
  double tree(const GiNaC::ex& e);
  /// e written out and multiplied out, as GiNaC's expand() would (an upper bound: like terms
  /// are counted apart). A function, or a power that is not a small positive integer one, stays
  /// one factor, multiplied out inside.
  Expanded expanded(const GiNaC::ex& e);

 private:
  ExpressionMap<double> tree_;
  ExpressionMap<Expanded> expanded_;
};

}  // namespace eomgen
