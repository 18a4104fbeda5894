#include "eomgen/derivation/model_equations.hpp"

#include <vector>

#include "eomgen/derivation/dimension_check.hpp"
#include "eomgen/symbolic/expression_size.hpp"

namespace eomgen {

ModelEquations derive_equations(const Model& model) {
  EquationsOfMotion eom = derive_equations(model.system);
  check_dimensions(eom, model.system.variables(), model.dimensions);
  // outputs of long chains (positions through compounded rotations) are bound to shared
  // intermediates; small ones stay as written. The large ones are shared in one pass, since the
  // components of a position or a velocity have most of their graph in common.
  const double large = 20000;
  GiNaC::exvector outputs;
  std::vector<std::size_t> large_components;
  GiNaC::lst shared;
  for (const Output& o : model.outputs)
    for (const GiNaC::ex& component : o.components) {
      if (tree_size(component) > large) {
        large_components.push_back(outputs.size());
        shared.append(component);
      }
      outputs.push_back(component);
    }
  if (!large_components.empty()) {
    const GiNaC::ex bound = eom.subexpressions.share(shared);
    for (std::size_t k = 0; k < large_components.size(); ++k) outputs[large_components[k]] = bound.op(k);
  }
  return ModelEquations(std::move(eom), std::move(outputs));
}

}  // namespace eomgen
