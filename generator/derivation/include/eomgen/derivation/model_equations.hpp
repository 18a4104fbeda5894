#pragma once
// A model's equations: the equations of motion of its system together with its outputs, bound
// to the same shared intermediates. Everything that reads outputs (evaluation, printing,
// emission) takes ModelEquations, and only derive_equations(const Model&) makes one, so the
// outputs cannot be left out by deriving from model.system by mistake.
#include <cstddef>

#include "eomgen/derivation/equations_of_motion.hpp"
#include "eomgen/mechanics/model.hpp"

namespace eomgen {

class ModelEquations : public EquationsOfMotion {
 public:
  /// The output components, counting the components of all outputs in the model's order.
  const GiNaC::exvector& outputs() const { return outputs_; }
  /// Output component k. \throws std::out_of_range for k >= outputs().size()
  const GiNaC::ex& output_component(std::size_t k) const { return outputs_.at(k); }

 private:
  friend ModelEquations derive_equations(const Model& model);
  ModelEquations(EquationsOfMotion equations, GiNaC::exvector outputs)
      : EquationsOfMotion(std::move(equations)), outputs_(std::move(outputs)) {}
  GiNaC::exvector outputs_;
};

/// Derives the model's equations, with its outputs bound to shared intermediates too.
ModelEquations derive_equations(const Model& model);

}  // namespace eomgen
