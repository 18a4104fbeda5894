#pragma once
// The identifiable base parameters of a regressor: the columns of Y that are independent at
// generic states, and every other column as their combination, found once from Y in numbers
// at random states (its rank there is its rank as a function).
#include "eomgen/derivation/header_functions.hpp"

namespace eomgen {

/// The base parameters of `functions.regressor`, whose combinations must not depend on the
/// model's parameters.
/// \throws DerivationError where they do (a geometry of parameters: the double pendulum's
///         lengths), naming those parameters, or where the model has no regressor.
BaseParameters find_base_parameters(const Model& model, const ModelEquations& eom, const HeaderFunctions& functions);

}  // namespace eomgen
