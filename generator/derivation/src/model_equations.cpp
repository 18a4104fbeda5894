#include "eomgen/derivation/model_equations.hpp"

#include <map>

namespace eomgen {
namespace {

// Size of e written out as a tree, visiting each shared node once (the number can be far
// larger than the memory the expression takes).
double tree_size(const GiNaC::ex& e, std::map<GiNaC::ex, double, GiNaC::ex_is_less>& memo) {
  if (e.nops() == 0) return 1;
  auto it = memo.find(e);
  if (it != memo.end()) return it->second;
  double size = 1;
  for (std::size_t i = 0; i < e.nops(); ++i) size += tree_size(e.op(i), memo);
  memo.emplace(e, size);
  return size;
}

}  // namespace

ModelEquations derive_equations(const Model& model) {
  EquationsOfMotion eom = derive_equations(model.system);
  // outputs of long chains (positions through compounded rotations) are bound to shared
  // intermediates so printing and evaluation stay linear; small ones stay as written
  const double large = 20000;
  std::map<GiNaC::ex, double, GiNaC::ex_is_less> memo;
  GiNaC::exvector outputs;
  for (const Output& o : model.outputs)
    for (const GiNaC::ex& component : o.components)
      outputs.push_back(tree_size(component, memo) > large ? eom.subexpressions.share(component) : component);
  return ModelEquations(std::move(eom), std::move(outputs));
}

}  // namespace eomgen
