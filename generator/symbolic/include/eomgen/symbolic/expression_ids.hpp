#pragma once
// Numbers for the values of expressions, so that a memo over expressions never compares two
// trees.
//
// GiNaC's own tools for this cost time that depends on the process, not on the expression:
// - its hash values are 32 bits seeded from the addresses of type_info objects, which change
//   from run to run, and they collide often (a sum's hash combines its terms' by exclusive or);
// - on equal hashes, ex_is_equal and ex_is_less compare whole trees, and a tree is
//   exponentially larger than the graph of shared nodes it is stored as (x = y*(1 + sin(y)),
//   y = ... twenty times over is 40 nodes and 2^20 paths).
// So a hash table or an ordered map keyed by `ex` can take seconds or hours for one lookup,
// depending on the run. Here each node is looked up by its address the first time it is seen
// and then by its kind and the numbers of its operands: one table lookup per node, whatever the
// hash values, and equal values (however they are stored) get one number.
//
// The numbers follow the order in which nodes are first seen, which follows GiNaC's order of
// operands, so they must never decide anything printed or emitted: use them for lookups only.
#include <ginac/ginac.h>

#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

namespace eomgen {

class ExpressionIds {
 public:
  using Id = std::uint32_t;

  /// The number of e's value: equal for equal values (numbers, symbols, constants, sums,
  /// products, powers, functions, lists and matrices of them; any other kind of node is equal
  /// only to itself). Costs a lookup per node of e not seen before, and one for e otherwise.
  Id operator()(const GiNaC::ex& e);

  /// Values numbered so far.
  std::size_t size() const { return key_start_.size(); }

 private:
  // Open addressing with linear probing over a power-of-two table, hashed by Fibonacci
  // multiplication: a lookup is a multiplication and (mostly) one cache line, where
  // std::unordered_map takes a division and a chase through its nodes.
  template <class Key>
  class FlatTable {
   public:
    /// Calls `match(id)` for each id stored under `key` until it returns true; returns that id.
    template <class Match>
    const Id* find(Key key, Match&& match) const {
      if (slots_.empty()) return nullptr;
      for (std::size_t i = slot(key);; i = (i + 1) & (slots_.size() - 1)) {
        const Entry& e = slots_[i];
        if (!e.used) return nullptr;
        if (e.key == key && match(e.id)) return &e.id;
      }
    }
    void insert(Key key, Id id);

   private:
    struct Entry {
      Key key{};
      Id id = 0;
      bool used = false;
    };
    std::size_t slot(Key key) const;
    std::vector<Entry> slots_;
    std::size_t count_ = 0;
  };

  Id intern(const GiNaC::ex& node, std::uint32_t kind, std::size_t first_operand, std::size_t operand_count);
  Id intern_leaf(const GiNaC::ex& node);
  Id new_id(std::uint64_t hash, const GiNaC::ex& node);
  const Id* known(const GiNaC::ex& e) const;

  // every node seen, by address; `kept_` holds a reference to each, so that no address is
  // freed and reused by another expression while this table remembers it (GiNaC may swap the
  // node an `ex` points to for an equal one when it compares them)
  FlatTable<const GiNaC::basic*> by_node_;
  std::vector<GiNaC::ex> kept_;
  // the content of every value: its key (a kind, then operand numbers or a leaf's hash) in
  // keys_[key_start_[id] .. key_start_[id + 1]), found by a 64-bit hash of the key
  FlatTable<std::uint64_t> by_content_;
  std::vector<std::uint32_t> keys_;
  std::vector<std::size_t> key_start_;
  std::vector<GiNaC::ex> leaves_;  // per id: the node, for leaves compared by GiNaC (cheap)
  // scratch of operator(), kept to spare allocations
  GiNaC::exvector operands_;
  std::vector<Id> operand_ids_;
  std::vector<std::uint32_t> key_;
};

}  // namespace eomgen
