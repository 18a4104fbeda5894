#include "variable_binding.hpp"

#include "eomgen/derivation/linearization.hpp"

namespace eomgen {

VariableNames bind_variables(const Model& model, const SymbolicLinearization* linearization,
                             const CppPrintOptions& print) {
  using ir::VariableKind;
  const Variables& vars = model.system.variables();
  VariableNames names;
  auto bind = [&](const GiNaC::ex& symbol, VariableKind kind, std::size_t index) {
    const ir::Variable variable{kind, index};
    names[symbol] = NamedVariable{variable, cpp_variable(variable, print)};
  };
  bind(vars.time(), VariableKind::time, 0);
  for (std::size_t k = 0; k < vars.coordinate_count(); ++k) {
    bind(vars.coordinates()[k].q, VariableKind::coordinate, k);
    bind(vars.coordinates()[k].qd, VariableKind::rate, k);
  }
  for (std::size_t k = 0; k < vars.inputs().size(); ++k) bind(vars.inputs()[k].symbol, VariableKind::input, k);
  for (std::size_t k = 0; k < vars.parameters().size(); ++k)
    bind(vars.parameters()[k].symbol, VariableKind::parameter, k);
  for (std::size_t k = 0; k < vars.derived_parameters().size(); ++k)
    bind(vars.derived_parameters()[k].symbol, VariableKind::derived_parameter, k);
  // the inverse dynamics and the regressor read accelerations, and the linearization's
  // derivatives are taken at given accelerations and multipliers
  for (std::size_t k = 0; k < vars.coordinate_count(); ++k) bind(vars.coordinates()[k].qdd, VariableKind::acceleration, k);
  if (linearization) {
    for (std::size_t r = 0; r < linearization->lambda.size(); ++r)
      bind(linearization->lambda[r], VariableKind::multiplier, r);
  }
  return names;
}

}  // namespace eomgen
