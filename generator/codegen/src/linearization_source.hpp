#pragma once
// The C++ text of the generated linearization(): the small dense solves that turn the
// emitted derivative terms (linearization_terms) into A and B. The terms are model-specific
// and lowered from the expression graph; this part is the same for every model of a kind.
#include <string>

namespace eomgen {

/// Member functions of the generated Model (unconstrained: second_order_linearization and
/// linearization; constrained: linearization through the KKT system).
std::string linearization_source(bool constrained);

}  // namespace eomgen
