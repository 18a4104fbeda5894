#pragma once
// Expressions whose graph of shared nodes is small and whose tree is exponentially large, for
// tests that a traversal, a memo or a comparison follows the graph.
#include <ginac/ginac.h>

namespace eomgen::testing {

/// e_0 = x, e_{i+1} = e_i*(1 + sin(e_i/x)) + x: 2^depth paths through about 6 depth nodes.
/// Every node is held (not evaluated): GiNaC's evaluation of a product asks its operands for
/// their return type, which for a sum asks its first term in GiNaC's order of terms (an order of
/// hash values that differ between processes), and so walks the tree, not the graph, in about
/// one process in twenty. Built twice, the same value has two sets of nodes sharing only x and
/// the numbers, so a structural comparison of the two would walk 2^depth paths.
inline GiNaC::ex doubling_graph(const GiNaC::ex& x, int depth) {
  GiNaC::ex e = x;
  for (int i = 0; i < depth; ++i) {
    const GiNaC::ex ratio = GiNaC::mul(e, GiNaC::pow(x, -1)).hold();
    const GiNaC::ex wave = GiNaC::sin(ratio).hold();
    const GiNaC::ex factor = GiNaC::add(GiNaC::ex(1), wave).hold();
    e = GiNaC::add(GiNaC::mul(e, factor).hold(), x).hold();
  }
  return e;
}

}  // namespace eomgen::testing
