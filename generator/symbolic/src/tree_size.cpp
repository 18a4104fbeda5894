#include "eomgen/symbolic/tree_size.hpp"

#include "eomgen/symbolic/expression_map.hpp"

namespace eomgen {
namespace {

double tree_size(const GiNaC::ex& e, ExpressionMap<double>& memo) {
  if (e.nops() == 0) return 1;
  if (const double* size = memo.find(e)) return *size;
  double size = 1;
  for (std::size_t i = 0; i < e.nops(); ++i) size += tree_size(e.op(i), memo);
  memo.emplace(e, size);
  return size;
}

}  // namespace

double tree_size(const GiNaC::ex& e) {
  ExpressionMap<double> memo;
  return tree_size(e, memo);
}

}  // namespace eomgen
