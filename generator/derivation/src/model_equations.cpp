#include "eomgen/derivation/model_equations.hpp"

#include "eomgen/derivation/dimension_check.hpp"
#include "eomgen/symbolic/expression_size.hpp"

namespace eomgen {

ModelEquations derive_equations(const Model& model) {
  EquationsOfMotion eom = derive_equations(model.system);
  check_dimensions(eom, model.system.variables(), model.dimensions);
  // outputs of long chains (positions through compounded rotations) are bound to shared
  // intermediates so printing and evaluation stay linear; small ones stay as written
  const double large = 20000;
  GiNaC::exvector outputs;
  for (const Output& o : model.outputs)
    for (const GiNaC::ex& component : o.components)
      outputs.push_back(tree_size(component) > large ? eom.subexpressions.share(component) : component);
  return ModelEquations(std::move(eom), std::move(outputs));
}

}  // namespace eomgen
