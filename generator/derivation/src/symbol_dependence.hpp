#pragma once
// Which kinds of model symbols an expression depends on, through the intermediates it refers
// to: whether M depends on time, whether an output is a position (of q and t alone) or a
// velocity. Each intermediate is looked at once, so the cost follows the shared graph.
#include <ginac/ginac.h>

#include <cstdint>
#include <map>
#include <vector>

#include "eomgen/mechanics/variables.hpp"
#include "eomgen/symbolic/subexpressions.hpp"

namespace eomgen {

class SymbolDependence {
 public:
  SymbolDependence(std::vector<const Subexpressions*> sources, const Variables& variables);

  /// Whether e depends on a symbol of the given kind.
  bool depends_on(const GiNaC::ex& e, SymbolKind kind) const;

 private:
  std::uint32_t kinds_of(const GiNaC::ex& e) const;

  const Variables& variables_;
  std::map<GiNaC::ex, const GiNaC::ex*, GiNaC::ex_is_less> definitions_;
  mutable std::map<GiNaC::ex, std::uint32_t, GiNaC::ex_is_less> memo_;  // intermediate -> kinds
};

}  // namespace eomgen
