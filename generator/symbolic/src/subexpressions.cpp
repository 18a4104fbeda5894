#include "eomgen/symbolic/subexpressions.hpp"
#include "eomgen/symbolic/operand.hpp"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include "eomgen/base/content_hash.hpp"
#include "eomgen/symbolic/expression_map.hpp"
#include "eomgen/symbolic/graph_calculus.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;

// a definition of more nodes than this, written out, is shared before it is bound
constexpr double large_tree = 5000;

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
  // a value that is a large tree (a small graph of nodes used more than once) is bound through
  // its shared nodes, so that no definition is itself a large tree to print or differentiate
  return bind_as_is(is_small_tree(value, large_tree) ? value : share(value));
}

ex Subexpressions::bind_as_is(const ex& value) {
  if (is_atomic(value)) return value;
  if (const ex* bound = by_value_.find(value)) return *bound;
  GiNaC::realsymbol z(prefix_ + std::to_string(definitions_.size() + 1));
  definitions_.push_back(Definition{z, value});
  by_value_.emplace(value, z);
  return z;
}

namespace {

// The content of an expression up to its sign: e = sign * magnitude, with a hash of the
// magnitude from names, numbers and structure, the operands of sums and products taken in
// sorted order. GiNaC orders those operands by hash values seeded from addresses, so from one
// process to the next it writes the same value in other orders and, inside products, with
// either sign (x*(a - b) or -x*(b - a)); e and -e have the same magnitude here in every run.
struct Signature {
  std::uint64_t magnitude = 0;
  int sign = 1;
};

class Signatures {
 public:
  Signature operator()(const ex& e) {
    if (const Signature* s = memo_.find(e)) return *s;
    const Signature s = compute(e);
    memo_.emplace(e, s);
    return s;
  }

 private:
  static std::uint64_t mix(std::uint64_t h, std::uint64_t v) {
    for (int i = 0; i < 8; ++i) h = (h ^ ((v >> (8 * i)) & 0xffu)) * 1099511628211ull;  // FNV-1a
    return h;
  }
  static std::uint64_t text_hash(const ex& e) {
    std::ostringstream text;  // numbers and constants: GiNaC prints these the same in every run
    text << e;
    return content_hash(text.str());
  }
  static std::uint64_t tag(const char* kind) { return content_hash(kind); }

  Signature compute(const ex& e) {
    using GiNaC::is_a;
    if (is_a<GiNaC::numeric>(e)) {
      const GiNaC::numeric& n = GiNaC::ex_to<GiNaC::numeric>(e);
      const bool negative = n.is_real() && n.is_negative();
      return {mix(tag("numeric"), text_hash(negative ? ex(-n) : e)), negative ? -1 : 1};
    }
    if (is_a<GiNaC::symbol>(e)) return {mix(tag("symbol"), content_hash(GiNaC::ex_to<GiNaC::symbol>(e).get_name())), 1};
    if (is_a<GiNaC::mul>(e)) {
      GiNaC::numeric coefficient = 1;
      int sign = 1;
      std::vector<std::uint64_t> factors;
      for (std::size_t i = 0; i < e.nops(); ++i) {
        if (is_a<GiNaC::numeric>(e.op(i))) {
          coefficient *= GiNaC::ex_to<GiNaC::numeric>(e.op(i));
          continue;
        }
        const Signature f = (*this)(e.op(i));
        sign *= f.sign;
        factors.push_back(f.magnitude);
      }
      if (coefficient.is_real() && coefficient.is_negative()) sign = -sign, coefficient = -coefficient;
      // -x is x negated, wherever it stands
      if (factors.size() == 1 && coefficient.is_equal(1)) return {factors[0], sign};
      std::sort(factors.begin(), factors.end());
      std::uint64_t h = mix(tag("mul"), text_hash(coefficient));
      for (std::uint64_t f : factors) h = mix(h, f);
      return {h, sign};
    }
    if (is_a<GiNaC::add>(e)) {
      std::vector<Signature> terms;
      for (std::size_t i = 0; i < e.nops(); ++i) terms.push_back((*this)(operand(e, i)));
      std::sort(terms.begin(), terms.end(), [](const Signature& a, const Signature& b) {
        return a.magnitude != b.magnitude ? a.magnitude < b.magnitude : a.sign < b.sign;
      });
      const int sign = terms.front().sign;
      std::uint64_t h = tag("add");
      for (const Signature& t : terms) h = mix(mix(h, t.magnitude), static_cast<std::uint64_t>(t.sign * sign + 1));
      return {h, sign};
    }
    if (is_a<GiNaC::power>(e)) {
      const Signature base = (*this)(e.op(0));
      const ex& exponent = e.op(1);
      std::uint64_t h = mix(mix(tag("power"), base.magnitude), text_hash(exponent));
      if (is_a<GiNaC::numeric>(exponent) && GiNaC::ex_to<GiNaC::numeric>(exponent).is_integer())
        return {h, GiNaC::ex_to<GiNaC::numeric>(exponent).is_odd() ? base.sign : 1};
      // sqrt(a - b) and sqrt(b - a) are different values
      const Signature x = (*this)(exponent);
      return {mix(mix(mix(h, static_cast<std::uint64_t>(base.sign + 1)), x.magnitude), static_cast<std::uint64_t>(x.sign + 1)), 1};
    }
    // functions (sin(a - b) is not -sin(b - a) to GiNaC), constants, lists: operands in order
    std::uint64_t h = mix(tag(GiNaC::ex_to<GiNaC::basic>(e).class_name()), e.nops() == 0 ? text_hash(e) : 0);
    if (is_a<GiNaC::function>(e)) h = mix(h, content_hash(GiNaC::ex_to<GiNaC::function>(e).get_name()));
    for (std::size_t i = 0; i < e.nops(); ++i) {
      const Signature o = (*this)(e.op(i));
      h = mix(mix(h, o.magnitude), static_cast<std::uint64_t>(o.sign + 1));
    }
    return {h, 1};
  }

  ExpressionMap<Signature> memo_;
};

}  // namespace

struct Subexpressions::ShareMemo {
  Signatures signature;
  // a node's value as +-1 times a canonical value: the one bound when the node is shared
  struct Done {
    ex canonical;
    int sign;                // of the node whose signature has sign +1
    ex intermediate;         // what bind() gave for canonical, when it was bound
    bool is_bound = false;
  };
  // the intermediate of the node with this signature, if it has one (a later bind() of an
  // equal value counts too)
  const ex* bound(std::uint64_t magnitude, Subexpressions& z) const {
    const auto it = done.find(magnitude);
    if (it == done.end()) return nullptr;
    return it->second.is_bound ? &it->second.intermediate : z.by_value_.find(it->second.canonical);
  }
  std::unordered_map<std::uint64_t, Done> done;  // by the magnitude of the node's signature
};

Subexpressions::ShareMemoHandle::ShareMemoHandle() : memo(std::make_unique<ShareMemo>()) {}
Subexpressions::ShareMemoHandle::~ShareMemoHandle() = default;
Subexpressions::ShareMemoHandle::ShareMemoHandle(const ShareMemoHandle&) : ShareMemoHandle() {}
Subexpressions::ShareMemoHandle& Subexpressions::ShareMemoHandle::operator=(const ShareMemoHandle&) {
  memo = std::make_unique<ShareMemo>();
  return *this;
}
Subexpressions::ShareMemoHandle::ShareMemoHandle(ShareMemoHandle&& other) noexcept : memo(std::move(other.memo)) {}
Subexpressions::ShareMemoHandle& Subexpressions::ShareMemoHandle::operator=(ShareMemoHandle&& other) noexcept {
  memo = std::move(other.memo);
  return *this;
}

ex Subexpressions::share(const ex& value) {
  // Everything below goes by values up to sign, not by GiNaC's structure: the same value
  // written as x*(a - b) here and -x*(b - a) there is one node, bound once, with the sign of
  // a fixed choice, and nodes are visited in the order of their content. So the intermediates
  // and their numbers are the same in every run.
  if (!share_memo_.memo) share_memo_.memo = std::make_unique<ShareMemo>();  // moved from
  ShareMemo& memo = *share_memo_.memo;
  Signatures& signature = memo.signature;
  // count the parents of every node, visiting each node once and no node that is an intermediate
  // already (one rebuilt but left inline is entered again: its inside may now be used twice)
  std::unordered_map<std::uint64_t, std::size_t> parents;
  std::vector<ex> stack{value};
  parents[signature(value).magnitude] = 1;
  while (!stack.empty()) {
    const ex e = stack.back();
    stack.pop_back();
    const std::uint64_t magnitude = signature(e).magnitude;
    if (memo.bound(magnitude, *this)) continue;
    for (std::size_t i = 0; i < e.nops(); ++i) {
      const ex o = operand(e, i);
      if (is_leaf(o)) continue;
      // the X of a negation -X has the negation's magnitude, so its count is already under
      // way; the rebuild below still enters it from here, so its inside is counted from here
      const std::uint64_t m = signature(o).magnitude;
      if (parents[m]++ == 0 || m == magnitude) stack.push_back(o);
    }
  }
  // rebuild bottom-up, binding the nodes used more than once
  struct Rebuild : GiNaC::map_function {
    Subexpressions& z;
    const std::unordered_map<std::uint64_t, std::size_t>& parents;
    ShareMemo& memo;
    std::unordered_set<std::uint64_t> visited;  // rebuilt by this call
    Rebuild(Subexpressions& s, const std::unordered_map<std::uint64_t, std::size_t>& p, ShareMemo& m)
        : z(s), parents(p), memo(m) {}
    ex operator()(const ex& e) override {
      if (is_leaf(e)) return e;
      const Signature s = memo.signature(e);
      if (const auto it = memo.done.find(s.magnitude); it != memo.done.end()) {
        const ShareMemo::Done d = it->second;  // a copy: binding may add entries
        // an intermediate already (made by this call or an earlier one)
        if (const ex* bound = memo.bound(s.magnitude, z)) return s.sign * d.sign * *bound;
        // rebuilt by this call and used once, or by an earlier one and left inline: rebuilt
        // again below, since this call may use its inside more than once
        if (visited.count(s.magnitude) != 0) return s.sign * d.sign * d.canonical;
      }
      visited.insert(s.magnitude);
      std::vector<std::size_t> order(e.nops());
      std::iota(order.begin(), order.end(), std::size_t{0});
      std::vector<std::uint64_t> keys;
      std::vector<ex> operands;
      for (std::size_t i = 0; i < e.nops(); ++i) {
        operands.push_back(operand(e, i));
        keys.push_back(memo.signature(operands.back()).magnitude);
      }
      std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return keys[a] < keys[b]; });
      for (std::size_t i : order) (*this)(operands[i]);
      // every operand is done: this only looks them up (a sum's from the operands read above,
      // which its map() would build again, evaluated, as other nodes)
      ex r;
      if (sum_pairs(e) != nullptr) {
        GiNaC::exvector terms;
        for (const ex& o : operands) terms.push_back((*this)(o));
        r = GiNaC::add(terms);
      } else {
        r = e.map(*this);
      }
      // r = e; its canonical value is r times its own sign (taken on its new content)
      const int r_sign = memo.signature(r).sign;
      const ex canonical = r_sign * r;
      ShareMemo::Done d{canonical, s.sign * r_sign, canonical, false};
      if (parents.at(s.magnitude) > 1) {
        d.intermediate = z.bind(canonical);
        d.is_bound = true;
      }
      memo.done.insert_or_assign(s.magnitude, d);
      return r_sign * d.intermediate;
    }
  } rebuild(*this, parents, memo);
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
