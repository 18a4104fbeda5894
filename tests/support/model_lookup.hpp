#pragma once
// What a test looks up by name in a model it parsed or built: a symbol, an output.
#include <gtest/gtest.h>

#include <string>

#include "eomgen/mechanics/model.hpp"

namespace eomgen::testing {

/// The symbol called `name` in s (a coordinate, a rate "x_dot", a parameter, an input or "t");
/// a test failure and 0 when s has none.
inline GiNaC::ex symbol_named(const MechanicalSystem& s, const std::string& name) {
  const auto found = s.variables().find(name);
  if (!found) {
    ADD_FAILURE() << "the model has no symbol '" << name << "'";
    return 0;
  }
  return *found;
}

/// The output called `name`, or nullptr.
inline const Output* find_output(const Model& m, const std::string& name) {
  for (const Output& o : m.outputs)
    if (o.name == name) return &o;
  return nullptr;
}

}  // namespace eomgen::testing
