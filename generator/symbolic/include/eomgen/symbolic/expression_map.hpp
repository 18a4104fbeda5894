#pragma once
// Memos keyed by the values of expressions: one table lookup per node, whatever GiNaC's hash
// values are (expression_ids.hpp says why GiNaC's own hashing and ordering cannot do this).
#include <ginac/ginac.h>

#include <cstddef>
#include <deque>
#include <utility>
#include <vector>

#include "eomgen/symbolic/expression_ids.hpp"

namespace eomgen {

/// A memo keyed by the values of expressions, for tables that are looked up but never iterated
/// (an order of iteration would follow the order of first sight). Lookups cost what
/// ExpressionIds costs; stored values keep their address (references stay valid).
template <class T>
class ExpressionMap {
 public:
  /// The value stored for e's value, or nullptr.
  T* find(const GiNaC::ex& e) {
    const ExpressionIds::Id id = ids_(e);
    return id < slots_.size() && slots_[id] != none ? &values_[slots_[id]] : nullptr;
  }
  /// Stores `value` for e unless e has one; returns the stored value and whether it is new.
  std::pair<T*, bool> emplace(const GiNaC::ex& e, T value) {
    const ExpressionIds::Id id = ids_(e);
    if (id >= slots_.size()) slots_.resize(static_cast<std::size_t>(id) + 1, none);
    if (slots_[id] != none) return {&values_[slots_[id]], false};
    slots_[id] = values_.size();
    values_.push_back(std::move(value));
    return {&values_.back(), true};
  }
  /// The value stored for e, default-constructed if it had none.
  T& operator[](const GiNaC::ex& e) { return *emplace(e, T{}).first; }
  bool contains(const GiNaC::ex& e) { return find(e) != nullptr; }
  std::size_t size() const { return values_.size(); }

 private:
  static constexpr std::size_t none = static_cast<std::size_t>(-1);
  ExpressionIds ids_;
  std::vector<std::size_t> slots_;  // by id: the index in values_, or none
  std::deque<T> values_;
};

}  // namespace eomgen
