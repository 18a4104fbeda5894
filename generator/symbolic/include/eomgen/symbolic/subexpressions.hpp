#pragma once
// Named intermediate quantities z_i = value_i shared by the derivation. Compounded DCMs,
// partial velocities and accelerations of long chains would grow exponentially as trees if
// written out; binding each to a symbol keeps every expression small and the whole
// derivation linear in the size of its shared graph. Code emission later prints the
// definitions in order, like the temporaries of an optimizing compiler.
#include <ginac/ginac.h>

#include <memory>
#include <string>
#include <vector>

#include "eomgen/symbolic/expression_map.hpp"

namespace eomgen {

class Subexpressions {
 public:
  struct Definition {
    GiNaC::realsymbol symbol;
    GiNaC::ex value;  // refers only to model symbols and to earlier definitions
  };

  explicit Subexpressions(std::string prefix = "z") : prefix_(std::move(prefix)) {}

  /// A symbol standing for `value`, or `value` itself when it is already atomic (a number,
  /// a symbol, a number times a symbol, a function of a symbol). Equal values share a symbol.
  /// A value that is a large tree is shared first (share()), so no definition is one.
  GiNaC::ex bind(const GiNaC::ex& value);
  /// A symbol standing for `value` as it is, its subexpressions not shared: for a definition of
  /// another Subexpressions taken over in its order (equal values still share a symbol).
  GiNaC::ex adopt(const GiNaC::ex& value) { return bind_as_is(value); }
  /// bind() applied to every entry.
  GiNaC::matrix bind(const GiNaC::matrix& value);

  /// `value` with every subexpression that occurs more than once in it bound to a symbol.
  /// Expressions built by compounding rotations are small graphs but exponentially large
  /// trees; after share() every consumer (printing, evaluation, emission) sees the graph.
  /// The new intermediates are numbered in an order that follows the content of `value`
  /// alone, not GiNaC's process-dependent order of operands, so printing is the same in every run.
  /// What one call rebuilt is remembered for the next: a node met again (the positions of
  /// points defined from one another's, each holding the ones before) is not entered again,
  /// and is its intermediate where an earlier call or bind() made one.
  GiNaC::ex share(const GiNaC::ex& value);

  /// Definitions in creation order (each refers only to earlier ones).
  const std::vector<Definition>& definitions() const { return definitions_; }
  std::size_t size() const { return definitions_.size(); }

  /// e with every intermediate written out in model symbols. Exponential for long chains;
  /// meant for small systems, printing and tests.
  GiNaC::ex expand(const GiNaC::ex& e) const;
  GiNaC::matrix expand(const GiNaC::matrix& m) const;

  /// Numeric value of e where `values` gives a number for every model symbol e and the
  /// definitions depend on.
  GiNaC::ex evaluate(const GiNaC::ex& e, const GiNaC::exmap& values) const;

  /// `values` extended with the numeric value of every intermediate, computed in order.
  GiNaC::exmap evaluate_all(const GiNaC::exmap& values) const;

 private:
  GiNaC::ex bind_as_is(const GiNaC::ex& value);

  struct ShareMemo;  // the nodes share() has rebuilt, by their content
  // owns a ShareMemo; a copy starts empty (the memo is a cache of this object's own calls)
  struct ShareMemoHandle {
    ShareMemoHandle();
    ~ShareMemoHandle();
    ShareMemoHandle(const ShareMemoHandle&);
    ShareMemoHandle& operator=(const ShareMemoHandle&);
    ShareMemoHandle(ShareMemoHandle&&) noexcept;
    ShareMemoHandle& operator=(ShareMemoHandle&&) noexcept;
    std::unique_ptr<ShareMemo> memo;
  };

  std::string prefix_;
  std::vector<Definition> definitions_;
  ExpressionMap<GiNaC::ex> by_value_;  // looked up, never iterated
  mutable GiNaC::exmap expanded_;  // symbol -> value written out, filled in order
  mutable std::size_t expanded_count_ = 0;
  ShareMemoHandle share_memo_;
};

}  // namespace eomgen
