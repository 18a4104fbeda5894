#include "chain_rule.hpp"

#include <algorithm>
#include <set>

#include "eomgen/mechanics/variables.hpp"
#include "eomgen/symbolic/graph_calculus.hpp"

namespace eomgen {

using GiNaC::ex;
using GiNaC::ex_to;
using GiNaC::symbol;

ChainRule::ChainRule(std::vector<const Subexpressions*> sources, std::vector<ex> variables, Subexpressions& out)
    : variables_(std::move(variables)), out_(out) {
  for (std::size_t k = 0; k < variables_.size(); ++k) variable_index_.emplace(variables_[k], k);
  for (const Subexpressions* z : sources)
    for (std::size_t i = 0; i < z->size(); ++i) {
      index_.emplace(z->definitions()[i].symbol, definitions_.size());
      definitions_.emplace_back(z, i);
    }
  derivative_.resize(definitions_.size());
}

// The derivatives of the intermediates e refers to, bound in the order of their definitions:
// GiNaC orders the symbols of e (and the terms of a sum) by hashes that change from process to
// process, and binding in that order would number the derivatives differently in every run.
void ChainRule::derive_intermediates_of(const ex& e) const {
  std::set<std::size_t> reached;
  for (const ex& s : symbols_of(e))
    if (const auto it = index_.find(s); it != index_.end() && !derivative_[it->second]) reached.insert(it->second);
  for (std::size_t i : reached) derivative(i);
}

std::vector<ex> ChainRule::total(const ex& e) const {
  // a long sum term by term: differentiating the whole sum once per symbol it holds would cost
  // its length times its symbols (an output of a chain sums a term per link)
  if (GiNaC::is_a<GiNaC::add>(e) && e.nops() > 4) {
    derive_intermediates_of(e);
    std::vector<GiNaC::exvector> terms(variables_.size());
    for (std::size_t i = 0; i < e.nops(); ++i) {
      const std::vector<ex> d = total(e.op(i));
      for (std::size_t k = 0; k < d.size(); ++k)
        if (!d[k].is_zero()) terms[k].push_back(d[k]);
    }
    std::vector<ex> d(variables_.size(), 0);
    for (std::size_t k = 0; k < d.size(); ++k)
      if (!terms[k].empty()) d[k] = GiNaC::add(terms[k]);
    return d;
  }
  derive_intermediates_of(e);
  std::vector<ex> d(variables_.size(), 0);
  for (const ex& s : symbols_of(e)) {
    if (const auto v = variable_index_.find(s); v != variable_index_.end()) {
      d[v->second] += eomgen::derivative(e, ex_to<symbol>(s));
      continue;
    }
    const auto it = index_.find(s);
    if (it == index_.end()) continue;
    const std::vector<ex>& dz = derivative(it->second);
    if (std::all_of(dz.begin(), dz.end(), [](const ex& x) { return x.is_zero(); })) continue;
    const ex partial = eomgen::derivative(e, ex_to<symbol>(s));
    for (std::size_t k = 0; k < dz.size(); ++k)
      if (!dz[k].is_zero()) d[k] += partial * dz[k];
  }
  return d;
}

const std::vector<ex>& ChainRule::derivative(std::size_t i) const {
  if (derivative_[i]) return *derivative_[i];
  // the intermediates i depends on and lacking derivatives, taken in the order of their
  // definitions: each then finds its own dependencies done, and the recursion stays one level
  // deep however long the chain of definitions
  std::set<std::size_t> pending{i};
  std::vector<std::size_t> stack{i};
  while (!stack.empty()) {
    const std::size_t j = stack.back();
    stack.pop_back();
    for (const ex& s : symbols_of(value(j)))
      if (const auto it = index_.find(s); it != index_.end() && !derivative_[it->second] && pending.insert(it->second).second)
        stack.push_back(it->second);
  }
  for (std::size_t j : pending) {
    std::vector<ex> gradient = total(value(j));
    for (ex& g : gradient) g = out_.bind(g);
    derivative_[j] = std::move(gradient);
  }
  return *derivative_[i];
}

DirectionalRule::DirectionalRule(std::vector<const Subexpressions*> sources, GiNaC::exmap rates, Subexpressions& out)
    : rates_(std::move(rates)), out_(out) {
  for (const Subexpressions* z : sources)
    for (std::size_t i = 0; i < z->size(); ++i) {
      index_.emplace(z->definitions()[i].symbol, definitions_.size());
      definitions_.emplace_back(z, i);
    }
  done_.assign(definitions_.size(), false);
}

void DirectionalRule::derive_intermediates(const ex& e) {
  // the intermediates e reaches that are not done, then each in the order of definition, so that
  // its own dependencies are done before it
  std::set<std::size_t> pending;
  std::vector<std::size_t> stack;
  for (const ex& s : symbols_of(e))
    if (const auto it = index_.find(s); it != index_.end() && !done_[it->second] && pending.insert(it->second).second)
      stack.push_back(it->second);
  while (!stack.empty()) {
    const std::size_t j = stack.back();
    stack.pop_back();
    const Subexpressions::Definition& d = definitions_[j].first->definitions()[definitions_[j].second];
    for (const ex& s : symbols_of(d.value))
      if (const auto it = index_.find(s); it != index_.end() && !done_[it->second] && pending.insert(it->second).second)
        stack.push_back(it->second);
  }
  for (std::size_t j : pending) {
    const Subexpressions::Definition& d = definitions_[j].first->definitions()[definitions_[j].second];
    const ex rate = out_.bind(along(d.value));
    if (!rate.is_zero()) rates_[d.symbol] = rate;
    done_[j] = true;
  }
}

// by the symbols of e (the rates hold every intermediate's: iterating over them would cost their
// number per call), a long sum term by term as in ChainRule::total
ex DirectionalRule::along(const ex& e) const {
  if (GiNaC::is_a<GiNaC::add>(e) && e.nops() > 4) {
    GiNaC::exvector terms;
    for (std::size_t i = 0; i < e.nops(); ++i)
      if (const ex d = along(e.op(i)); !d.is_zero()) terms.push_back(d);
    return terms.empty() ? ex(0) : ex(GiNaC::add(terms));
  }
  GiNaC::exvector terms;
  for (const ex& s : symbols_of(e))
    if (const auto it = rates_.find(s); it != rates_.end())
      terms.push_back(eomgen::derivative(e, ex_to<symbol>(s)) * it->second);
  return terms.empty() ? ex(0) : ex(GiNaC::add(terms));
}

std::vector<ex> DirectionalRule::operator()(const std::vector<ex>& es) {
  for (const ex& e : es) derive_intermediates(e);
  DirectionalDerivative derivative(rates_);
  std::vector<ex> out;
  for (const ex& e : es) out.push_back(derivative(e));
  return out;
}

}  // namespace eomgen
