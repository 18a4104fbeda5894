#pragma once
// Hash tables keyed by expressions, for memos that are looked up but never iterated (iteration
// order would depend on hashes, and output must not). GiNaC's ordering compares whole trees and
// class names, which made ordered maps of expressions the slowest part of emitting long chains.
#include <ginac/ginac.h>

#include <cstddef>
#include <unordered_map>

namespace eomgen {

/// GiNaC's own hash of an expression. Deliberately not noexcept: libstdc++ then keeps each key's
/// hash beside it and compares hashes before it calls the structural equality, which would
/// otherwise run for every key of a bucket.
struct ExpressionHash {
  std::size_t operator()(const GiNaC::ex& e) const { return e.gethash(); }
};

template <class T>
using ExpressionMap = std::unordered_map<GiNaC::ex, T, ExpressionHash, GiNaC::ex_is_equal>;

}  // namespace eomgen
