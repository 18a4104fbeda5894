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

#include <memory>

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

/// Trees of at most this many nodes are differentiated and substituted by GiNaC: every shipped
/// model's expressions are smaller (the bicycle's largest that is differentiated or substituted
/// into has about 9,400 nodes), and a tree this size costs GiNaC a millisecond.
inline constexpr double small_tree_limit = 20000;

namespace detail {
class NodeBuilder;
class Directional;
class Substitution;
}  // namespace detail

/// directional_derivative along one fixed map of rates, remembering the derivative of every
/// node of a large expression across calls: a derivation that differentiates the positions of
/// points defined from one another (each point's expression holding the ones before it) then
/// differentiates each shared node once in all, not once per point. Equal to
/// directional_derivative(e, rates) for every e.
class DirectionalDerivative {
 public:
  explicit DirectionalDerivative(GiNaC::exmap rates);
  ~DirectionalDerivative();
  DirectionalDerivative(const DirectionalDerivative&) = delete;
  DirectionalDerivative& operator=(const DirectionalDerivative&) = delete;
  GiNaC::ex operator()(const GiNaC::ex& e);

 private:
  GiNaC::exmap rates_;
  std::unique_ptr<detail::NodeBuilder> build_;
  std::unique_ptr<detail::Directional> large_;
};

/// substitute with one fixed map of values, remembering every node of a large expression across
/// calls (as DirectionalDerivative). Equal to substitute(e, values) for every e.
class Substitution {
 public:
  explicit Substitution(GiNaC::exmap values);
  ~Substitution();
  Substitution(const Substitution&) = delete;
  Substitution& operator=(const Substitution&) = delete;
  GiNaC::ex operator()(const GiNaC::ex& e);

 private:
  GiNaC::exmap values_;
  std::unique_ptr<detail::NodeBuilder> build_;
  std::unique_ptr<detail::Substitution> large_;
};

}  // namespace eomgen
