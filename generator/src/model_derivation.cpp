#include "eomgen/model.hpp"

#include "eomgen/error.hpp"

namespace eomgen {

EquationsOfMotion derive_equations(const Model& model) {
  EquationsOfMotion eom = derive_equations(model.system);
  for (const Output& o : model.outputs)
    for (const GiNaC::ex& component : o.components) eom.outputs.push_back(eom.subexpressions.share(component));
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
