#pragma once
// Differentiation and substitution that follow the graph of shared nodes, not the tree.
//
// GiNaC's diff() and subs() walk an expression as a tree: a model whose points are defined from
// other points' positions inside functions (x_i = x_{i-1} + sin(y_{i-1}), y_i = y_{i-1} +
// cos(x_{i-1})) is a graph of a few nodes per point and a tree of 2^n, and differentiating it
// took minutes at n = 14. These functions handle each shared node once, so their cost follows
// the graph. A small tree is left to GiNaC, whose results (and so the printed equations and the
// generated code of every usual model) they then equal exactly.
#include <ginac/ginac.h>

namespace eomgen {

/// de/dx.
GiNaC::ex derivative(const GiNaC::ex& e, const GiNaC::symbol& x);

/// The derivative of e along `rates`: sum over the symbols s of e of de/ds * rates[s] (the
/// symbols not in `rates` are constants). With rates {q: qd, qd: qdd, t: 1} it is the total time
/// derivative.
GiNaC::ex directional_derivative(const GiNaC::ex& e, const GiNaC::exmap& rates);

/// e with every symbol that is a key of `values` replaced by its value.
/// \pre every key of `values` is a symbol
GiNaC::ex substitute(const GiNaC::ex& e, const GiNaC::exmap& values);

/// Whether e written out as a tree has at most `limit` nodes; costs at most about `limit` steps.
bool is_small_tree(const GiNaC::ex& e, double limit);

}  // namespace eomgen
