#include "symbol_dependence.hpp"

namespace eomgen {

namespace {
std::uint32_t bit(SymbolKind kind) { return std::uint32_t(1) << static_cast<unsigned>(kind); }
}  // namespace

SymbolDependence::SymbolDependence(std::vector<const Subexpressions*> sources, const Variables& variables)
    : variables_(variables) {
  for (const Subexpressions* z : sources)
    for (const Subexpressions::Definition& d : z->definitions()) definitions_.emplace(d.symbol, &d.value);
}

bool SymbolDependence::depends_on(const GiNaC::ex& e, SymbolKind kind) const { return (kinds_of(e) & bit(kind)) != 0; }

std::uint32_t SymbolDependence::kinds_of(const GiNaC::ex& e) const {
  std::uint32_t kinds = 0;
  for (const GiNaC::ex& s : symbols_of(e)) {
    if (const auto kind = variables_.kind_of(s)) {
      kinds |= bit(*kind);
      continue;
    }
    const auto definition = definitions_.find(s);
    if (definition == definitions_.end()) continue;
    if (const auto known = memo_.find(s); known != memo_.end()) {
      kinds |= known->second;
      continue;
    }
    // definitions refer only to earlier ones: resolve the chain below s first, deepest last on
    // the stack, so the recursion stays shallow however long the chain
    std::vector<GiNaC::ex> stack{s};
    while (!stack.empty()) {
      const GiNaC::ex top = stack.back();
      bool ready = true;
      for (const GiNaC::ex& t : symbols_of(*definitions_.at(top)))
        if (definitions_.count(t) && !memo_.count(t)) {
          stack.push_back(t);
          ready = false;
        }
      if (!ready) continue;
      stack.pop_back();
      if (memo_.count(top)) continue;
      std::uint32_t own = 0;
      for (const GiNaC::ex& t : symbols_of(*definitions_.at(top))) {
        if (const auto kind = variables_.kind_of(t)) own |= bit(*kind);
        else if (const auto m = memo_.find(t); m != memo_.end()) own |= m->second;
      }
      memo_.emplace(top, own);
    }
    kinds |= memo_.at(s);
  }
  return kinds;
}

}  // namespace eomgen
