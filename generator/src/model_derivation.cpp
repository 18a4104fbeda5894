#include "eomgen/model.hpp"

#include "eomgen/error.hpp"

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

EquationsOfMotion derive_equations(const Model& model) {
  EquationsOfMotion eom = derive_equations(model.system);
  // outputs of long chains (positions through compounded rotations) are bound to shared
  // intermediates so printing and evaluation stay linear; small ones stay as written
  const double large = 20000;
  std::map<GiNaC::ex, double, GiNaC::ex_is_less> memo;
  for (const Output& o : model.outputs)
    for (const GiNaC::ex& component : o.components)
      eom.outputs.push_back(tree_size(component, memo) > large ? eom.subexpressions.share(component) : component);
  return eom;
}

const GiNaC::ex& output_component(const Model& model, const EquationsOfMotion& equations, std::size_t k) {
  std::size_t count = 0;
  for (const Output& o : model.outputs) count += o.components.size();
  if (equations.outputs.size() != count || k >= count)
    throw Error("output component requested from equations derived without the model's outputs: "
                "use derive_equations(model), not derive_equations(model.system)");
  return equations.outputs[k];
}

}  // namespace eomgen
