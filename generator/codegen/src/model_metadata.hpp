#pragma once
// The metadata of a generated Model: sizes, names, parameter defaults, the constraint and
// speed structure, the generator version and the model's hash.
#include <cstdint>
#include <string>

#include "eomgen/derivation/header_functions.hpp"
#include "eomgen/derivation/model_equations.hpp"

namespace eomgen {

/// The `static constexpr` members: nq, nu, nc, nh, np, ny, ni, the name, description,
/// generator version and `model_hash`, and the arrays of names, defaults, holonomic rows and
/// independent speeds.
std::string metadata_source(const Model& model, const HeaderFunctions& functions, std::uint64_t model_hash);

/// The Parameters struct: one field per parameter, defaulted to its value, and fields() in the
/// order of parameter_names; then, for a model with derived parameters, DerivedParameters.
std::string parameters_source(const Model& model);

/// The DerivedParameters struct: one field per derived parameter, with its definition in a
/// comment ("" for a model without derived parameters).
std::string derived_parameters_source(const Model& model);

/// The coordinate indices of the declared independent speeds, "1, 3" ("" when none are).
std::string independent_speed_list(const Model& model);

}  // namespace eomgen
