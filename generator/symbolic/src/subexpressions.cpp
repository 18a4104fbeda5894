#include "eomgen/symbolic/subexpressions.hpp"


namespace eomgen {
namespace {

using GiNaC::ex;

bool is_leaf(const ex& e) {
  return GiNaC::is_a<GiNaC::numeric>(e) || GiNaC::is_a<GiNaC::symbol>(e) || GiNaC::is_a<GiNaC::constant>(e);
}

bool is_atomic(const ex& e) {
  if (is_leaf(e)) return true;
  // a number times a leaf, such as -z3 or 2*q1
  if (GiNaC::is_a<GiNaC::mul>(e) && e.nops() == 2 &&
      ((GiNaC::is_a<GiNaC::numeric>(e.op(1)) && is_leaf(e.op(0))) ||
       (GiNaC::is_a<GiNaC::numeric>(e.op(0)) && is_leaf(e.op(1)))))
    return true;
  // sin(q1), cos(q2): code emission caches these itself
  if (GiNaC::is_a<GiNaC::function>(e) && e.nops() == 1 && is_leaf(e.op(0))) return true;
  return false;
}

}  // namespace

ex Subexpressions::bind(const ex& value) {
  if (is_atomic(value)) return value;
  auto it = by_value_.find(value);
  if (it != by_value_.end()) return it->second;
  GiNaC::realsymbol z(prefix_ + std::to_string(definitions_.size() + 1));
  definitions_.push_back(Definition{z, value});
  by_value_.emplace(value, z);
  return z;
}

ex Subexpressions::share(const ex& value) {
  // count the parents of every node, visiting each shared node once (identical shared nodes
  // compare by pointer, so the maps stay cheap)
  std::map<ex, std::size_t, GiNaC::ex_is_less> parents;
  std::vector<ex> stack{value};
  parents[value] = 1;
  while (!stack.empty()) {
    const ex e = stack.back();
    stack.pop_back();
    for (std::size_t i = 0; i < e.nops(); ++i) {
      if (is_leaf(e.op(i))) continue;
      if (parents[e.op(i)]++ == 0) stack.push_back(e.op(i));
    }
  }
  // rebuild bottom-up, binding the nodes used more than once
  struct Rebuild : GiNaC::map_function {
    Subexpressions& z;
    std::map<ex, std::size_t, GiNaC::ex_is_less>& parents;
    std::map<ex, ex, GiNaC::ex_is_less> done;
    Rebuild(Subexpressions& s, std::map<ex, std::size_t, GiNaC::ex_is_less>& p) : z(s), parents(p) {}
    ex operator()(const ex& e) override {
      if (is_leaf(e)) return e;
      auto it = done.find(e);
      if (it != done.end()) return it->second;
      ex r = e.map(*this);
      if (parents[e] > 1) r = z.bind(r);
      done.emplace(e, r);
      return r;
    }
  } rebuild(*this, parents);
  return rebuild(value);
}

GiNaC::matrix Subexpressions::bind(const GiNaC::matrix& value) {
  GiNaC::matrix out(value.rows(), value.cols());
  for (unsigned i = 0; i < value.rows(); ++i)
    for (unsigned j = 0; j < value.cols(); ++j) out(i, j) = bind(value(i, j));
  return out;
}

ex Subexpressions::expand(const ex& e) const {
  // write out definitions in order; each only refers to earlier ones
  for (; expanded_count_ < definitions_.size(); ++expanded_count_) {
    const Definition& d = definitions_[expanded_count_];
    expanded_[d.symbol] = d.value.subs(expanded_, GiNaC::subs_options::no_pattern);
  }
  return e.subs(expanded_, GiNaC::subs_options::no_pattern);
}

GiNaC::matrix Subexpressions::expand(const GiNaC::matrix& m) const {
  GiNaC::matrix out(m.rows(), m.cols());
  for (unsigned i = 0; i < m.rows(); ++i)
    for (unsigned j = 0; j < m.cols(); ++j) out(i, j) = expand(m(i, j));
  return out;
}

GiNaC::exmap Subexpressions::evaluate_all(const GiNaC::exmap& values) const {
  GiNaC::exmap all = values;
  for (const Definition& d : definitions_)
    all[d.symbol] = d.value.subs(all, GiNaC::subs_options::no_pattern).evalf();
  return all;
}

ex Subexpressions::evaluate(const ex& e, const GiNaC::exmap& values) const {
  return e.subs(evaluate_all(values), GiNaC::subs_options::no_pattern).evalf();
}

}  // namespace eomgen
