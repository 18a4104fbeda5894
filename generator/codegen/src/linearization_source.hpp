#pragma once
// What the generated header says about its linearization. The model-specific derivative
// terms (linearization_terms) are lowered from the expression graph like every other
// function; the solves that turn them into A and B are the runtime's, generic over models
// (eomrt/linearization.hpp), so no numerics are emitted as text.
#include <string>

namespace eomgen {

/// Text for the body of the generated Model after linearization_terms: a comment naming the
/// runtime algorithms that use it (unconstrained: second_order_linearization and linearization;
/// constrained: linearization through the KKT system).
std::string linearization_source(bool constrained);

}  // namespace eomgen
