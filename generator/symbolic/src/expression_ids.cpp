// Numbers for the values of expressions (expression_ids.hpp): hash-consing of GiNaC's nodes.
#include "eomgen/symbolic/expression_ids.hpp"
#include "eomgen/symbolic/operand.hpp"

#include <algorithm>
#include <limits>

#include "eomgen/base/error.hpp"

namespace eomgen {
namespace {

using GiNaC::ex;
using Id = ExpressionIds::Id;

// the kind of a node, the first entry of its key; a function's is function_kinds + its serial
enum Kind : std::uint32_t { opaque = 0, leaf = 1, sum = 2, product = 3, power = 4, list = 5, matrix = 6, function_kinds = 16 };

// the kind of a node whose value its operands determine, or opaque for one compared by
// identity (a relation, a series, anything the derivation does not build)
std::uint32_t kind_of(const ex& e) {
  if (e.nops() == 0) return leaf;
  if (GiNaC::is_exactly_a<GiNaC::add>(e)) return sum;
  if (GiNaC::is_exactly_a<GiNaC::mul>(e)) return product;
  if (GiNaC::is_exactly_a<GiNaC::power>(e)) return power;
  if (GiNaC::is_exactly_a<GiNaC::lst>(e)) return list;
  if (GiNaC::is_exactly_a<GiNaC::matrix>(e)) return matrix;
  if (GiNaC::is_a<GiNaC::function>(e)) return function_kinds + GiNaC::ex_to<GiNaC::function>(e).get_serial();
  return opaque;
}

// Whether op(i) of a sum or a product may have built `operand` for the call: a sum keeps c*x
// as the pair (x, c) and a product keeps x^c as (x, c), both with c a number, and op() returns
// a new node for each pair whose c is not 1. Such nodes are numbered from their operands, which
// are stored nodes, and their addresses are not remembered: they die when the caller's copy
// does, and keeping them alive would keep every one ever built.
bool built_by_op(std::uint32_t parent_kind, const ex& operand) {
  if (parent_kind == sum)
    return GiNaC::is_exactly_a<GiNaC::mul>(operand) && GiNaC::is_a<GiNaC::numeric>(operand.op(operand.nops() - 1));
  if (parent_kind == product)
    return GiNaC::is_exactly_a<GiNaC::power>(operand) && GiNaC::is_a<GiNaC::numeric>(operand.op(1));
  return false;
}

// splitmix64's finalizer over the key's entries: a hash of content only, the same in every run
std::uint64_t key_hash(const std::vector<std::uint32_t>& key) {
  std::uint64_t h = 0x9e3779b97f4a7c15ull ^ key.size();
  for (std::uint32_t v : key) {
    h += 0x9e3779b97f4a7c15ull + v;
    h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ull;
    h = (h ^ (h >> 27)) * 0x94d049bb133111ebull;
    h ^= h >> 31;
  }
  return h;
}

std::uint64_t bits_of(const GiNaC::basic* p) { return static_cast<std::uint64_t>(reinterpret_cast<std::uintptr_t>(p)); }
std::uint64_t bits_of(std::uint64_t h) { return h; }

const GiNaC::basic* address(const ex& e) { return &GiNaC::ex_to<GiNaC::basic>(e); }

}  // namespace

template <class Key>
std::size_t ExpressionIds::FlatTable<Key>::slot(Key key) const {
  // the high bits of a Fibonacci product mix every bit of the key (addresses end in zeros)
  const std::uint64_t h = bits_of(key) * 0x9e3779b97f4a7c15ull;
  return static_cast<std::size_t>(h >> 32) & (slots_.size() - 1);
}

template <class Key>
void ExpressionIds::FlatTable<Key>::insert(Key key, Id id) {
  if (2 * (count_ + 1) > slots_.size()) {  // at most half full: probes stay short
    std::vector<Entry> old(std::max<std::size_t>(64, 2 * slots_.size()));
    old.swap(slots_);
    count_ = 0;
    for (const Entry& e : old)
      if (e.used) insert(e.key, e.id);
  }
  std::size_t i = slot(key);
  while (slots_[i].used) i = (i + 1) & (slots_.size() - 1);
  slots_[i] = Entry{key, id, true};
  ++count_;
}

const Id* ExpressionIds::known(const ex& e) const {
  return by_node_.find(address(e), [](Id) { return true; });
}

Id ExpressionIds::operator()(const ex& root) {
  if (const Id* id = known(root)) return *id;
  // Post-order without recursion (an expression may be deep): a node's operands are numbered
  // before it. An expanded node's operands sit at the end of operands_, their numbers at the
  // same places + 1 in operand_ids_, where its children, done before it, leave them.
  struct Pending {
    ex node;
    std::uint32_t kind;
    bool remember;          // by address
    std::size_t result;     // where its number goes in operand_ids_
    std::size_t first = 0;  // its operands: operands_[first, first + nops)
    bool expanded = false;
  };
  std::vector<Pending> stack;
  operands_.clear();
  operand_ids_.assign(1, 0);  // slot 0: the root's number
  stack.push_back({root, kind_of(root), true, 0});
  while (!stack.empty()) {
    Pending& top = stack.back();
    if (top.remember) {
      if (const Id* id = known(top.node)) {
        operand_ids_[top.result] = *id;
        stack.pop_back();
        continue;
      }
    }
    if (!top.expanded && top.kind != leaf && top.kind != opaque) {
      top.expanded = true;
      top.first = operands_.size();
      const std::size_t count = top.node.nops();
      for (std::size_t i = 0; i < count; ++i) operands_.push_back(operand(top.node, i));
      operand_ids_.resize(top.first + 1 + count);
      const std::uint32_t parent_kind = top.kind;
      const std::size_t first = top.first;  // push_back below may move `top`
      for (std::size_t i = count; i-- > 0;) {
        const ex& operand = operands_[first + i];
        if (const Id* id = known(operand)) {
          operand_ids_[first + 1 + i] = *id;
        } else {
          stack.push_back({operand, kind_of(operand), !built_by_op(parent_kind, operand), first + 1 + i});
        }
      }
      continue;
    }
    const Pending done = std::move(top);
    stack.pop_back();
    const std::size_t count = done.expanded ? done.node.nops() : 0;
    const Id id = intern(done.node, done.kind, done.first + 1, count);
    if (done.expanded) {
      operands_.resize(done.first);
      operand_ids_.resize(done.first + 1);
    }
    operand_ids_[done.result] = id;
    if (done.remember) {
      by_node_.insert(address(done.node), id);
      kept_.push_back(done.node);
    }
  }
  return operand_ids_[0];
}

Id ExpressionIds::intern(const ex& node, std::uint32_t kind, std::size_t first_operand, std::size_t operand_count) {
  if (kind == leaf) return intern_leaf(node);
  key_.assign(1, kind);
  if (kind == opaque) {
    // equal to itself only: a key no other node has
    key_.push_back(static_cast<std::uint32_t>(size()));
    return new_id(key_hash(key_), node);
  }
  if (kind == matrix) {
    const GiNaC::matrix& m = GiNaC::ex_to<GiNaC::matrix>(node);
    key_.push_back(m.rows());
    key_.push_back(m.cols());
  }
  key_.insert(key_.end(), operand_ids_.begin() + static_cast<long>(first_operand),
              operand_ids_.begin() + static_cast<long>(first_operand + operand_count));
  const std::uint64_t hash = key_hash(key_);
  const Id* found = by_content_.find(hash, [&](Id candidate) {
    const std::size_t start = key_start_[candidate];
    const std::size_t end = candidate + 1 < key_start_.size() ? key_start_[candidate + 1] : keys_.size();
    return end - start == key_.size() && std::equal(key_.begin(), key_.end(), keys_.begin() + static_cast<long>(start));
  });
  return found ? *found : new_id(hash, node);
}

// A leaf (a number, a symbol, a constant) is compared by GiNaC among the leaves of its hash:
// comparing two leaves costs a few operations, whatever they are.
Id ExpressionIds::intern_leaf(const ex& node) {
  key_.assign({leaf, node.gethash()});
  const std::uint64_t hash = key_hash(key_);
  const Id* found = by_content_.find(hash, [&](Id candidate) {
    return keys_[key_start_[candidate]] == leaf && leaves_[candidate].is_equal(node);
  });
  return found ? *found : new_id(hash, node);
}

// a new number for the value whose key is key_
Id ExpressionIds::new_id(std::uint64_t hash, const ex& node) {
  EOMGEN_DEMAND(size() < std::numeric_limits<Id>::max(), "ExpressionIds: more than 2^32 distinct values");
  const Id id = static_cast<Id>(size());
  key_start_.push_back(keys_.size());
  keys_.insert(keys_.end(), key_.begin(), key_.end());
  leaves_.push_back(key_.front() == leaf ? node : ex());
  by_content_.insert(hash, id);
  return id;
}

}  // namespace eomgen
