// Text of expressions in an order that does not depend on GiNaC's hashes (ordered_text.hpp).
#include "eomgen/symbolic/ordered_text.hpp"

#include <algorithm>
#include <sstream>
#include <vector>

namespace eomgen {

using GiNaC::ex;

std::string ordered_text(const ex& e) {
  const bool sum = GiNaC::is_a<GiNaC::add>(e), product = GiNaC::is_a<GiNaC::mul>(e);
  if (!sum && !product) {
    if (GiNaC::is_a<GiNaC::power>(e)) {
      const bool simple = GiNaC::is_a<GiNaC::symbol>(e.op(0)) || GiNaC::is_a<GiNaC::function>(e.op(0));
      const std::string base = ordered_text(e.op(0)), exponent = ordered_text(e.op(1));
      const bool plain_exponent = GiNaC::is_a<GiNaC::symbol>(e.op(1)) ||
                                  (GiNaC::is_a<GiNaC::numeric>(e.op(1)) && GiNaC::ex_to<GiNaC::numeric>(e.op(1)).is_pos_integer());
      return (simple ? base : "(" + base + ")") + "^" + (plain_exponent ? exponent : "(" + exponent + ")");
    }
    if (GiNaC::is_a<GiNaC::function>(e)) {
      std::string args;
      for (const ex& a : e) args += (args.empty() ? "" : ",") + ordered_text(a);
      return GiNaC::ex_to<GiNaC::function>(e).get_name() + "(" + args + ")";
    }
    std::ostringstream out;
    out << e;
    return out.str();
  }
  std::vector<std::string> parts;
  std::string coefficient;  // of a product, written first: -F*l, 2*F*l
  for (const ex& part : e) {
    if (product && GiNaC::is_a<GiNaC::numeric>(part)) {
      const GiNaC::numeric& c = GiNaC::ex_to<GiNaC::numeric>(part);
      coefficient = c == -1 ? "-" : ordered_text(part) + "*";
      continue;
    }
    const std::string text = ordered_text(part);
    parts.push_back(product && GiNaC::is_a<GiNaC::add>(part) ? "(" + text + ")" : text);
  }
  std::sort(parts.begin(), parts.end());
  std::string text = coefficient;
  for (const std::string& part : parts) {
    if (text.empty() || text == coefficient) text += part;
    else if (sum && part[0] == '-') text += part;
    else text += (sum ? "+" : "*") + part;
  }
  return text;
}

}  // namespace eomgen
