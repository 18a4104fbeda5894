#include "eomgen/symbolic/expression_size.hpp"
#include "eomgen/symbolic/operand.hpp"

#include <vector>

namespace eomgen {
namespace {

using Expanded = ExpressionSizes::Expanded;

// each term of the product takes one term of every factor
Expanded product_size(const std::vector<Expanded>& factors) {
  Expanded out{1, 0};
  double nodes_per_term = 1;
  for (const Expanded& f : factors) {
    out.terms *= f.terms;
    nodes_per_term += f.nodes / f.terms;
  }
  out.nodes = out.terms * nodes_per_term;
  return out;
}

}  // namespace

double tree_size(const GiNaC::ex& e) { return ExpressionSizes().tree(e); }

void ExpressionSizes::define(const GiNaC::ex& symbol, const GiNaC::ex& value) {
  tree_.emplace(symbol, tree(value));
  expanded_.emplace(symbol, expanded(value));
}

double ExpressionSizes::tree(const GiNaC::ex& e) {
  if (const double* known = tree_.find(e)) return *known;
  if (e.nops() == 0) return 1;
  double size = 1;
  for (std::size_t i = 0; i < e.nops(); ++i) size += tree(operand(e, i));
  tree_.emplace(e, size);
  return size;
}

ExpressionSizes::Expanded ExpressionSizes::expanded(const GiNaC::ex& e) {
  if (const Expanded* known = expanded_.find(e)) return *known;
  if (e.nops() == 0) return {};
  std::vector<Expanded> operands;
  for (std::size_t k = 0; k < e.nops(); ++k) operands.push_back(expanded(operand(e, k)));
  Expanded out{1, 1};
  if (GiNaC::is_a<GiNaC::add>(e)) {
    out = Expanded{0, 1};
    for (const Expanded& o : operands) out.terms += o.terms, out.nodes += o.nodes;
  } else if (GiNaC::is_a<GiNaC::mul>(e)) {
    out = product_size(operands);
  } else if (GiNaC::is_a<GiNaC::power>(e) && GiNaC::is_a<GiNaC::numeric>(e.op(1)) &&
             GiNaC::ex_to<GiNaC::numeric>(e.op(1)).is_pos_integer() && GiNaC::ex_to<GiNaC::numeric>(e.op(1)) <= 16) {
    out = product_size(std::vector<Expanded>(GiNaC::ex_to<GiNaC::numeric>(e.op(1)).to_int(), operands[0]));
  } else {
    for (const Expanded& o : operands) out.nodes += o.nodes;
  }
  expanded_.emplace(e, out);
  return out;
}

}  // namespace eomgen
