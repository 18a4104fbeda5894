#pragma once
// A multiplied-out sum grouped by its state-dependent monomials: k1 cos(q)^2 + k2 cos(q)^2 +
// k3 sin(q)^2 becomes (k1 + k2) cos(q)^2 + k3 sin(q)^2. Each coefficient depends on parameters
// and numbers only, so code emission computes it once per parameter set and every call does one
// product per monomial: the form a hand derivation collects into.
#include <ginac/ginac.h>

#include "eomgen/mechanics/variables.hpp"

namespace eomgen {

/// `sum` (multiplied out) with the terms that share their state-dependent factors combined. A
/// symbol is state-dependent unless it is one of `variables`' parameters.
GiNaC::ex collect_parameter_coefficients(const GiNaC::ex& sum, const Variables& variables);

}  // namespace eomgen
