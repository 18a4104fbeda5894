#pragma once
// Evaluates expressions in double precision from numbers given for their symbols. Walking the
// expression in doubles (rather than GiNaC's subs and evalf) turns a pole into inf instead of
// a GiNaC exception, whose unwinding from inside subs leaks the half-built expression.
#include <ginac/ginac.h>

#include <map>
#include <string>
#include <unordered_map>
#include <utility>

namespace eomgen {

class DoubleEvaluator {
 public:
  void set(const GiNaC::ex& symbol, double value) { values_[symbol] = value; }

  /// e as a real number, possibly inf or NaN. \throws Error for a symbol without a value, a
  /// complex number or a function with no double form; `what` names e in messages. Each node
  /// of e is evaluated once, however often e refers to it.
  double value(const GiNaC::ex& e, const std::string& what) const;

  /// e as a finite real number. \throws Error otherwise.
  double finite(const GiNaC::ex& e, const std::string& what) const;

 private:
  // the values of one call's nodes by address, each with the node, so that no address is
  // freed (op() of a sum or product may build a node for the call) and reused meanwhile
  using Memo = std::unordered_map<const GiNaC::basic*, std::pair<GiNaC::ex, double>>;
  double value(const GiNaC::ex& e, const std::string& what, Memo& memo) const;
  double function(const GiNaC::ex& e, const std::string& what, Memo& memo) const;

  std::map<GiNaC::ex, double, GiNaC::ex_is_less> values_;  // looked up, never iterated
};

}  // namespace eomgen
